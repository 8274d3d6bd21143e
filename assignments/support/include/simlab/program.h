// What every lab program shares: its command-line options, its error handling, the integrator trade table
// and the animation.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "simlab/driver.h"
#include "simlab/messages.h"
#include "simlab/replay.h"
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
    std::string plot;      ///< draw the run, with the exact solution where there is one, into this PNG or SVG
    std::string replay;    ///< write a page that replays the run in 3-D, beside its table, into this HTML file
    std::string from;      ///< with plot: draw this results file of an earlier run instead of running
    bool trade = false;    ///< print digits against cost for every integrator instead of one run
    int repeats = 5;       ///< runs per row of the trade table (the median time is shown)
};

/// Adds --integrator, --accuracy, --dt, --final-time, --fixed-step, --output, --quiet, --animate, --plot, --from,
/// --replay, --trade and --repeats,
/// with `options` holding the defaults, and makes parse errors one line: "<program>: error: ...".
void addProgramOptions(CLI::App& app, ProgramOptions& options);

/// Parses the command line. Returns -1 to go on; otherwise the program should exit with the returned status:
/// 0 after --help, 2 after a usage error (already printed as one line).
int parseCommandLine(CLI::App& app, int argc, char** argv);

/// Checks the settings the command line gave (simlab::validate): a combination that cannot run (a sample interval
/// past the final time, say) is a usage error like any other, "<program>: error: ... (see <program> --help)", and
/// returns 2. Returns -1 when they can run.
int checkRunSettings(const std::string& program, const RunSettings& run);

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
/// that fails is listed with its error; one whose run throws TooCostly (driver.h) as too costly, with the reason.
/// Each row is flushed as it is done; when `program` is given and a run takes more than a few seconds, a line on
/// stderr says how long the rest of the table will take.
void printTrade(std::ostream& out, const RunSettings& base, const std::string& figure,
                const std::function<TradePoint(const RunSettings&)>& once, int repeats = 5,
                const std::string& program = "");

/// Keeps what CPodes' C library prints straight to stderr (every error and warning, often dozens of them, each over
/// several lines) off the screen while it exists, when `active`; finish() gives it back as one line. Lines the lab
/// programs print meanwhile (Progress) still reach the screen.
class SolverChatter {
public:
    explicit SolverChatter(bool active);
    ~SolverChatter();
    SolverChatter(const SolverChatter&) = delete;
    SolverChatter& operator=(const SolverChatter&) = delete;
    /// Stops keeping it; returns "" if the solver printed nothing, else one line saying how many messages it
    /// printed and what the first said.
    std::string finish();

private:
    int saved_ = -1;  // the screen's stderr while it is kept
    std::FILE* kept_ = nullptr;
};

/// Writes one line to the screen's stderr, even while a SolverChatter keeps the solver's.
void tellUser(const std::string& line);

/// Says on stderr how long a long run will take. Call at() with the simulated time as the run goes: once ~0.2 s
/// of wall time has passed since its first sample (building the model and starting the run are not the run's pace)
/// it estimates the whole run from the pace since then, and if that is over a minute prints one line saying so, then
/// a progress line at every tenth of the run. A shorter run prints nothing. A run that has not reached its first
/// sample after half that minute says so too (its steps are very small). The minute is SIMLAB_LONG_RUN_SECONDS where
/// that is set (studies lower it, to hear of long runs sooner). `finalTime` is where the run is expected to end: for
/// a run an event ends sooner, that end (the estimate is of the run, never of a final time it will not reach).
class Progress {
public:
    Progress(std::string program, double finalTime, std::string what = "this run");
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;
    void at(double t);

private:
    std::string program_, what_;
    double finalTime_;
    double start_;        // s, wall clock
    double longRun_ = 60; // s: a run expected to take longer is announced
    double firstWall_ = -1, firstTime_ = 0;  // the first sample's wall clock and simulated time
    bool decided_ = false;
    bool long_ = false;
    int tenths_ = 0;      // progress lines printed
    struct Watch;         // the watch for a first sample that does not come
    std::unique_ptr<Watch> watch_;
};

