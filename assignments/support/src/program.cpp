#include "simlab/program.h"
#include "simlab/plot.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <thread>
#include <mutex>
#include <condition_variable>
#include <cmath>
#include <cstdio>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iostream>
#include <sstream>
#include <unistd.h>
#include <vector>

#include "Simbody.h"
#include "simlab/cli_checks.h"
#include "simlab/integrators.h"
#include "simlab/todo.h"

namespace simlab {

void addProgramOptions(CLI::App& app, ProgramOptions& options) {
    int major = 0, minor = 0, build = 0;
    SimTK_version_simbody(&major, &minor, &build);
    app.set_version_flag("--version",
                         app.get_name() + " (simlab " SIMLAB_VERSION ", Simbody " + std::to_string(major) + "." +
                             std::to_string(minor) + ")",
                         "print the program's version and exit");
    RunSettings& run = options.run;
    std::string names;
    for (const std::string& n : integratorNames()) names += (names.empty() ? "" : ", ") + n;

    app.add_flag_callback(
        "--integrators",
        [] {
            std::cout << integratorTable();
            throw CLI::Success();
        },
        "list the integrators, whether each controls its error, and what the accuracy means for it; then exit");
    app.add_option("--integrator", run.integrator, "Simbody integrator (--integrators lists them): " + names)
        ->check([](const std::string& name) {
            try {
                requireIntegratorName(name);
                return std::string();
            } catch (const std::invalid_argument& e) {
                return std::string(e.what());
            }
        })
        ->capture_default_str();
    app.add_option("--accuracy", run.accuracy,
                   "relative accuracy each step of an error-controlled integrator keeps; at a fixed step Verlet "
                   "still solves its implicit velocity update to it (to min(1e-4, accuracy / 10)), and events are "
                   "timed by it")
        ->check(between(1e-15, 0.5))
        ->capture_default_str();
    app.add_option("--dt", run.dt,
                   "seconds between samples, each of which ends an integrator's step (so a smaller --dt shortens an "
                   "error-controlled integrator's steps; --dt equal to --final-time leaves them its own); also the "
                   "step of fixed-step integration")
        ->check(positive())
        ->capture_default_str();
    app.add_option("--final-time", run.finalTime, "seconds to simulate")
        ->check(positive())
        ->capture_default_str();
    app.add_flag("--fixed-step", run.fixedStep,
                 "step at exactly --dt without error control (SemiExplicitEuler always does); --accuracy still counts "
                 "for Verlet's implicit step and for the times of events");
    app.add_option("--output,-o", options.output, "results file (tab-separated columns)")->capture_default_str();
    app.add_flag("--quiet,-q", options.quiet, "do not print the table on the screen");
    app.add_flag("--animate", options.animate, "show the motion in Simbody's visualizer (needs a display)");
    CLI::Option* plot =
        app.add_option("--plot", options.plot, "draw the run against the exact solution into this .png or .svg file")
            ->check([](const std::string& path) { return plotPathProblem(path); });
    CLI::Option* from = app.add_option("--from", options.from,
                                       "with --plot: draw this results file of an earlier run instead of running")
                            ->needs(plot);
    CLI::Option* replay =
        app.add_option("--replay", options.replay, "write a page that replays the run in 3-D into this .html file")
            ->check([](const std::string& path) {
                const bool html = path.size() > 5 && path.compare(path.size() - 5, 5, ".html") == 0;
                return html ? std::string() : "a replay is an .html file, not '" + path + "'";
            });
    app.add_flag("--trade", options.trade,
                 "instead of one run, print accuracy digits against cost for every integrator")
        ->excludes(plot)
        ->excludes(replay);
    from->excludes(replay)->excludes("--animate");
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

int checkRunSettings(const std::string& program, const RunSettings& run) {
    try {
        validate(run);
        return -1;
    } catch (const std::invalid_argument& e) {
        std::cerr << program << ": error: " << e.what() << " (see " << program << " --help)\n";
        return 2;
    }
}

namespace {

int screenStderr = 2;  // where tellUser writes: fd 2, or the screen's stderr while a SolverChatter keeps fd 2
char abortPrefix[256];  // "<program>: error: ", set before the run

/// The line of `text` (n bytes) that names an internal check or a terminate, if any: [begin, end).
std::pair<std::size_t, std::size_t> checkLine(const char* text, std::size_t n) {
    std::size_t begin = 0;
    for (std::size_t i = 0; i <= n; ++i) {
        if (i == n || text[i] == '\n') {
            for (std::size_t j = begin; j + 9 <= i; ++j) {
                if (std::memcmp(text + j, "Assertion", 9) == 0 || std::memcmp(text + j, "terminate", 9) == 0) {
                    return {begin, i};
                }
            }
            begin = i + 1;
        }
    }
    return {0, 0};
}

/// SIGABRT: an assert() inside Simbody or the C++ library failed, or the run was terminated. One line on the
/// screen names it (the check's own words, if a SolverChatter kept them from the screen) and the program exits
/// with status 1, as for any other error. Only async-signal-safe calls.
extern "C" void onAbort(int) {
    auto say = [](const char* text, std::size_t n) {
        if (::write(screenStderr, text, n) < 0) return;
    };
    say(abortPrefix, std::strlen(abortPrefix));
    static const char stopped[] = "the run stopped in an internal check of Simbody or the C++ library";
    say(stopped, sizeof stopped - 1);
    static char kept[4096];
    std::size_t n = 0;
    if (screenStderr != 2 && ::lseek(2, 0, SEEK_SET) == 0) {
        const ssize_t got = ::read(2, kept, sizeof kept);
        n = got > 0 ? static_cast<std::size_t>(got) : 0;
    }
    const std::pair<std::size_t, std::size_t> line = checkLine(kept, n);
    if (line.second > line.first) {
        say(": ", 2);
        say(kept + line.first, std::min<std::size_t>(line.second - line.first, 300));
    } else {
        static const char above[] = " (the line above names it)";
        say(above, sizeof above - 1);
    }
    static const char advice[] = "; the scene or setting is past what it can follow\n";
    say(advice, sizeof advice - 1);
    ::_exit(1);
}

}  // namespace

int runGuarded(const std::string& program, const std::function<int()>& body) {
    std::snprintf(abortPrefix, sizeof abortPrefix, "%s: error: ", program.c_str());
    std::signal(SIGABRT, onAbort);
    // An exception that reaches std::terminate (thrown through a noexcept function) says what it was, in one line.
    static std::string name;
    name = program;
    std::set_terminate([] {
        std::string what = "an exception of unknown type";
        if (const std::exception_ptr e = std::current_exception()) {
            try {
                std::rethrow_exception(e);
            } catch (const std::exception& x) {
                what = x.what();
            } catch (...) {
            }
        }
        std::cout.flush();
        tellUser(name + ": error: the run stopped on an exception where none may pass: " + oneLineMessage(what));
        std::_Exit(1);
    });
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
        std::cerr << program << ": error: " << oneLineMessage(e.what()) << '\n';
        return 1;
    }
}


void tellUser(const std::string& line) {
    std::cerr.flush();
    const std::string text = line + "\n";
    if (::write(screenStderr, text.data(), text.size()) < 0) return;
}

SolverChatter::SolverChatter(bool active) {
    if (!active || screenStderr != 2) return;  // not nested
    kept_ = std::tmpfile();
    if (!kept_) return;
    std::fflush(stderr);
    saved_ = ::dup(2);
    if (saved_ < 0 || ::dup2(::fileno(kept_), 2) < 0) {
        std::fclose(kept_);
        kept_ = nullptr;
        return;
    }
    screenStderr = saved_;
}

SolverChatter::~SolverChatter() { finish(); }

std::string SolverChatter::finish() {
    if (!kept_) return "";
    std::fflush(stderr);
    ::dup2(saved_, 2);
    ::close(saved_);
    screenStderr = 2;
    std::rewind(kept_);
    std::string text;
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, kept_)) > 0;) text.append(buffer, n);
    std::fclose(kept_);
    kept_ = nullptr;
    // CPodes writes each message as "\n[CPODES ERROR]  CPode\n  At t = ..., what happened.\n\n".
    int messages = 0;
    std::string first, line;
    std::istringstream lines(text);
    bool header = false;
    while (std::getline(lines, line)) {
        const std::size_t begin = line.find_first_not_of(" \t");
        if (begin == std::string::npos) continue;
        line = line.substr(begin);
        if (line[0] == '[') {
            ++messages;
            header = true;
            continue;
        }
        if (header && first.empty()) first = line;
        if (!header && messages == 0) ++messages, first = line;  // something else printed it
        header = false;
    }
    if (messages == 0) return "";
    return "the solver printed " + std::to_string(messages) + (messages == 1 ? " message" : " messages") +
           (first.empty() ? "" : ", the first: " + first);
}

