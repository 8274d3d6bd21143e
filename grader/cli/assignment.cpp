// simlab assignment: labs of one's own - start one from the template, build it, verify it before students see it.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.h"
#include "simlab/build/lab.h"
#include "simlab/build/manifest.h"
#include "simlab/common/errors.h"
#include "simlab/common/text.h"
#include "simlab/course/authoring.h"

namespace simlab::cli {

namespace {

namespace fs = std::filesystem;

struct AssignmentOptions {
    std::string name;
    std::string dir;
    engine::VerifyOptions verify;
};

// A folder as commands take a lab: a path, never read as one of the course's ids.
std::string asFolder(const std::string& dir) { return engine::isLabFolder(dir) ? dir : "./" + dir; }

}  // namespace

void addAssignment(CLI::App& app) {
    CLI::App* assignment =
        app.add_subcommand("assignment",
                           "Labs of one's own, kept in a folder anywhere: start one, build it, verify it "
                           "(docs/authors.md). Every command that takes an assignment takes such a folder too.");
    assignment->require_subcommand(1);

    auto made = std::make_shared<AssignmentOptions>();
    CLI::App* make = assignment->add_subcommand(
        "new",
        "Write a new lab NAME in the folder DIR from the template: a block on a spring that builds, a "
        "reference that earns every point, a starter with SIMLAB_TODOs, one test of each kind, a rubric, a "
        "handout and a corpus; its comments marked CHANGE say what to make your own.");
    make->add_option("name", made->name, "the lab's id and C++ namespace (lowercase letters, digits or '_')")
        ->required();
    make->add_option("dir", made->dir, "a new folder (default: ./NAME)");
    make->callback([made] {
        const engine::Manifest manifest = engine::loadManifest();
        const std::string dir = made->dir.empty() ? made->name : made->dir;
        const int files = engine::writeLabSkeleton(manifest, made->name, dir);
        const std::string shown = engine::printable(asFolder(dir));
        std::cout << "Wrote the lab " << made->name << " in " << engine::printable(dir) << ": " << files << " files.\n"
                  << "Next (docs/authors.md walks through each):\n"
                  << "  " << selfPath() << " assignment verify " << shown << "    # builds it, grades the reference, "
                  << "the starter and the corpus\n"
                  << "  grep -rn CHANGE " << engine::printable(dir) << "                  # what to make your own\n";
    });

    auto built = std::make_shared<AssignmentOptions>();
    CLI::App* build = assignment->add_subcommand(
        "build",
        "Build the lab in DIR against this simlab now (every command builds it on first use; a "
        "package's setup builds it here).");
    build->add_option("dir", built->dir, "the lab's folder")->required();
    build->callback([built] {
        const engine::Manifest manifest = engine::loadManifest();
        const engine::Assignment& lab = manifest.find(asFolder(built->dir));
        std::cout << "Built " << lab.id << " (" << engine::printable(lab.title) << ") in "
                  << engine::labBuildFolder(manifest, lab.dir) << "\n";
    });

    auto verified = std::make_shared<AssignmentOptions>();
    CLI::App* verify = assignment->add_subcommand(
        "verify",
        "Check the lab in DIR before students see it, one line per check: it builds; the reference "
        "earns every point, hidden tests included; the starter earns at most --starter-share; each corpus "
        "case its score; each extreme case names its outcome; a graded trade has measured fronts; the "
        "students' copy holds no hidden test; the CPU limit leaves the reference a margin of 2. Exit 0 "
        "only when every check holds.");
    verify->add_option("dir", verified->dir, "the lab's folder")->required();
    verify
        ->add_option("--starter-share", verified->verify.starterShare,
                     "the most the starter may earn, as a share of the points")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    verify->add_option("-j,--jobs", verified->verify.judges, "judges a grading runs at once (default: the cores)");
    verify->callback([verified] {
        const engine::Manifest manifest = engine::loadManifest();
        if (verified->verify.judges < 1) verified->verify.judges = cores();
        int counts[4] = {0, 0, 0, 0};
        const int failures =
            engine::verifyLab(manifest, asFolder(verified->dir), verified->verify, [&](const engine::VerifyLine& line) {
                const std::string statuses[4] = {"ok", "FAIL", "warn", "skip"};
                for (int i = 0; i < 4; ++i) counts[i] += line.status == statuses[i];
                std::printf("%-5s %s\n", line.status.c_str(), engine::printable(line.text).c_str());
                std::fflush(stdout);
            });
        std::printf("verify: %d hold, %d fail, %d warnings, %d skipped\n", counts[0], counts[1], counts[2], counts[3]);
        std::fflush(stdout);
        if (failures > 0) std::exit(1);  // every line said already why
    });
}

}  // namespace simlab::cli
