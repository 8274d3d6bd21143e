// simlab list: the assignments this build knows.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "commands.h"
#include "simlab/engine/manifest.h"
#include "simlab/rubric.h"

namespace simlab::cli {

void addList(CLI::App& app) {
    CLI::App* list = app.add_subcommand("list", "List the assignments, their files and points.");
    list->callback([] {
        const engine::Manifest manifest = engine::loadManifest();
        for (const engine::Assignment& a : manifest.assignments) {
            const Rubric rubric = loadRubric(a.rubric);
            int visible = 0;
            for (const RubricTest& t : rubric.tests) visible += t.visible();
            std::printf("%-12s %-28s %-24s %2zu tests (%d visible), %g points", a.id.c_str(), a.title.c_str(),
                        a.source.c_str(), rubric.tests.size(), visible, rubric.totalPoints());
            if (!rubric.manual.empty()) std::printf(" + %g graded by hand", rubric.manualPoints());
            std::printf("\n");
        }
    });
}

}  // namespace simlab::cli
