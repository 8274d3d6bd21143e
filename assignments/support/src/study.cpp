#include "simlab/study.h"

#include "simlab/cli_checks.h"

#include <fcntl.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "simlab/integrators.h"
#include "simlab/measured_run.h"
#include "simlab/messages.h"
#include "simlab/model_info.h"
#include "simlab/reproducible_math.h"
#include "simlab/trade_question.h"

namespace simlab::study {

namespace {

using Clock = std::chrono::steady_clock;

struct Settings {
    bool quick = false;
    /// The cost cap, in evaluations of the equations of motion: a count, so that which points pass it is the same
    /// on every machine, however busy.
    double maxEvaluations = 5e5;
    /// s of CPU time: a net for one point's measured run, never a measure of cost (a point it stops is
    /// "failed", and says so). Which points are too costly is decided by maxEvaluations alone.
    double cap = 600;
    int repeats = 3;   ///< timed runs per point; the fastest is kept
    /// --quick (without --repeats): no timed run; a point's seconds are those its measured run's own steps took,
    /// timed once, the checks against the reference between them left out.
    bool timeMeasuredRun = false;
    std::string subject;
    std::vector<std::string> integrators;  ///< only these (empty: every one)
    bool fixedStepsOnly = false;           ///< only the fixed-step sweeps
    int sweep = -1;                        ///< only this sweep of the study (-1: all of them)
    /// The digits a question asks for (0: none): a point short of them from its first start answers nothing, since
    /// the other starts can only lower its worst; it is measured from that start alone.
    double answerDigits = 0;
};

/// One point of the study: an integrator at an accuracy, or at a fixed step.
struct Point {
    std::string integrator;
    std::string mode;  ///< "accuracy" or "fixed step"
    double accuracy = 0;  ///< for a fixed step too (kFixedStepAccuracy)
    double step = 0;   ///< s, for "fixed step"
    bool namesAccuracy = true;  ///< a fixed step whose figures read the accuracy (Verlet's; any, with events)
};

/// The accuracy of the fixed-step sweeps: Simbody's default, which the study has always run them at, so that the
/// trade questions' fronts stay what they were measured to be. Verlet solves its implicit velocity update to it
/// (simlab::fixedStepUsesAccuracy), and events are localized by it at any step: where it counts, the tables name it.
constexpr double kFixedStepAccuracy = 1e-3;

/// What a point measured. A figure the point did not measure is NaN, an empty cell in trade.csv: a point not run
/// reached no time, and a run that did not reach the final time has no final digits.
struct Outcome {
    std::string status = "ok";  ///< ok, too costly, failed, blew up, no error control
    std::string message;
    double reached = NAN;      ///< s of simulated time
    double finalDigits = NAN;  ///< at the final time, for a run that got there
    double worstDigits = NAN;  ///< the fewest over the steps it took (up to `reached`)
    double drift = NAN;        ///< largest |conserved - its start| / the subject's scale, over the same steps
    int stepsTaken = 0, stepsAttempted = 0, evaluations = 0;
    double seconds = NAN;      ///< fastest timed repeat (timeMeasuredRun: the measured run's)
    double measuredSeconds = NAN;  ///< the measured run's (first start's) own steps, its checks left out
    int repeats = 0;
};

/// Silences stderr while it lives: CPodes prints its complaints there before it throws (the throw says it in
/// one line).
class QuietStderr {
public:
    QuietStderr() {
        std::fflush(stderr);
        saved_ = dup(2);
        const int null = open("/dev/null", O_WRONLY);
        if (null >= 0) {
            dup2(null, 2);
            close(null);
        }
    }
    ~QuietStderr() {
        std::fflush(stderr);
        if (saved_ >= 0) {
            dup2(saved_, 2);
            close(saved_);
        }
    }
    QuietStderr(const QuietStderr&) = delete;
    QuietStderr& operator=(const QuietStderr&) = delete;

private:
    int saved_ = -1;
};

/// The run settings a point stands for.
simlab::RunSettings choiceOf(const Point& p) {
    simlab::RunSettings choice;
    choice.integrator = p.integrator;
    choice.fixedStep = p.mode == "fixed step";
    if (choice.fixedStep) choice.dt = p.step;
    if (p.accuracy > 0) choice.accuracy = p.accuracy;
    return choice;
}

/// The measured run (simlab/measured_run.h): the error at the integrator's own steps (at most about a thousand
/// of them, spread evenly in time, since the reference costs as much as a step), under the cap.
void measure(const Subject& subject, const Point& point, const Settings& settings, Outcome& out) {
    std::unique_ptr<Instance> instance = subject.make();
    std::unique_ptr<SimTK::Integrator> integrator =
        simlab::integratorFor(choiceOf(point), instance->system(), subject.finalTime);
    bool first = true;
    double start = 0;
    simlab::MeasureLimits limits;
    limits.maxEvaluations = settings.maxEvaluations;
    limits.cpuSeconds = settings.cap;
    const simlab::RunSettings choice = choiceOf(point);
    const simlab::MeasuredRun run = simlab::measureRun(
        instance->system(), *integrator, instance->initial(), subject.finalTime, limits,
        [&](const SimTK::State& state, bool last) {
            out.worstDigits = first ? instance->digits(state) : std::min(out.worstDigits, instance->digits(state));
            if (first) start = instance->conserved(state);
            const double drift = relativeDrift(std::abs(instance->conserved(state) - start), subject.conservedScale);
            out.drift = first ? 0.0 : std::max(out.drift, std::isfinite(drift) ? drift : INFINITY);
            first = false;
            if (last) out.finalDigits = instance->finalDigits(state);
        },
        simlab::takesFixedSteps(choice) ? choice.dt : 0.0);
    out.reached = run.reached;
    out.status = run.status;
    out.message = run.message;
    if (run.status != "ok") out.finalDigits = NAN;  // it stopped short of the final time
    if (run.status == "blew up" || run.status == "failed") return;
    out.stepsTaken = run.integrator.stepsTaken;
    out.stepsAttempted = run.integrator.stepsAttempted;
    out.evaluations = run.integrator.realizations;
    out.measuredSeconds = run.stepSeconds;
}

/// Points dearer than this are timed once: their one run is long enough to time.
constexpr int kOneRepeatEvaluations = 100000;

/// Seconds one run of `point` takes to the final time, reporting only there. Building the model is not timed.
double timedRun(const Subject& subject, const Point& point) {
    std::unique_ptr<Instance> instance = subject.make();
    std::unique_ptr<SimTK::Integrator> integrator =
        simlab::integratorFor(choiceOf(point), instance->system(), subject.finalTime);
    SimTK::TimeStepper stepper(instance->system(), *integrator);
    const simlab::RunSettings choice = choiceOf(point);
    const double fixedStep = simlab::takesFixedSteps(choice) ? choice.dt : 0.0;
    const Clock::time_point began = Clock::now();
    stepper.initialize(instance->initial());
    while (!integrator->isSimulationOver() && stepper.getState().getTime() < subject.finalTime) {
        stepper.stepTo(simlab::nextStepEnd(fixedStep, subject.finalTime, stepper.getState().getTime()));
    }
    return std::chrono::duration<double>(Clock::now() - began).count();
}

/// The timed repeats: reporting only at the end; the fastest is kept. How many is decided by the point's
/// evaluations, never by the clock, so that trade.csv's columns but the seconds are the same on every machine.
void timeRepeats(const Subject& subject, const Point& point, const Settings& settings, Outcome& out) {
    const int repeats = out.evaluations > kOneRepeatEvaluations ? 1 : settings.repeats;
    for (int r = 0; r < repeats; ++r) {
        const double seconds = timedRun(subject, point);
        out.seconds = std::isnan(out.seconds) ? seconds : std::min(out.seconds, seconds);
        out.repeats = r + 1;
    }
}

/// `other`, the same point from another start, folded into `out` at the worse of the two: the fewest digits, the
/// most drift, steps and evaluations, the shortest reach, and the first failure.
void keepWorst(Outcome& out, const Outcome& other, std::size_t start) {
    if (out.status == "ok" && other.status != "ok") {
        out.status = other.status;
        out.message = "from start " + std::to_string(start + 1) + ": " + other.message;
    }
    auto least = [](double a, double b) { return std::isnan(a) || std::isnan(b) ? NAN : std::min(a, b); };
    out.worstDigits = least(out.worstDigits, other.worstDigits);
    out.finalDigits = least(out.finalDigits, other.finalDigits);
    out.reached = least(out.reached, other.reached);
    out.drift = std::isnan(other.drift) ? out.drift : std::max(out.drift, other.drift);
    out.stepsTaken = std::max(out.stepsTaken, other.stepsTaken);
    out.stepsAttempted = std::max(out.stepsAttempted, other.stepsAttempted);
    out.evaluations = std::max(out.evaluations, other.evaluations);
}

/// A point measured (from every start of its subject, kept at its worst) and, if it ran to the end, timed from
/// the first; whatever it throws is its outcome, in one line.
void measureAndTime(const Subject& subject, const Point& point, const Settings& settings, Outcome& out) {
    try {
        QuietStderr quiet;
        measure(subject, point, settings, out);
        const bool noAnswer = settings.answerDigits > 0 && out.status == "ok" && !(out.worstDigits >= settings.answerDigits);
        if (noAnswer && !subject.moreStarts.empty()) {
            char digits[32];
            std::snprintf(digits, sizeof digits, "%g", settings.answerDigits);
            out.message = std::string("short of ") + digits + " digits from the first start, so no answer: measured "
                          "from that start alone";
        }
        for (std::size_t k = 0; k < subject.moreStarts.size() && out.status == "ok" && !noAnswer; ++k) {
            Subject from = subject;
            from.make = subject.moreStarts[k];
            Outcome other;
            measure(from, point, settings, other);
            keepWorst(out, other, k + 1);
        }
        if (out.status == "ok" && settings.timeMeasuredRun) {
            out.seconds = out.measuredSeconds;
            out.repeats = 1;
        } else if (out.status == "ok") {
            timeRepeats(subject, point, settings, out);
        }
    } catch (const std::exception& e) {
        out.status = "failed";
        out.message = simlab::oneLineMessage(e.what(), 200);
    }
}

nlohmann::json number(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(); }

nlohmann::json toJson(const Subject& s, const Point& p, const Outcome& o) {
    return {{"type", "point"},         {"subject", s.name},
            {"integrator", p.integrator}, {"mode", p.mode},
            {"accuracy", number(p.namesAccuracy ? p.accuracy : 0.0)}, {"step", number(p.step)},
            {"status", o.status},       {"message", o.message},
            {"reached", number(o.reached)}, {"final_digits", number(o.finalDigits)},
            {"worst_digits", number(o.worstDigits)}, {"drift", number(o.drift)},
            {"steps_taken", o.stepsTaken}, {"steps_attempted", o.stepsAttempted},
            {"evaluations", o.evaluations}, {"seconds", number(o.seconds)},
            {"repeats", o.repeats}};
}

/// The study's points in the order it measures and prints them: each integrator's accuracies, then each one's fixed
/// steps.
std::vector<Point> pointsOf(const Subject& subject, const Settings& settings) {
    std::vector<std::string> names;
    for (const std::string& name : integratorNames()) {
        if (settings.integrators.empty() ||
            std::find(settings.integrators.begin(), settings.integrators.end(), name) != settings.integrators.end()) {
            names.push_back(name);
        }
    }
    std::vector<Point> points;
    for (const std::string& name : names) {
        if (settings.fixedStepsOnly) break;
        for (int exponent = 1; exponent <= 14; ++exponent) {
            points.push_back({name, "accuracy", std::pow(10.0, -exponent), 0, true});
        }
    }
    // Steps from a tenth of the run down, by half decades (whole decades with --quick).
    const std::vector<double> fractions = settings.quick ? std::vector<double>{1e-1, 1e-2, 1e-3, 1e-4}
                                                         : std::vector<double>{1e-1, 3e-2, 1e-2, 3e-3, 1e-3,
                                                                               3e-4, 1e-4, 3e-5};
    for (const std::string& name : names) {
        if (name == "CPodes") continue;  // a multistep method: its steps are its own
        const bool names = subject.events || fixedStepUsesAccuracy(name);
        for (const double f : fractions) {
            points.push_back({name, "fixed step", kFixedStepAccuracy, f * subject.finalTime, names});
        }
    }
    return points;
}

/// A timed batch lasts at least this long, s: runs of a millisecond are timed in batches, since the clock and the
/// scheduler blur one of them by more than the difference being measured.
constexpr double kBatchSeconds = 0.02;
/// Rounds of batches per repeat asked for: the fastest of many short batches finds the machine at its quietest.
/// A run longer than a batch gets fewer rounds, as many as fit in the time of those (at least `repeats`).
constexpr int kRoundsPerRepeat = 5;

/// A point to be timed in batches beside others.
struct Batched {
    const Subject* subject;
    Point point;
    Outcome* out;
    int batch = 1;   ///< runs per batch, enough for kBatchSeconds
    int rounds = 1;  ///< batches timed
};

/// Seconds per run of each of `points`, timed A B A B: a run of each (warm: their measured runs came first) sets
/// its batch, then rounds of batches time each in turn, so that a machine that slows down slows all of them
/// alike; each keeps its fastest batch's seconds per run. Sets `out.seconds` and `out.repeats` (runs timed).
void timeInterleaved(std::vector<Batched>& points, int repeats) {
    int rounds = 0;
    for (Batched& b : points) {
        const double first = timedRun(*b.subject, b.point);
        b.batch = static_cast<int>(std::clamp(std::ceil(kBatchSeconds / std::max(first, 1e-9)), 1.0, 1e5));
        // As many rounds as a short run gets, but no more time than its rounds take: at least `repeats`.
        const double share = kRoundsPerRepeat * repeats * std::min(1.0, kBatchSeconds / std::max(first, 1e-9));
        b.rounds = std::max(repeats, static_cast<int>(std::ceil(share)));
        rounds = std::max(rounds, b.rounds);
        b.out->repeats = 1;
        b.out->seconds = b.batch == 1 ? first : NAN;
    }
    for (int r = 0; r < rounds; ++r) {
        for (Batched& b : points) {
            if (r >= b.rounds) continue;
            double total = 0;
            for (int k = 0; k < b.batch; ++k) total += timedRun(*b.subject, b.point);
            b.out->repeats += b.batch;
            b.out->seconds = std::isnan(b.out->seconds) ? total / b.batch : std::min(b.out->seconds, total / b.batch);
        }
    }
}

/// The accuracies `study minimal` sweeps: half decades from 1e-1 to 1e-12, enough points to read each model's
/// cost at any digits between its ends.
std::vector<double> minimalAccuracies() {
    std::vector<double> accuracies;
    for (int half = 2; half <= 24; ++half) accuracies.push_back(std::pow(10.0, -0.5 * half));
    return accuracies;
}

/// The same scene with its minimal mobilizers and over-modelled, each model's work-precision curve with the labs'
/// integrator: digits kept all the way, evaluations and seconds per run at each accuracy. simlab reads the two
/// curves at equal digits.
void runMinimal(const std::string& lab, const Subject& subject, const Settings& settings) {
    if (!subject.makeOverModelled) return;
    static const bool progress = isatty(2) || std::getenv("SIMLAB_PROGRESS") != nullptr;
    struct Model {
        Subject subject;
        std::string name;
        int dof = 0, coordinates = 0, ok = 0;
        double best = -INFINITY;
    };
    std::array<Model, 2> models;
    for (const bool over : {false, true}) {
        Model& m = models[over];
        m.subject = subject;
        if (over) m.subject.make = subject.makeOverModelled;
        m.name = over ? subject.overModelled : subject.minimal;
        try {
            const std::unique_ptr<Instance> instance = m.subject.make();
            // Degrees of freedom: the mobilities less the constraints that hold some of them back.
            m.dof = simlab::describeModel(instance->system().getMatterSubsystem(), instance->initial())
                        .degreesOfFreedom();
            m.coordinates = instance->initial().getNQ();
        } catch (const std::exception&) {
            // the measured run says what went wrong
        }
    }
    const std::vector<double> accuracies = minimalAccuracies();
    if (progress) {
        std::cerr << "  " << subject.name << ": " << models[0].name << " and " << models[1].name << " at "
                  << accuracies.size() << " accuracies, timed in alternating batches of at least " << kBatchSeconds
                  << " s\n";
    }
    Clock::time_point told = Clock::now();
    for (std::size_t i = 0; i < accuracies.size(); ++i) {
        const Point point{"RungeKuttaMerson", "accuracy", accuracies[i], 0};
        std::array<Outcome, 2> outs;
        std::vector<Batched> timed;
        for (const bool over : {false, true}) {
            try {
                QuietStderr quiet;
                measure(models[over].subject, point, settings, outs[over]);
                if (outs[over].status == "ok") timed.push_back({&models[over].subject, point, &outs[over]});
            } catch (const std::exception& e) {
                outs[over].status = "failed";
                outs[over].message = simlab::oneLineMessage(e.what(), 200);
            }
        }
        try {
            QuietStderr quiet;
            timeInterleaved(timed, settings.repeats);
        } catch (const std::exception& e) {
            for (Batched& b : timed) {
                b.out->status = "failed";
                b.out->message = simlab::oneLineMessage(e.what(), 200);
            }
        }
        for (const bool over : {false, true}) {
            Model& m = models[over];
            if (outs[over].status == "ok") {
                ++m.ok;
                m.best = std::max(m.best, outs[over].worstDigits);
            }
            nlohmann::json j = toJson(m.subject, point, outs[over]);
            j["type"] = "minimal";
            j["lab"] = lab;
            j["model"] = m.name;
            j["over_modelled"] = over;
            j["dof"] = m.dof;
            j["coordinates"] = m.coordinates;
            std::cout << j.dump() << std::endl;
        }
        // A line every few seconds, so that a long sweep is never silent for long.
        if (progress && i + 1 < accuracies.size() && Clock::now() - told > std::chrono::seconds(3)) {
            told = Clock::now();
            std::cerr << "  " << subject.name << ": " << i + 1 << " of " << accuracies.size() << " accuracies done (to "
                      << accuracies[i] << ")\n";
        }
    }
    if (progress) {
        for (const Model& m : models) {
            std::cerr << "  " << subject.name << ", " << m.name << ": " << m.ok << " of " << accuracies.size() << " ok";
            if (std::isfinite(m.best)) std::cerr << "; best " << std::fixed << std::setprecision(1) << m.best << " digits";
            std::cerr << std::defaultfloat << '\n';
        }
    }
}

/// A scene's study as one run measures it: its points in order, and where each sweep (an integrator's accuracies,
/// or its fixed steps) begins.
struct Plan {
    std::vector<Point> points;
    std::vector<std::size_t> sweeps;
};

Plan planOf(const Subject& subject, const Settings& settings) {
    Plan plan{pointsOf(subject, settings), {}};
    for (std::size_t i = 0; i < plan.points.size(); ++i) {
        const std::vector<Point>& p = plan.points;
        if (i == 0 || p[i].integrator != p[i - 1].integrator || p[i].mode != p[i - 1].mode) plan.sweeps.push_back(i);
    }
    if (settings.sweep >= 0 && static_cast<std::size_t>(settings.sweep) >= plan.sweeps.size()) {
        throw std::runtime_error("--sweep " + std::to_string(settings.sweep) + ": the study has only " +
                                 std::to_string(plan.sweeps.size()) + " sweeps (0 to " +
                                 std::to_string(plan.sweeps.size() - 1) + ")");
    }
    return plan;
}

/// The subject line, which counts the whole study's points and sweeps, whichever sweep this run measures. The
/// model is built first: one that cannot be (a SIMLAB_TODO, say) stops the study here, saying why.
void printSubject(const std::string& lab, const Subject& subject, const Settings& settings, const Plan& plan) {
    subject.make();
    const double referenceDigits = subject.referenceDigits();
    std::cout << nlohmann::json{{"type", "subject"},       {"lab", lab},
                                {"subject", subject.name}, {"figure", subject.figure},
                                {"final_figure", subject.finalFigure},
                                {"conserved", subject.conservedName}, {"final_time", subject.finalTime},
                                {"reference", subject.reference},     {"reference_digits", number(referenceDigits)},
                                {"cap", settings.cap},     {"max_evaluations", settings.maxEvaluations},
                                {"repeats", settings.repeats},
                                {"timing", settings.timeMeasuredRun ? "measured run" : "repeats"},
                                {"starts", 1 + subject.moreStarts.size()},
                                {"points", plan.points.size()}, {"sweeps", plan.sweeps.size()}}
                     .dump()
              << std::endl;
}

/// The points of `plan` this run measures (all, or --sweep's), one line each.
void runSubject(const Subject& subject, const Settings& settings, const Plan& plan) {
    std::vector<Point> points = plan.points;
    const std::size_t total = points.size();
    if (settings.sweep >= 0) {
        const auto k = static_cast<std::size_t>(settings.sweep);
        const std::size_t end = k + 1 < plan.sweeps.size() ? plan.sweeps[k + 1] : points.size();
        points = std::vector<Point>(points.begin() + static_cast<std::ptrdiff_t>(plan.sweeps[k]),
                                    points.begin() + static_cast<std::ptrdiff_t>(end));
    }
    // Progress, for a person watching: on a terminal, or where simlab asks for it (SIMLAB_PROGRESS=1: it shows
    // what is not a JSON line), so that a log or a pipe holds only the results. A line as the study starts, and
    // one as each integrator's sweep of accuracies or of fixed steps ends.
    static const bool progress = isatty(2) || std::getenv("SIMLAB_PROGRESS") != nullptr;
    if (progress && settings.sweep <= 0) {
        std::cerr << "  " << subject.name << ": " << total << " points, each under "
                  << settings.maxEvaluations << " evaluations (and " << settings.cap << " s of CPU time)\n";
    }
    struct Sweep {
        std::string key;
        int points = 0, ok = 0, costly = 0;
        std::vector<std::string> failures;  // "1e-13: blew up", a point each
        double best = -INFINITY;
        long evaluations = 0;
    } sweep;
    auto tell = [&] {
        if (!progress || sweep.points == 0) return;
        std::ostringstream line;
        line << "  " << subject.name << ": " << sweep.key << ": " << sweep.ok << " of " << sweep.points << " ok";
        if (sweep.costly) line << ", " << sweep.costly << " too costly";
        if (!sweep.failures.empty()) {
            line << ", " << sweep.failures.size() << " failed or blew up (";
            for (std::size_t i = 0; i < sweep.failures.size(); ++i) line << (i ? "; " : "") << sweep.failures[i];
            line << ")";
        }
        if (std::isfinite(sweep.best)) line << "; best " << std::fixed << std::setprecision(1) << sweep.best << " digits";
        line << "; " << sweep.evaluations << " evaluations in all\n";
        std::cerr << line.str();
    };
    // A point that passed the cap makes every tighter point of the same integrator and mode dearer still: they
    // are recorded as too costly, not run.
    std::string costlyKey, costlyMessage;
    for (const Point& point : points) {
        Outcome out;
        const std::string key = point.integrator + "/" + point.mode;
        if (point.mode == "accuracy" && !hasErrorControl(point.integrator)) {
            out.status = "no error control";
            out.message = point.integrator + " takes fixed steps whatever the accuracy: see its step sweep";
        } else if (key == costlyKey) {
            out.status = "too costly";
            out.message = "not run: " + costlyMessage;
        } else {
            measureAndTime(subject, point, settings, out);
            if (out.status == "too costly") {
                costlyKey = key;
                costlyMessage = point.mode == "accuracy" ? "a looser accuracy already passed the cap"
                                                         : "a longer step already passed the cap";
            }
        }
        std::cout << toJson(subject, point, out).dump() << std::endl;
        const std::string sweepKey = point.integrator + (point.mode == "accuracy" ? " at accuracies 1e-1 to 1e-14"
                                                                                   : " at fixed steps");
        if (sweepKey != sweep.key) {
            tell();
            sweep = Sweep();
            sweep.key = sweepKey;
        }
        if (out.status == "no error control") continue;
        ++sweep.points;
        if (out.status == "ok") {
            ++sweep.ok;
            sweep.best = std::max(sweep.best, out.finalDigits);
        } else if (out.status == "too costly") {
            ++sweep.costly;
        } else {
            char setting[32];
            std::snprintf(setting, sizeof setting, "%g", point.mode == "accuracy" ? point.accuracy : point.step);
            sweep.failures.push_back(std::string(setting) + (point.mode == "accuracy" ? "" : " s") + ": " + out.status);
        }
        sweep.evaluations += out.evaluations;
    }
    tell();
}

}  // namespace

int studyMain(int argc, char** argv, const std::string& lab, const std::vector<Subject>& subjects,
              const SubjectForScene& forScene) {
    simlab::useReproducibleMath(argv);
    Settings settings;
    bool list = false, minimal = false;
    std::string sceneText, sceneName = "scene", nudge;
    double finalTime = 0;
    int starts = 1;
    CLI::App app{"The work-precision study of the " + lab + " lab's scenes, one JSON object per line (run it with "
                 "`simlab study trade " + lab + "`).", lab + "-study"};
    app.set_version_flag("--version", lab + "-study (simlab " SIMLAB_VERSION ")", "print the program's version and exit");
    app.add_flag("--quick", settings.quick,
                 "fewer step sizes, a cap of 1e5 evaluations, and each point timed once, on its measured run (no "
                 "timed runs unless --repeats is given)");
    app.add_option("--max-evaluations", settings.maxEvaluations, "the cost cap: evaluations one point may take")
        ->check(between(100.0, 1e9))
        ->capture_default_str();
    app.add_option("--cap", settings.cap,
                   "seconds of CPU time a point may take: a net for a run that would not end (a point it stops is "
                   "failed, and says so), never the cost cap")
        ->check(between(0.01, 3600.0))
        ->capture_default_str();
    app.add_option("--repeats", settings.repeats, "timed runs per point; the fastest is kept")
        ->check(CLI::Range(1, 100))
        ->capture_default_str();
    app.add_option("--subject", settings.subject, "only this scene");
    app.add_flag("--list", list, "list the scenes and stop");
    app.add_flag("--minimal", minimal, "each scene with its minimal mobilizers and over-modelled, side by side");
    app.add_option("--integrators", settings.integrators, "only these integrators")->delimiter(',');
    app.add_flag("--fixed-steps-only", settings.fixedStepsOnly, "only the sweeps of fixed steps");
    app.add_option("--sweep", settings.sweep,
                   "measure only this sweep (0, 1, ...): one integrator's accuracies or its fixed steps, in the order "
                   "the study prints them; the subject line counts the whole study's points and sweeps")
        ->check(CLI::Range(0, 1000));
    if (forScene) {
        CLI::Option* scene = app.add_option("--scene", sceneText,
                                            "study this scene instead (the lab's Scene as JSON, as the trade "
                                            "question's data file holds it)");
        app.add_option("--final-time", finalTime, "with --scene: its final time, s")
            ->check(between(1e-9, 1e6))
            ->needs(scene);
        app.add_option("--name", sceneName, "with --scene: what to call it")->needs(scene);
        app.add_option("--starts", starts,
                       "with --scene: measure each point from this many starts (--nudge moved by 0, 1, ... units in "
                       "its last place) and keep it at its worst")
            ->check(CLI::Range(1, 10))
            ->needs(scene);
        app.add_option("--nudge", nudge, "with --starts: the JSON pointer of the scene's number a start moves")
            ->needs(scene);
        app.add_option("--answer-digits", settings.answerDigits,
                       "with --starts: the digits a question asks for; a point short of them from the first start "
                       "answers nothing and is measured from that start alone")
            ->check(between(0.0, 20.0))
            ->needs(scene);
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;
    }
    for (const std::string& name : settings.integrators) {
        const std::vector<std::string> known = integratorNames();
        if (std::find(known.begin(), known.end(), name) == known.end()) {
            std::cerr << lab << "-study: error: --integrators: no integrator named '" << name << "'\n";
            return 2;
        }
    }
    std::vector<Subject> scenes = subjects;
    if (!sceneText.empty()) {
        try {
            const nlohmann::json scene = nlohmann::json::parse(sceneText);
            if (!(finalTime > 0)) throw std::runtime_error("--scene needs --final-time");
            Subject subject = forScene(scene, finalTime);
            subject.name = sceneName;
            for (int k = 1; k < starts; ++k) {
                subject.moreStarts.push_back(forScene(simlab::trade::nudged(scene, nudge, k), finalTime).make);
            }
            scenes = {subject};
        } catch (const std::exception& e) {
            std::cerr << lab << "-study: error: --scene: " << simlab::oneLineMessage(e.what(), 200) << '\n';
            return 2;
        }
    }
    if (settings.quick) {
        if (app.count("--max-evaluations") == 0) settings.maxEvaluations = 1e5;
        if (app.count("--repeats") == 0) {
            settings.repeats = 1;
            settings.timeMeasuredRun = true;
        }
    }
    if (list) {
        for (const Subject& s : scenes) std::cout << s.name << ": " << s.figure << '\n';
        return 0;
    }
    bool found = settings.subject.empty();
    // A run of one sweep names every scene before it measures any, so that whoever runs the sweeps side by side
    // knows the whole study's points from its first lines; a whole run names each scene as it comes to it.
    std::vector<std::pair<const Subject*, Plan>> named;
    for (const Subject& s : scenes) {
        if (!settings.subject.empty() && s.name != settings.subject) continue;
        found = true;
        try {
            if (minimal) {
                runMinimal(lab, s, settings);
                continue;
            }
            named.emplace_back(&s, planOf(s, settings));
            printSubject(lab, s, settings, named.back().second);
            if (settings.sweep >= 0) continue;
            runSubject(s, settings, named.back().second);
        } catch (const std::exception& e) {
            std::cerr << lab << "-study: error: " << s.name << ": " << simlab::oneLineMessage(e.what(), 200) << '\n';
            return 1;
        }
    }
    for (const auto& [s, plan] : named) {
        if (settings.sweep < 0) break;
        try {
            runSubject(*s, settings, plan);
        } catch (const std::exception& e) {
            std::cerr << lab << "-study: error: " << s->name << ": " << simlab::oneLineMessage(e.what(), 200) << '\n';
            return 1;
        }
    }
    if (!found) {
        std::cerr << lab << "-study: error: no scene named '" << settings.subject << "' (see --list)\n";
        return 2;
    }
    return 0;
}

}  // namespace simlab::study
