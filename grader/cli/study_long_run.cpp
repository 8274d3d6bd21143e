// `simlab study long-run LAB`: the long-run view of the book or the baby boot. The lab's study program
// (simlab/long_run.h) runs each setting, writes the CSV and the figure, and prints the table; this command checks
// the lab, builds the studies where they are not built yet, and hands over to it.
#include <CLI/CLI.hpp>
#include <memory>

#include "commands.h"
#include "simlab/cli_checks.h"
#include "simlab/common/errors.h"
#include "simlab/build/manifest.h"
#include "simlab/common/text.h"

namespace simlab::cli {

namespace {

struct LongRunOptions {
    std::string lab;
    double finalTime = 0;  ///< s; 0: the study program's default (1000 s, or a short run with --quick)
    bool quick = false;
    std::string output = "long-run";
    bool plots = true;
};

[[noreturn]] void runLongRun(const LongRunOptions& o, const StudiesBuilder& ensureBuilt) {
    if (o.lab != "book" && o.lab != "biosim") {
        throw engine::UsageError("the long-run view is the book's or the baby boot's: book or biosim, not '" +
                                 engine::printable(o.lab) + "'");
    }
    const engine::Manifest manifest = engine::loadManifest();
    const engine::Assignment& a = manifest.find(o.lab);
    if (a.studyProgramPath.empty()) {
        throw engine::UsageError("no long-run view of " + o.lab + ": its reference solution is not in this tree");
    }
    ensureBuilt(manifest, a);
    std::vector<std::string> args = {a.studyProgramPath, "long-run", "--output", o.output};
    if (o.finalTime > 0) args.insert(args.end(), {"--final-time", std::to_string(o.finalTime)});
    if (o.quick) args.push_back("--quick");
    if (!o.plots) args.push_back("--no-plots");
    handOver(a.studyProgramPath, args);
}

}  // namespace

void addStudyLongRun(CLI::App& study, const StudiesBuilder& ensureBuilt) {
    auto options = std::make_shared<LongRunOptions>();
    CLI::App* longRun = study.add_subcommand(
        "long-run",
        "A long-run view of the book (its spin about the intermediate axis) or the baby boot: RungeKuttaMerson at "
        "accuracies 1e-6 and 1e-9 and Verlet at a fixed step of 1 ms, each run to the final time (1000 s) and "
        "sampled 20 times a decade from 0.1 s. It prints, for each setting, the energy's drift |E(t) - E(0)| / "
        "scale at 1, 10, 100 and 1000 s and the time its trajectory keeps less than 1 digit - against the "
        "long-double reference for the book, against the same method run tighter (a tenth of the accuracy, half "
        "the step) for the chaotic boot - and writes LAB-long-run.csv and LAB-long-run.svg (both against time on "
        "log-log axes). The full view takes a minute or two; --quick, seconds.");
    longRun->add_option("lab", options->lab, "book or biosim (the baby boot)")->required();
    longRun->add_option("--final-time", options->finalTime, "s, how long each setting runs (default 1000)")
        ->check(simlab::between(1.0, 1e5));
    longRun->add_flag("--quick", options->quick, "a final time of 20 s (seconds of work), unless --final-time is given");
    longRun->add_option("--output,-o", options->output, "folder for the CSV and the figure")->capture_default_str();
    longRun->add_flag("!--no-plots", options->plots, "the CSV and the table only");
    longRun->callback([options, ensureBuilt] { runLongRun(*options, ensureBuilt); });
}

}  // namespace simlab::cli