/// What --animate shows of a run besides the bodies: where to look, the floor, the bodies' trails.
struct Scenery {
    SimTK::Vec3 low{-1, -1, -1}, high{1, 1, 1};  ///< m, in Ground: a box the whole motion stays in; the camera frames it
    bool floor = true;                            ///< draw the visualizer's floor ...
    double floorHeight = 0;                       ///< ... at this y (m)
    bool trails = false;                          ///< a line behind each body, where its origin has been
};

/// Adds a Simbody visualizer to `system` (call before its topology is realized) that shows a frame every
/// `frameInterval` s of simulated time, in real time, with the camera framing `scenery`'s box. A body is drawn as
/// its decorations say (the course's, or a student's own); one without any as a sphere of `radius` m. Needs a
/// display; throws std::runtime_error saying so if there is none. The visualizer plays behind the simulation:
/// call the returned function once the simulation is over to wait for the last frame, while `system` still
/// exists.
std::function<void()> attachVisualizer(SimTK::MultibodySystem& system, double frameInterval, double radius,
                                       const Scenery& scenery = {});

/// Adds `geometry` to `body` unless something already draws it: what a student put on a body in buildModel is
/// shown as drawn, instead of the course's drawing. Call before the topology is realized.
void decorateUnlessDrawn(SimTK::MobilizedBody& body, const std::vector<SimTK::DecorativeGeometry>& geometry);

/// How a lab program shows a run.
template <class Sample, class Model>
struct Tabulation {
    std::vector<std::string> columns;                         ///< the results file's header
    std::function<std::vector<double>(const Sample&)> row;    ///< one value per column
    std::string banner;                                       ///< one line saying what runs
    double bodyRadius = 0.05;                                 ///< m, the sphere --animate draws for a bare body
    Scenery scenery;                                          ///< what else --animate shows
    std::function<void(Model&)> decorate;                     ///< adds the course's drawing of the bodies
    std::string program;                                      ///< for the progress lines of a long run
    /// s: where the run is expected to end when an event ends it before the final time (the projectile's ground hit),
    /// for the progress lines' estimate; 0: at the final time.
    double expectedEnd = 0;
    std::string conserved;       ///< a column the run should conserve (the energy), or empty
    /// The run fails if `conserved` moves from its first value by more than this many times its scale in the scene:
    /// the largest of its first value's magnitude, `conservedSize` and its terms at the first sample.
    double conservedGrowth = 1e6;
    /// The size of the terms the conserved quantity sums in a sample (for an energy, |kinetic| + |potential|), or
    /// empty where it has no terms that cancel: rounding on that scale is what a row's value can be trusted to.
    std::function<double(const Sample&)> conservedScale;
    /// The scene's own size for the conserved quantity over the whole motion, where its terms at the first sample
    /// can be zero (an apple dropped from y = 0 at rest); 0: those terms and the first value are the scale.
    double conservedSize = 0;
};

