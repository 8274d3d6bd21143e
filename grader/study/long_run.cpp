// `simlab study long-run`: the book's or the baby boot's long-run view, which the lab's study program
// (simlab/long_run.h) runs whole: it runs each setting, writes the CSV and the figure, and prints the table.
#include "internal.h"
#include "simlab/common/errors.h"
#include "simlab/build/manifest.h"
#include "simlab/common/text.h"

namespace simlab::study {

std::vector<std::string> longRunCommand(const LongRunOptions& o, int cores) {
    if (o.lab != "book" && o.lab != "biosim") {
        throw engine::UsageError("the long-run view is the book's or the baby boot's: book or biosim, not '" +
                                 engine::printable(o.lab) + "'");
    }
    const engine::Manifest manifest = engine::loadManifest();
    const engine::Assignment& a = manifest.find(o.lab);
    if (a.studyProgramPath.empty()) {
        throw engine::UsageError("no long-run view of " + o.lab + ": its reference solution is not in this tree");
    }
    ensureStudiesBuilt(manifest, {&a}, false, cores);
    std::vector<std::string> args = {a.studyProgramPath, "long-run", "--output", o.output};
    if (o.finalTime > 0) args.insert(args.end(), {"--final-time", std::to_string(o.finalTime)});
    if (o.quick) args.push_back("--quick");
    if (!o.plots) args.push_back("--no-plots");
    return args;
}

}  // namespace simlab::study