struct Progress::Watch {
    std::mutex mutex;
    std::condition_variable wake;
    bool sampled = false;  // the first sample came, or the run is over
    std::thread thread;
};

Progress::Progress(std::string program, double finalTime, std::string what)
    : program_(std::move(program)), what_(std::move(what)), finalTime_(finalTime),
      start_(std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count()) {
    if (const char* seconds = std::getenv("SIMLAB_LONG_RUN_SECONDS")) {
        const double value = std::strtod(seconds, nullptr);
        if (value > 0 && value < 1e6) longRun_ = value;
    }
    if (program_.empty()) return;
    watch_ = std::make_unique<Watch>();
    Watch* watch = watch_.get();
    const double patience = longRun_ / 2;
    const std::string line = program_ + ": no sample after " + std::to_string(static_cast<int>(patience)) +
                             " s: the integrator's steps are very small (see --accuracy, --integrator), and " +
                             what_ + " may take very long";
    watch->thread = std::thread([watch, patience, line] {
        std::unique_lock<std::mutex> lock(watch->mutex);
        if (!watch->wake.wait_for(lock, std::chrono::duration<double>(patience), [watch] { return watch->sampled; })) {
            tellUser(line);
        }
    });
}

Progress::~Progress() {
    if (!watch_) return;
    {
        std::lock_guard<std::mutex> lock(watch_->mutex);
        watch_->sampled = true;
    }
    watch_->wake.notify_all();
    watch_->thread.join();
}