/// One run of a lab program: open the results file (an unwritable path fails before anything runs), print the
/// banner, simulate with the course's driver while printing and saving each row, with the course's drawing of the
/// bodies animate it (--animate) and record it for its replay page (--replay), and say where everything went.
template <class Sample, class Scene, class Model>
RunResult<Sample> runTabulated(const Scene& scene, Model& model, const ProgramOptions& options,
                               const Tabulation<Sample, Model>& tabulation) {
    ResultsTable table(tabulation.columns, options.output, options.quiet ? nullptr : &std::cout);
    if (!tabulation.conserved.empty()) {
        table.watchGrowth(tabulation.conserved, tabulation.conservedGrowth, tabulation.conservedSize);
    }
    std::cout << tabulation.banner << std::endl;
    const double end = tabulation.expectedEnd > 0 ? std::min(tabulation.expectedEnd, options.run.finalTime)
                                                  : options.run.finalTime;
    Progress progress(tabulation.program, end);
    RunHooks<Model> hooks;
    std::function<void()> finishAnimation;
    std::unique_ptr<ReplayRecorder> replay;
    std::vector<std::vector<double>> rows;  // for the replay's charts
    if (options.animate || !options.replay.empty()) {
        hooks.afterBuild = [&](Model& m) {
            if (tabulation.decorate) tabulation.decorate(m);
            if (options.animate) {
                finishAnimation = attachVisualizer(m.system, 1.0 / 30, tabulation.bodyRadius, tabulation.scenery);
            }
            if (!options.replay.empty()) replay = std::make_unique<ReplayRecorder>(m.system, 1.0 / 30);
        };
        hooks.afterRun = [&](const Model&, const SimTK::Integrator&) {
            if (finishAnimation) finishAnimation();
        };
    }
    RunResult<Sample> result;
    SolverChatter chatter(options.run.integrator == "CPodes");
    // Where the conserved column sums terms that cancel, how far they outgrow it (rounding on the terms' scale is all
    // a row's value can be trusted to), and how far it moves over the run.
    const auto conservedAt = std::find(tabulation.columns.begin(), tabulation.columns.end(), tabulation.conserved);
    const bool watched = conservedAt != tabulation.columns.end();
    double termsOverValue = 0, largestTerms = 0, first = NAN, largestChange = 0;
    try {
        result = run<Sample>(
            scene, model, options.run,
            [&](const Sample& s) {
                const std::vector<double> row = tabulation.row(s);
                const double terms = tabulation.conservedScale ? tabulation.conservedScale(s) : 0.0;
                if (watched) {
                    const double value = row[static_cast<std::size_t>(conservedAt - tabulation.columns.begin())];
                    if (std::isnan(first)) {
                        first = value;
                        // The scene's size for the quantity: its terms at the start count too (m g L, say).
                        if (std::isfinite(terms) && terms > tabulation.conservedSize) {
                            table.watchGrowth(tabulation.conserved, tabulation.conservedGrowth, terms);
                        }
                    }
                    if (terms > 0) {
                        termsOverValue = std::max(termsOverValue, value != 0 ? terms / std::abs(value) : INFINITY);
                        largestTerms = std::max(largestTerms, terms);
                    }
                    if (std::isfinite(value - first)) largestChange = std::max(largestChange, std::abs(value - first));
                }
                table.add(row);
                if (!options.replay.empty()) rows.push_back(row);
                if (!tabulation.program.empty()) progress.at(row.front());
            },
            hooks);
    } catch (const std::exception& e) {
        // A run that stops part way leaves a file that says so.
        if (table.rows() > 0) table.note("the run stopped here: " + oneLineMessage(e.what()));
        chatter.finish();  // the error says what failed
        throw;
    }
    if (const std::string said = chatter.finish(); !said.empty()) tellUser(tabulation.program + ": " + said);
    if (result.samples.empty()) throw std::runtime_error("the simulation recorded no samples");
    std::cout << "\nResults written to " << table.path() << '\n';
    // A double holds 15.9 digits of the terms; what they cancel to keeps 15.9 - log10(terms / value) of them. Where
    // that leaves fewer than 12, the rows' values carry rounding of about one unit in the terms' last place, which
    // the note gives in the column's own unit, beside how far the value moved over the run: a change well past that
    // rounding is the integrator's drift, not rounding.
    if (termsOverValue > 0 && 15.9 - std::log10(termsOverValue) < 12) {
        const double rounding = 2.2e-16 * largestTerms;
        char said[400];
        if (largestChange > 10 * rounding) {
            std::snprintf(said, sizeof said,
                          "Note: %s sums terms of up to %.3g that cancel, so rounding moves each row's value by about "
                          "%.2g (past that the 17 digits of the results file are rounding); its largest change over "
                          "the run, %.2g, is the integrator's drift, %.2g times that rounding.\n",
                          tabulation.conserved.c_str(), largestTerms, rounding, largestChange,
                          largestChange / rounding);
        } else {
            std::snprintf(said, sizeof said,
                          "Note: %s sums terms of up to %.3g that cancel, so rounding moves each row's value by about "
                          "%.2g (past that the 17 digits of the results file are rounding); its largest change over "
                          "the run, %.2g, is of that rounding's order.\n",
                          tabulation.conserved.c_str(), largestTerms, rounding, largestChange);
        }
        std::cout << said;
    }
    if (replay) {
        replay->write(options.replay, tabulation.banner, tabulation.columns, rows);
        std::cout << "Replay written to " << options.replay << " (open it in a web browser)\n";
    }
    return result;
}

}  // namespace simlab
