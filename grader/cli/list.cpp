// simlab list: the assignments this build knows (or, with --secrets, what no student may have).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "commands.h"
#include "simlab/build/manifest.h"
#include "simlab/rubric/rubric.h"

namespace simlab::cli {

void addList(CLI::App& app) {
    CLI::App* list = app.add_subcommand("list", "List the assignments, their files and points.");
    auto secrets = std::make_shared<bool>(false);
    list->add_flag("--secrets", *secrets,
                   "list instead, one per line, what no student may have - every assignment's hidden tests, "
                   "solutions (not a worked example's), judges and what the build made of them, the corpus, the "
                   "object cache, the sources' history - where it exists: what the student bundle leaves out. (No "
                   "test's code may read any of simlab's places but what it is lent; simlab lock closes them.)");
    list->callback([secrets] {
        const engine::Manifest manifest = engine::loadManifest();
        if (*secrets) {
            for (const std::string& path : engine::courseSecrets(manifest)) {
                std::error_code error;
                if (std::filesystem::exists(path, error)) std::printf("%s\n", path.c_str());
            }
            return;
        }
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
