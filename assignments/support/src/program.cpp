#include "simlab/program.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <vector>

#include "Simbody.h"
#include "simlab/cli_checks.h"
#include "simlab/integrators.h"
#include "simlab/todo.h"

namespace simlab {

void addProgramOptions(CLI::App& app, ProgramOptions& options) {
    RunSettings& run = options.run;
    std::string names;
    for (const std::string& n : integratorNames()) names += (names.empty() ? "" : ", ") + n;

    app.add_option("--integrator", run.integrator, "Simbody integrator: " + names)
        ->check([](const std::string& name) {
            try {
                requireIntegratorName(name);
                return std::string();
            } catch (const std::invalid_argument& e) {
                return std::string(e.what());
            }
        })
        ->capture_default_str();
    app.add_option("--accuracy", run.accuracy, "relative accuracy of the error-controlled integrators")
        ->check(CLI::Range(1e-15, 0.5).description("between 1e-15 and 0.5"))
        ->capture_default_str();
    app.add_option("--dt", run.dt, "seconds between samples; also the step of fixed-step integration")
        ->check(positive())
        ->capture_default_str();
    app.add_option("--final-time", run.finalTime, "seconds to simulate")
        ->check(positive())
        ->capture_default_str();
    app.add_flag("--fixed-step", run.fixedStep,
                 "step at exactly --dt without error control (SemiExplicitEuler always does)");
    app.add_option("--output,-o", options.output, "results file (tab-separated columns)")->capture_default_str();
    app.add_flag("--quiet,-q", options.quiet, "do not print the table on the screen");
    app.add_flag("--animate", options.animate, "show the motion in Simbody's visualizer (needs a display)");
    app.add_flag("--trade", options.trade,
                 "instead of one run, print accuracy digits against cost for every integrator");
    app.add_option("--repeats", options.repeats, "with --trade: runs per row; the median time is shown")
        ->check(CLI::Range(1, 100))
        ->capture_default_str();

    const std::string program = app.get_name();
    app.failure_message([program](const CLI::App*, const CLI::Error& e) {
        return program + ": error: " + e.what() + " (see " + program + " --help)\n";
    });
}

int parseCommandLine(CLI::App& app, int argc, char** argv) {
    try {
        app.parse(argc, argv);
        return -1;
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;
    }
}

int runGuarded(const std::string& program, const std::function<int()>& body) {
    try {
        return body();
    } catch (const NotDoneYet& e) {
        std::cout.flush();
        std::cerr << program << ": " << e.what() << '\n'
                  << program << ": finish the SIMLAB_TODO at " << e.file() << ":" << e.line()
                  << ", rebuild, and run again.\n";
        return 3;
    } catch (const std::exception& e) {
        std::cout.flush();
        // Simbody's messages span lines; the first says what went wrong.
        std::string what = e.what();
        std::replace(what.begin(), what.end(), '\n', ' ');
        std::cerr << program << ": error: " << what << '\n';
        return 1;
    }
}

void printTrade(std::ostream& out, const RunSettings& base, const std::string& figure,
                const std::function<TradePoint(const RunSettings&)>& once, int repeats) {
    char line[256];
    std::snprintf(line, sizeof line, "%-20s %10s %10s %14s %12s\n", "integrator", "digits", "steps",
                  "evaluations", "median ms");
    out << "Digits of " << figure << " against cost, accuracy " << base.accuracy << ", dt " << base.dt << " s"
        << (base.fixedStep ? ", fixed steps" : "") << ", median of " << repeats << " runs\n"
        << line;
    for (const std::string& name : integratorNames()) {
        RunSettings run = base;
        run.integrator = name;
        try {
            TradePoint point;
            std::vector<double> ms;
            for (int r = 0; r < repeats; ++r) {
                const auto start = std::chrono::steady_clock::now();
                point = once(run);
                const std::chrono::duration<double, std::milli> took = std::chrono::steady_clock::now() - start;
                ms.push_back(took.count());
            }
            std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
            std::snprintf(line, sizeof line, "%-20s %10.2f %10d %14d %12.2f\n", name.c_str(), point.digits,
                          point.steps, point.realizations, ms[ms.size() / 2]);
            out << line;
        } catch (const std::exception& e) {
            std::string what = e.what();
            what = what.substr(0, what.find('\n'));
            out << name << std::string(name.size() < 20 ? 21 - name.size() : 1, ' ') << "failed: " << what << '\n';
        }
    }
}

namespace {

// Draws every body other than Ground as a sphere at its origin.
class BodySpheres : public SimTK::DecorationGenerator {
public:
    BodySpheres(const SimTK::SimbodyMatterSubsystem& matter, double radius) : matter_(matter), radius_(radius) {}
    void generateDecorations(const SimTK::State& state, SimTK::Array_<SimTK::DecorativeGeometry>& geometry) override {
        for (int i = 1; i < matter_.getNumBodies(); ++i) {
            const SimTK::MobilizedBody& body = matter_.getMobilizedBody(SimTK::MobilizedBodyIndex(i));
            geometry.push_back(SimTK::DecorativeSphere(radius_)
                                   .setTransform(body.getBodyTransform(state))
                                   .setColor(SimTK::Red));
        }
    }

private:
    const SimTK::SimbodyMatterSubsystem& matter_;
    double radius_;
};

}  // namespace

std::function<void()> attachVisualizer(SimTK::MultibodySystem& system, double frameInterval, double radius) {
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display) {
        throw std::runtime_error("--animate needs a display and DISPLAY is not set (over ssh use -X; without a "
                                 "screen, run under xvfb-run)");
    }
    // Debian installs the visualizer as simbody-visualizer; without this Simbody looks for a _d variant.
    setenv("SIMBODY_VISUALIZER_NAME", "simbody-visualizer", /*overwrite=*/0);
    SimTK::Visualizer visualizer(system);  // a counted handle: the reporter keeps it alive
    visualizer.setMode(SimTK::Visualizer::RealTime);
    visualizer.setShowSimTime(true);
    visualizer.addDecorationGenerator(new BodySpheres(system.getMatterSubsystem(), radius));
    system.addEventReporter(new SimTK::Visualizer::Reporter(visualizer, frameInterval));  // the system adopts it
    return [visualizer] { visualizer.flushFrames(); };
}

}  // namespace simlab
