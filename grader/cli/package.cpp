// simlab package: the student bundle and the Gradescope autograder; simlab autograde: what run_autograder runs.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.h"
#include "simlab/engine/batch.h"
#include "simlab/engine/errors.h"
#include "simlab/engine/files.h"
#include "simlab/engine/manifest.h"
#include "simlab/engine/package.h"
#include "simlab/engine/report.h"
#include "simlab/engine/text.h"

namespace fs = std::filesystem;

namespace simlab::cli {

namespace {

struct PackageOptions {
    std::string assignment;
    std::string output;
};

void printSummary(const engine::PackageSummary& s, const std::string& where) {
    std::cout << "Wrote " << where << ": " << s.files << " files.\n";
    for (const std::string& line : s.left) std::cout << "  left out: " << line << "\n";
    for (const std::string& line : s.made) std::cout << "  made: " << line << "\n";
}

struct AutogradeOptions {
    std::string assignment;
    std::string submission;
    std::string results;
};

// Gradescope needs a results.json whatever happens: an error becomes one, with the reason in its output.
void runAutograde(const AutogradeOptions& o) {
    using namespace simlab::engine;
    fs::create_directories(fs::absolute(o.results).parent_path());
    try {
        const Manifest manifest = loadManifest();
        const Assignment& assignment = manifest.find(o.assignment);
        if (!fs::is_directory(o.submission)) throw UsageError("no submission folder " + o.submission);
        const Rubric rubric = loadRubric(assignment.rubric);
        GradeOptions options;
        options.includeHidden = true;
        const GradeReport report =
            gradeFolder(Builder(manifest), assignment, rubric, o.submission, /*recursive=*/true, /*followFolder=*/true,
                        options);
        writeFileAtomically(o.results,
                            toGradescope(report).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
        std::cout << renderText(report);
    } catch (const std::exception& e) {
        const nlohmann::json failed = {
            {"score", 0},
            {"output", std::string("The autograder could not grade this submission: ") + printable(e.what())},
            {"tests", nlohmann::json::array()}};
        writeFileAtomically(o.results, failed.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
        throw;
    }
}

}  // namespace

void addPackage(CLI::App& app) {
    CLI::App* package = app.add_subcommand("package", "Make what you hand out: the student bundle, or Gradescope's "
                                                      "autograder archive.");
    package->require_subcommand(1);

    auto student = std::make_shared<PackageOptions>();
    CLI::App* s = package->add_subcommand(
        "student", "Write the student bundle: everything but the solutions, the hidden tests and the corpus. It "
                   "builds with scripts/setup and self-checks with simlab check.");
    s->add_option("-o,--output", student->output, "a new folder for the bundle")->required();
    s->callback([student] {
        const engine::Manifest manifest = engine::loadManifest();
        printSummary(engine::writeStudentBundle(manifest, student->output), student->output);
    });

    auto gradescope = std::make_shared<PackageOptions>();
    CLI::App* g = package->add_subcommand(
        "gradescope", "Write a Gradescope autograder archive for one assignment: setup.sh builds simlab on "
                      "Gradescope's image (choose Ubuntu 24.04), run_autograder grades each submission on every "
                      "test, hidden tests marked by their rubric visibility.");
    g->add_option("assignment", gradescope->assignment, "which assignment")->required();
    g->add_option("-o,--output", gradescope->output, "the zip file to write")->required();
    g->callback([gradescope] {
        const engine::Manifest manifest = engine::loadManifest();
        const engine::Assignment& assignment = manifest.find(gradescope->assignment);
        printSummary(engine::writeGradescopeZip(manifest, assignment, gradescope->output), gradescope->output);
    });
}

void addAutograde(CLI::App& app) {
    auto options = std::make_shared<AutogradeOptions>();
    CLI::App* a = app.add_subcommand(
        "autograde", "Grade one submission folder on every test and write a Gradescope results.json (what the "
                     "archive's run_autograder runs). The file is searched for in subfolders too; a lone C++ file "
                     "of another name is graded and noted.");
    a->add_option("assignment", options->assignment, "which assignment")->required();
    a->add_option("--submission", options->submission, "the submission folder")->required();
    a->add_option("--results", options->results, "where to write results.json")->required();
    a->callback([options] { runAutograde(*options); });
}

}  // namespace simlab::cli