void Progress::at(double t) {
    if (program_.empty() || !(t > 0) || !(finalTime_ > 0)) return;
    if (watch_ && !decided_) {
        {
            std::lock_guard<std::mutex> lock(watch_->mutex);
            watch_->sampled = true;
        }
        watch_->wake.notify_all();
    }
    const double now = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
    const double elapsed = now - start_;
    if (firstWall_ < 0) {
        firstWall_ = now;
        firstTime_ = t;
    }
    if (!decided_) {
        // The pilot: the pace over ~0.2 s of wall time from the first sample, which the time before it (building
        // the model, starting the run) would only blur.
        if (now - firstWall_ < 0.2 || !(t > firstTime_)) return;
        decided_ = true;
        const double estimate = elapsed + (now - firstWall_) * (finalTime_ - t) / (t - firstTime_);
        long_ = estimate > longRun_;
        if (long_) {
            std::ostringstream line;
            line << program_ << ": " << what_ << " will take about " << durationText(estimate) << " (t = " << t
                 << " of " << finalTime_ << " s simulated in " << durationText(elapsed) << ")";
            tellUser(line.str());
        }
    }
    if (!long_) return;
    const int tenths = static_cast<int>(10 * t / finalTime_);
    if (tenths > tenths_ && tenths < 10) {
        tenths_ = tenths;
        std::ostringstream line;
        line << program_ << ": t = " << t << " of " << finalTime_ << " s (" << 10 * tenths << " %), about "
             << durationText(elapsed * (finalTime_ - t) / t) << " left";
        tellUser(line.str());
    }
}

void printTrade(std::ostream& out, const RunSettings& base, const std::string& figure,
                const std::function<TradePoint(const RunSettings&)>& once, int repeats,
                const std::string& program) {
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
            // CPodes' own messages stay off the screen: the row says what failed.
            SolverChatter chatter(name == "CPodes");
            for (int r = 0; r < repeats; ++r) {
                const auto start = std::chrono::steady_clock::now();
                point = once(run);
                const std::chrono::duration<double, std::milli> took = std::chrono::steady_clock::now() - start;
                ms.push_back(took.count());
                if (r == 0 && !program.empty() && took.count() > 5000 && repeats > 1) {
                    tellUser(program + ": " + name + " took " + durationText(took.count() / 1000) +
                             " a run; its row needs " +
                             std::to_string(repeats - 1) + " more (--repeats 1 for one)");
                }
            }
            std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
            std::snprintf(line, sizeof line, "%-20s %10.2f %10d %14d %12.2f\n", name.c_str(), point.digits,
                          point.steps, point.realizations, ms[ms.size() / 2]);
            out << line << std::flush;
        } catch (const TooCostly& e) {
            out << name << std::string(name.size() < 20 ? 21 - name.size() : 1, ' ')
                << "too costly: " << oneLineMessage(e.what()) << '\n' << std::flush;
        } catch (const std::exception& e) {
            out << name << std::string(name.size() < 20 ? 21 - name.size() : 1, ' ')
                << "failed: " << oneLineMessage(e.what()) << '\n' << std::flush;
        }
    }
}

