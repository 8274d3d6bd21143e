// simlab build: the lab program built from any student file, the same way the grader builds it.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.h"
#include "simlab/build/build.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/build/manifest.h"
#include "simlab/common/text.h"
#include "simlab/rubric/rubric.h"

namespace simlab::cli {

namespace {

struct BuildOptions {
    std::string assignment;
    std::string source;
    std::string output;
};

void runBuild(const BuildOptions& o) {
    using namespace simlab::engine;
    using namespace simlab::isolation;
    const Manifest manifest = loadManifest();
    const Assignment& assignment = manifest.find(o.assignment);
    const std::string source = o.source.empty() ? assignment.starter : o.source;
    requireCppSource(source);
    const Rubric rubric = loadRubric(assignment.rubric);
    const engine::SubmissionFiles files = readSubmission(source, rubric, rubric.limits);
    const std::string output = o.output.empty() ? assignment.program : o.output;
    // Never onto a folder (from the folder above a lab, ./<program> may be the lab's own), and said before the build.
    std::error_code error;
    if (std::filesystem::is_directory(output, error)) {
        throw UsageError("'" + printable(output) + "' is a folder, not where a program can be written: give -o PATH " +
                         "(say -o " + printable(assignment.program) + "-program)");
    }
    const std::filesystem::path parent = std::filesystem::absolute(output).parent_path();
    if (!std::filesystem::is_directory(parent)) {
        throw UsageError("cannot write '" + output + "': no directory " + parent.string());
    }
    if (const std::string closed = sandboxCannotReach(manifest, assignment); !closed.empty()) throw UsageError(closed);
    const BuildResult result = Builder(manifest).buildProgram(assignment, files.name, files.text, output);
    if (result.interrupted) throw UsageError("interrupted");
    if (!result.ok) {
        std::cerr << printable(firstLines(result.log, 30), true);
        throw UsageError(printable(source) + (result.stage == "link" ? " did not link" : " did not compile"));
    }
    std::cerr << printable(result.warnings, true);
    // A path with a slash runs as it is; a bare name needs ./ before it.
    const std::string command = output.find('/') == std::string::npos ? "./" + output : output;
    std::cout << "Built " << output << " from " << source << "; run " << command << " --help\n";
}

}  // namespace

void addBuild(CLI::App& app) {
    auto options = std::make_shared<BuildOptions>();
    CLI::App* build = app.add_subcommand("build", "Build an assignment's lab program from a student file.");
    build->add_option("assignment", options->assignment, "which assignment")->required();
    build->add_option("source", options->source, "the student file (default: the starter in this tree)");
    build->add_option("-o,--output", options->output, "the program to write (default: ./<program name>)");
    build->callback([options] { runBuild(*options); });
}

}  // namespace simlab::cli
