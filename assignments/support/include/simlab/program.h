// What every lab program shares: its command-line options, its error handling, the integrator trade table
// and the animation.
#pragma once

#include <functional>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "simlab/driver.h"
#include "simlab/results_table.h"
#include "simlab/run_settings.h"

namespace CLI {
class App;
}

namespace simlab {

struct ProgramOptions {
    RunSettings run;
    std::string output;    ///< results file
    bool quiet = false;    ///< do not print the table on the screen
    bool animate = false;  ///< show the motion in Simbody's visualizer
    bool trade = false;    ///< print digits against cost for every integrator instead of one run
    int repeats = 5;       ///< runs per row of the trade table (the median time is shown)
};

/// Adds --integrator, --accuracy, --dt, --final-time, --fixed-step, --output, --quiet, --animate, --trade and --repeats,
/// with `options` holding the defaults, and makes parse errors one line: "<program>: error: ...".
void addProgramOptions(CLI::App& app, ProgramOptions& options);

/// Parses the command line. Returns -1 to go on; otherwise the program should exit with the returned status:
/// 0 after --help, 2 after a usage error (already printed as one line).
int parseCommandLine(CLI::App& app, int argc, char** argv);

/// Runs `body` and returns its exit status. A SIMLAB_TODO that is reached prints where and what is missing and
/// returns 3; any other exception prints one line "<program>: error: ..." and returns 1.
int runGuarded(const std::string& program, const std::function<int()>& body);

/// One run of the trade table: the digits it reached and the steps it took.
struct TradePoint {
    double digits = 0;
    int steps = 0;
    int realizations = 0;
};

/// For every integrator, run `once` with `base` changed to that integrator `repeats` times and print one row:
/// digits of `figure`, steps, evaluations of the equations of motion and the median wall time. An integrator
/// that fails is listed with its error.
void printTrade(std::ostream& out, const RunSettings& base, const std::string& figure,
                const std::function<TradePoint(const RunSettings&)>& once, int repeats = 5);

/// Adds a Simbody visualizer to `system` (call before its topology is realized) that draws every body as a
/// sphere of `radius` m and shows a frame every `frameInterval` s of simulated time, in real time. Needs a
/// display; throws std::runtime_error saying so if there is none. The visualizer plays behind the simulation:
/// call the returned function once the simulation is over to wait for the last frame, while `system` still
/// exists.
std::function<void()> attachVisualizer(SimTK::MultibodySystem& system, double frameInterval, double radius);

/// How a lab program shows a run.
template <class Sample>
struct Tabulation {
    std::vector<std::string> columns;                         ///< the results file's header
    std::function<std::vector<double>(const Sample&)> row;    ///< one value per column
    std::string banner;                                       ///< one line saying what runs
    double bodyRadius = 0.05;                                 ///< m, the spheres --animate draws
};

/// One run of a lab program: open the results file (an unwritable path fails before anything runs), print the
/// banner, simulate with the course's driver while printing and saving each row, animate with --animate, and
/// say where the results went.
template <class Sample, class Scene, class Model>
RunResult<Sample> runTabulated(const Scene& scene, Model& model, const ProgramOptions& options,
                               const Tabulation<Sample>& tabulation) {
    ResultsTable table(tabulation.columns, options.output, options.quiet ? nullptr : &std::cout);
    std::cout << tabulation.banner << std::endl;
    RunHooks<Model> hooks;
    std::function<void()> finishAnimation;
    if (options.animate) {
        hooks.afterBuild = [&](Model& m) {
            finishAnimation = attachVisualizer(m.system, 1.0 / 30, tabulation.bodyRadius);
        };
        hooks.afterRun = [&](const Model&, const SimTK::Integrator&) { finishAnimation(); };
    }
    RunResult<Sample> result = run<Sample>(
        scene, model, options.run, [&](const Sample& s) { table.add(tabulation.row(s)); }, hooks);
    if (result.samples.empty()) throw std::runtime_error("the simulation recorded no samples");
    std::cout << "\nResults written to " << table.path() << '\n';
    return result;
}

}  // namespace simlab
