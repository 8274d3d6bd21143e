// simlab plot: an existing results file drawn as its lab program draws a run (--plot), by that program.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <memory>

#include "commands.h"
#include "simlab/common/errors.h"
#include "simlab/build/manifest.h"
#include "simlab/common/text.h"

namespace simlab::cli {

namespace {

struct PlotOptions {
    std::string assignment;
    std::string results;
    std::string output;
    std::vector<std::string> scene;  // the lab program's options of the run that wrote the file
};

// Hands over to the lab program, `<program> --from RESULTS --plot OUTPUT [scene options]`: it reads the file back,
// checks it against the scene, and draws it over that scene's exact solution. It runs no student code to do so.
[[noreturn]] void runPlot(const PlotOptions& o) {
    using namespace simlab::engine;
    const Manifest manifest = loadManifest();
    const Assignment& assignment = manifest.find(o.assignment);
    if (!std::filesystem::is_regular_file(o.results)) throw UsageError("no results file '" + o.results + "'");
    if (!std::filesystem::exists(assignment.programPath)) {
        throw UsageError("the " + assignment.program + " program is not built yet (cmake --build build)");
    }
    std::string output = o.output;
    if (output.empty()) output = std::filesystem::path(o.results).replace_extension(".png").string();
    std::vector<std::string> args = {assignment.program, "--from", o.results, "--plot", output};
    args.insert(args.end(), o.scene.begin(), o.scene.end());
    handOver(assignment.programPath, args);
}

}  // namespace

void addPlot(CLI::App& app) {
    auto options = std::make_shared<PlotOptions>();
    CLI::App* plot = app.add_subcommand(
        "plot", "Draw a lab program's results file over the exact solution, as the program's --plot draws a run: "
                "`simlab plot LAB RESULTS.txt -- OPTIONS`. Options after -- are the run's own "
                "(its scene); the file must start where that scene does.");
    plot->add_option("assignment", options->assignment, "which assignment's program wrote the file")->required();
    plot->add_option("results", options->results, "the results file")->required();
    plot->add_option("-o,--output", options->output, "the plot to write, .png or .svg (default: RESULTS as .png)");
    plot->add_option("scene", options->scene, "after --: the options of the run that wrote the file");
    plot->callback([options] { runPlot(*options); });
}

}  // namespace simlab::cli