namespace {

// Draws each body that has no decorations of its own as a sphere at its origin, so that nothing is invisible.
class BareBodySpheres : public SimTK::DecorationGenerator {
public:
    BareBodySpheres(const SimTK::SimbodyMatterSubsystem& matter, double radius) : matter_(matter), radius_(radius) {}
    void generateDecorations(const SimTK::State& state, SimTK::Array_<SimTK::DecorativeGeometry>& geometry) override {
        for (int i = 1; i < matter_.getNumBodies(); ++i) {
            const SimTK::MobilizedBody& body = matter_.getMobilizedBody(SimTK::MobilizedBodyIndex(i));
            if (body.getBody().getNumDecorations() > 0) continue;
            geometry.push_back(SimTK::DecorativeSphere(radius_)
                                   .setTransform(body.getBodyTransform(state))
                                   .setColor(SimTK::Red));
        }
    }

private:
    const SimTK::SimbodyMatterSubsystem& matter_;
    double radius_;
};

// Draws where each body's origin has been, as a line through its positions at the frames shown so far.
class Trails : public SimTK::DecorationGenerator {
public:
    explicit Trails(const SimTK::SimbodyMatterSubsystem& matter) : matter_(matter) {}
    void generateDecorations(const SimTK::State& state, SimTK::Array_<SimTK::DecorativeGeometry>& geometry) override {
        paths_.resize(matter_.getNumBodies());
        for (int i = 1; i < matter_.getNumBodies(); ++i) {
            std::vector<SimTK::Vec3>& path = paths_[i];
            if (!path.empty() && state.getTime() == 0) path.clear();  // a new run
            path.push_back(matter_.getMobilizedBody(SimTK::MobilizedBodyIndex(i)).getBodyOriginLocation(state));
            for (std::size_t k = 1; k < path.size(); ++k) {
                geometry.push_back(SimTK::DecorativeLine(path[k - 1], path[k]).setColor(SimTK::Gray).setLineThickness(2));
            }
        }
    }

private:
    const SimTK::SimbodyMatterSubsystem& matter_;
    std::vector<std::vector<SimTK::Vec3>> paths_;
};

}  // namespace

void decorateUnlessDrawn(SimTK::MobilizedBody& body, const std::vector<SimTK::DecorativeGeometry>& geometry) {
    if (body.getBody().getNumDecorations() > 0) return;
    for (const SimTK::DecorativeGeometry& g : geometry) body.updBody().addDecoration(g);  // placed by its own transform
}

std::function<void()> attachVisualizer(SimTK::MultibodySystem& system, double frameInterval, double radius,
                                       const Scenery& scenery) {
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
    visualizer.setSystemUpDirection(SimTK::YAxis);
    // Only what the bodies' decorations draw (and the spheres below): Simbody's own frames and wire spheres on
    // every body and mobilizer would hide the scene.
    system.updMatterSubsystem().setShowDefaultGeometry(false);
    if (scenery.floor) {
        visualizer.setGroundHeight(scenery.floorHeight);
    } else {
        visualizer.setBackgroundType(SimTK::Visualizer::SolidColor);
    }
    visualizer.addDecorationGenerator(new BareBodySpheres(system.getMatterSubsystem(), radius));
    if (scenery.trails) visualizer.addDecorationGenerator(new Trails(system.getMatterSubsystem()));
    // The camera looks at the box's middle from in front, a little above and to the right, far enough back that
    // the whole box fits in its field of view (which is vertical).
    const SimTK::Vec3 middle = (scenery.low + scenery.high) / 2, size = scenery.high - scenery.low;
    const double fieldOfView = SimTK::Pi / 4;
    const double aspect = 4.0 / 3;  // the visualizer's window
    const double distance =
        0.6 * std::max({size[0] / aspect, size[1], 1e-3}) / std::tan(fieldOfView / 2) + size[2] / 2;
    const SimTK::Vec3 from = middle + distance * SimTK::UnitVec3(0.15, 0.1, 1).asVec3();
    visualizer.setCameraFieldOfView(fieldOfView);
    visualizer.setCameraClippingPlanes(distance / 1000, distance * 10);
    visualizer.setCameraTransform(SimTK::Transform(from));
    visualizer.pointCameraAt(middle, SimTK::Vec3(0, 1, 0));
    system.addEventReporter(new SimTK::Visualizer::Reporter(visualizer, frameInterval));  // the system adopts it
    return [visualizer] { visualizer.flushFrames(); };
}

}  // namespace simlab
