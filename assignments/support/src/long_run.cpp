#include "simlab/long_run.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <vector>

#include "simlab/cli_checks.h"
#include "simlab/measured_run.h"
#include "simlab/messages.h"
#include "simlab/plot.h"
#include "simlab/reproducible_math.h"
#include "simlab/run_settings.h"

namespace simlab::study {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// Samples per decade of time, from kFirstSample to the final time.
constexpr int kPerDecade = 20;
constexpr double kFirstSample = 0.1;  ///< s
/// Seconds between progress lines on standard error during a long setting.
constexpr double kProgressSeconds = 3;
/// An energy drift below this is drawn at it: the rounding of a sum of terms the size of the scale.
constexpr double kDriftFloor = 1e-16;

/// One setting of the view and the tighter run its trajectory is judged against (with TrajectoryCheck::tighterRun).
struct Setting {
    RunSettings run;
    RunSettings tighter;  ///< a tenth of the accuracy, or half the fixed step
};

/// A state the run stepped to: the first of its own step ends at or after a sample time.
struct Sample {
    double asked = 0;     ///< s, the sample time (kPerDecade a decade): what the table reads it for
    double time = 0;      ///< s, the step end whose state was read
    double drift = 0;     ///< |E(t) - E(0)| / the subject's scale
    double largest = 0;   ///< the largest drift at the samples up to this one
    double digits = 0;    ///< of the trajectory, against the reference or the tighter run
};

struct SettingRun {
    Setting setting;
    std::vector<Sample> samples;
    std::string failure;  ///< one line, where and why the run stopped short; empty if it reached the final time
    double seconds = 0;   ///< of wall time, the tighter run and the reference included
    int steps = 0;        ///< the setting's own steps (not its tighter run's)
};

RunSettings accuracyOf(double accuracy) {
    RunSettings run;
    run.integrator = "RungeKuttaMerson";
    run.accuracy = accuracy;
    return run;
}

RunSettings fixedStepOf(const std::string& integrator, double step) {
    RunSettings run;
    run.integrator = integrator;
    run.fixedStep = true;
    run.dt = step;
    return run;
}

/// Merson, error-controlled (each step's error kept under the accuracy, its sign left to chance), at a loose and a
/// tight accuracy; Verlet, second order and time-reversible, at a fixed step, its implicit velocity update solved to
/// the view's accuracy for it (simlab::fixedStepUsesAccuracy), its tighter run at the same.
std::vector<Setting> settingsOf(const LongRunView& view) {
    RunSettings verlet = fixedStepOf("Verlet", view.fixedStep), finer = fixedStepOf("Verlet", view.fixedStep / 2);
    verlet.accuracy = finer.accuracy = view.fixedStepAccuracy;
    return {{accuracyOf(1e-6), accuracyOf(1e-7)}, {accuracyOf(1e-9), accuracyOf(1e-10)}, {verlet, finer}};
}

/// kPerDecade times per decade from kFirstSample up to `finalTime`, which ends the list; for a fixed-step run each
/// is moved to the nearest multiple of its step, so that the run (and its tighter one, at half the step) lands
/// there by whole steps.
std::vector<double> sampleTimes(double finalTime, const RunSettings& run) {
    std::vector<double> times;
    for (int k = 0;; ++k) {
        double t = kFirstSample * std::pow(10.0, static_cast<double>(k) / kPerDecade);
        if (t >= finalTime * (1 - 1e-12)) break;
        if (takesFixedSteps(run)) t = std::max(1.0, std::round(t / run.dt)) * run.dt;
        if (times.empty() || t > times.back()) times.push_back(t);
    }
    times.push_back(finalTime);
    return times;
}

bool finite(const SimTK::State& state) {
    const SimTK::Vector& y = state.getY();
    for (int i = 0; i < y.size(); ++i) {
        if (!std::isfinite(y[i])) return false;
    }
    return true;
}

/// A run of `run` on a new instance of `subject`. With `ownSteps`, each state it gives is the one at the first of the
/// run's own step ends at or after the time asked for, so that no sample cuts a step short (a fixed step stays fixed,
/// bar the last, which lands on the final time); without, the run is stepped to the time exactly, its step there cut
/// short (interpolation off): what the tighter run, the reference for self-convergence, does at the run's sample times.
class Stepped {
public:
    Stepped(const Subject& subject, const RunSettings& run, bool ownSteps)
        : instance_(subject.make()),
          integrator_(integratorFor(run, instance_->system(), subject.finalTime)),
          stepper_(instance_->system(), *integrator_),
          finalTime_(subject.finalTime),
          fixedStep_(takesFixedSteps(run) ? run.dt : 0.0),
          ownSteps_(ownSteps) {
        integrator_->setAllowInterpolation(false);
        if (ownSteps_) {
            integrator_->setReturnEveryInternalStep(true);
            stepper_.setReportAllSignificantStates(true);
        }
        stepper_.initialize(instance_->initial());
    }
    /// Steps to `t` (see above); throws std::runtime_error, in one line, where the run cannot get there.
    const SimTK::State& to(double t) {
        // A step end within a trillionth of `t` is at `t`: n fixed steps of h add up to n h but for rounding.
        const double by = t * (1 - 1e-12);
        while (stepper_.getState().getTime() < by && !integrator_->isSimulationOver()) {
            // Its own steps: at a fixed step each ends at k h, as a lab program's do (nextStepEnd).
            stepper_.stepTo(ownSteps_ ? nextStepEnd(fixedStep_, finalTime_, stepper_.getState().getTime()) : t);
        }
        const SimTK::State& state = stepper_.getState();
        char where[64];
        std::snprintf(where, sizeof where, " at t = %.4g s", state.getTime());
        if (!finite(state)) throw std::runtime_error(std::string("the state is not finite") + where);
        if (state.getTime() < by) {
            throw std::runtime_error(std::string("the integrator stopped") + where + " (" +
                                     SimTK::Integrator::getTerminationReasonString(
                                         integrator_->getTerminationReason()) +
                                     ")");
        }
        return state;
    }
    Instance& instance() { return *instance_; }
    int steps() const { return integrator_->getNumStepsTaken(); }

private:
    std::unique_ptr<Instance> instance_;
    std::unique_ptr<SimTK::Integrator> integrator_;
    SimTK::TimeStepper stepper_;
    double finalTime_;
    double fixedStep_;  // s, or 0 for a run with error control
    bool ownSteps_;
};

std::string againstOf(const LongRunView& view, const Setting& s) {
    return view.trajectory == TrajectoryCheck::reference ? "the reference" : describeStepping(s.tighter);
}

/// One setting to the final time: the energy's drift and the trajectory's digits at each sample time, a progress
/// line every few seconds. What Simbody throws stops the run, said in one line with where it stopped.
SettingRun runSetting(const std::string& lab, const Subject& subject, const LongRunView& view, const Setting& s) {
    SettingRun out;
    out.setting = s;
    const Clock::time_point began = Clock::now();
    Clock::time_point told = began;
    double reached = 0;
    try {
        Stepped run(subject, s.run, true);
        // The tighter run's fixed steps end where the run's do (half the step), so it too is read at its own step
        // ends; an error-controlled one is stepped to the run's step ends exactly.
        std::unique_ptr<Stepped> tighter;
        if (view.trajectory == TrajectoryCheck::tighterRun) {
            tighter = std::make_unique<Stepped>(subject, s.tighter, takesFixedSteps(s.tighter));
        }
        const double start = run.instance().conserved(run.to(0));
        for (const double t : sampleTimes(subject.finalTime, s.run)) {
            const SimTK::State& state = run.to(t);
            reached = state.getTime();
            Sample sample;
            sample.asked = t;
            sample.time = reached;
            const double change = std::abs(run.instance().conserved(state) - start);
            if (!std::isfinite(change)) throw std::runtime_error("the energy is not finite");
            sample.drift = relativeDrift(change, subject.conservedScale);
            sample.largest = std::max(sample.drift, out.samples.empty() ? 0.0 : out.samples.back().largest);
            sample.digits = tighter ? run.instance().agreementDigits(state, tighter->to(reached))
                                    : run.instance().digits(state);
            out.samples.push_back(sample);
            out.steps = run.steps();
            if (Clock::now() - told > std::chrono::duration<double>(kProgressSeconds)) {
                // The time left at the pace so far: a setting's work (its steps, its tighter run's or the reference's)
                // grows in proportion to the time simulated.
                told = Clock::now();
                const double elapsed = std::chrono::duration<double>(told - began).count();
                std::fprintf(stderr, "  %s: %s: t = %.4g s of %g s, about %s left\n", lab.c_str(),
                             describeRun(s.run).c_str(), reached, subject.finalTime,
                             durationText(elapsed * (subject.finalTime - reached) / reached).c_str());
            }
        }
    } catch (const std::exception& e) {
        char where[64];
        std::snprintf(where, sizeof where, "stopped after t = %.4g s: ", reached);
        out.failure = where + oneLineMessage(e.what(), 200);
    }
    out.seconds = std::chrono::duration<double>(Clock::now() - began).count();
    std::fprintf(stderr, "  %s: %s: %s in %.1f s (%d steps)\n", lab.c_str(), describeRun(s.run).c_str(),
                 out.failure.empty() ? "done" : "stopped short", out.seconds, out.steps);
    return out;
}

/// The sample taken for time `t` (s), or nullptr where the run did not get there.
const Sample* sampleAt(const SettingRun& r, double t) {
    for (const Sample& s : r.samples) {
        if (std::abs(s.asked - t) <= 1e-9 * t) return &s;
    }
    return nullptr;
}

/// The first sample at which the trajectory keeps less than 1 digit, or nullptr.
const Sample* trajectoryLost(const SettingRun& r) {
    for (const Sample& s : r.samples) {
        if (s.digits < 1) return &s;
    }
    return nullptr;
}

/// The times the table reads the drift at: each decade from 1 s up to the final time, and the final time.
std::vector<double> tableTimes(double finalTime) {
    std::vector<double> times;
    for (double t = 1; t < finalTime * (1 - 1e-9); t *= 10) times.push_back(t);
    times.push_back(finalTime);
    return times;
}

void printTable(const std::string& lab, const Subject& subject, const LongRunView& view,
                const std::vector<SettingRun>& runs, double referenceDigits) {
    const std::vector<double> times = tableTimes(subject.finalTime);
    std::printf("\n%s, %s, to %g s\n", lab.c_str(), view.scene.c_str(), subject.finalTime);
    std::printf("  energy drift: |E(t) - E(0)| / scale, the largest at the samples up to t; %s\n",
                subject.conservedName.c_str());
    if (view.trajectory == TrajectoryCheck::reference) {
        std::printf("  trajectory: %s, against %s (itself good to %.1f digits at %g s)\n", subject.figure.c_str(),
                    subject.reference.c_str(), std::floor(referenceDigits * 10) / 10, subject.finalTime);
    } else {
        std::printf("  trajectory: %s, against the same method run tighter (the column 'against')\n",
                    subject.figure.c_str());
    }
    std::printf("  %-46s", "setting");
    for (const double t : times) {
        char head[32];
        std::snprintf(head, sizeof head, "drift %g s", t);
        std::printf(" %11s", head);
    }
    std::printf("  %-22s %-37s %8s\n", "trajectory < 1 digit", "against", "run (s)");
    std::vector<const SettingRun*> failed;
    for (const SettingRun& r : runs) {
        std::printf("  %-46s", describeRun(r.setting.run).c_str());
        for (const double t : times) {
            const Sample* s = sampleAt(r, t);
            if (s && std::isfinite(s->largest)) std::printf(" %11.1e", s->largest);
            else if (s) std::printf(" %11s", "no scale");
            else std::printf(" %11s", "not reached");
        }
        char lost[64];
        if (const Sample* s = trajectoryLost(r)) {
            std::snprintf(lost, sizeof lost, "by %.3g s", s->asked);
        } else if (!r.samples.empty()) {
            std::snprintf(lost, sizeof lost, "kept (%.1f at %g s)", r.samples.back().digits, r.samples.back().asked);
        } else {
            std::snprintf(lost, sizeof lost, "no sample");
        }
        std::printf("  %-22s %-37s %8.1f\n", lost, againstOf(view, r.setting).c_str(), r.seconds);
        if (!r.failure.empty()) failed.push_back(&r);
    }
    std::printf("  'by T': the first sample time (%d a decade from %g s) with under 1 digit left. A sample is the "
                "state at the run's first own step end at or after its time: sampling cuts no step.\n",
                kPerDecade, kFirstSample);
    for (const SettingRun* r : failed) {
        std::printf("  %s %s\n", describeRun(r->setting.run).c_str(), r->failure.c_str());
    }
}

/// DIR/<lab>-long-run.csv: a row per sample of each setting. Its texts are the course's own words (integrator
/// names and settings): none needs quoting.
void writeCsv(const fs::path& path, const std::string& lab, const LongRunView& view,
              const std::vector<SettingRun>& runs) {
    const fs::path partial = path.string() + ".partial";
    {
        std::ofstream out(partial);
        out << "lab,integrator,stepping,trajectory_against,t_s,energy_drift,energy_drift_largest,trajectory_digits,"
               "step_end_s\n";
        char line[160];
        for (const SettingRun& r : runs) {
            for (const Sample& s : r.samples) {
                std::snprintf(line, sizeof line, "%.10g,%.4g,%.4g,%.3f,%.10g\n", s.asked, s.drift, s.largest, s.digits,
                              s.time);
                out << lab << ',' << r.setting.run.integrator << ',' << describeStepping(r.setting.run) << ','
                    << againstOf(view, r.setting) << ',' << line;
            }
        }
        if (!out.flush()) throw std::runtime_error("cannot write " + path.string());
    }
    fs::rename(partial, path);
}

/// DIR/<lab>-long-run.svg: the energy's drift over the trajectory's error, both against time on log-log axes.
void drawFigure(const fs::path& path, const std::string& lab, const Subject& subject, const LongRunView& view,
                const std::vector<SettingRun>& runs) {
    Plot plot;
    char title[256];
    std::snprintf(title, sizeof title, "%s, %s: energy digits are not trajectory digits (%g s)", lab.c_str(),
                  view.scene.c_str(), subject.finalTime);
    plot.title = title;
    PlotPanel energy("t (s)", "energy drift |E(t) - E(0)| / scale (drawn at least 1e-16)");
    const std::string against = view.trajectory == TrajectoryCheck::reference
                                    ? "error against the reference"
                                    : "difference from the tighter run";
    PlotPanel trajectory("t (s)", "trajectory " + against + " (10^-digits)");
    for (PlotPanel* panel : {&energy, &trajectory}) panel->logX = panel->logY = true;
    for (const SettingRun& r : runs) {
        PlotCurve e(describeRun(r.setting.run)), d(describeRun(r.setting.run) + " against " + againstOf(view, r.setting));
        e.dashed = d.dashed = takesFixedSteps(r.setting.run);
        for (const Sample& s : r.samples) {
            e.x.push_back(s.time);
            e.y.push_back(std::max(s.drift, kDriftFloor));
            d.x.push_back(s.time);
            d.y.push_back(std::pow(10.0, -s.digits));
        }
        energy.curves.push_back(e);
        trajectory.curves.push_back(d);
    }
    plot.panels = {energy, trajectory};
    drawPlot(plot, path.string());
}

}  // namespace

bool asksForLongRun(int argc, char** argv) { return argc > 1 && std::strcmp(argv[1], "long-run") == 0; }

int longRunMain(int argc, char** argv, const std::string& lab, const LongRunView& view) {
    simlab::useReproducibleMath(argv);
    double finalTime = 1000;
    bool quick = false, plots = true;
    std::string output = "long-run";
    CLI::App app{"The long-run view of the " + lab + " lab (run it with `simlab study long-run " + lab + "`).",
                 lab + "-study long-run"};
    app.add_option("--final-time", finalTime, "s, how long each setting runs")
        ->check(between(1.0, 1e5))
        ->capture_default_str();
    app.add_flag("--quick", quick, "a short final time (seconds of work), unless --final-time is given");
    app.add_option("--output,-o", output, "folder for the CSV and the figure")->capture_default_str();
    app.add_flag("!--no-plots", plots, "the CSV and the table only");
    try {
        app.parse(argc - 1, argv + 1);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;
    }
    if (quick && app.count("--final-time") == 0) finalTime = view.quickFinalTime;
    const std::string name = lab + "-study long-run";
    try {
        const Subject subject = view.subject(finalTime);
        const fs::path dir = fs::absolute(output);
        fs::create_directories(dir);
        std::vector<SettingRun> runs;
        std::fprintf(stderr, "%s: %s to %g s, %d samples a decade from %g s\n", lab.c_str(), view.scene.c_str(),
                     finalTime, kPerDecade, kFirstSample);
        // The reference's own accuracy at the final time (a looser run's agreement with it), where it is the judge.
        double referenceDigits = 0;
        if (view.trajectory == TrajectoryCheck::reference && subject.referenceDigits) {
            std::fprintf(stderr, "  %s: the reference's own accuracy at %g s (%s, and again looser)\n", lab.c_str(),
                         finalTime, subject.reference.c_str());
            referenceDigits = subject.referenceDigits();
        }
        for (const Setting& s : settingsOf(view)) runs.push_back(runSetting(lab, subject, view, s));
        printTable(lab, subject, view, runs, referenceDigits);
        const fs::path csv = dir / (lab + "-long-run.csv"), svg = dir / (lab + "-long-run.svg");
        writeCsv(csv, lab, view, runs);
        if (plots) drawFigure(svg, lab, subject, view, runs);
        std::printf("\nWritten to %s: %s%s\n", dir.string().c_str(), csv.filename().string().c_str(),
                    plots ? (", " + svg.filename().string() + " (energy drift over trajectory error)").c_str() : "");
        for (const SettingRun& r : runs) {
            if (!r.failure.empty()) return 1;
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: %s\n", name.c_str(), oneLineMessage(e.what(), 200).c_str());
        return 1;
    }
    return 0;
}

}  // namespace simlab::study
