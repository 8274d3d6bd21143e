// What every assignment's grader tests share: observing a student's simulation, and the checks that are the
// same from one lab to the next (samples present, the integrator honoured, the degrees of freedom the scene
// needs). Each assignment's tests call these inside their own TEST_CASEs, under their own names. The tests run
// in the judge, which never holds student code: what they know of it, they observe (simlab/observe.h).
#pragma once

#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <optional>
#include <stdexcept>
#include <sstream>
#include <string>
#include <vector>

#include "simlab/digits.h"
#include "simlab/driver.h"
#include "simlab/harness/grading.h"
#include "simlab/harness/observe.h"
#include "simlab/run_settings.h"
#include "simlab/trade_question.h"
#include "simlab/wire_types.h"

namespace simlab::testing {

/// The student's simulation of `scene`, driven as the lab program drives it.
template <class Sample, class Scene>
RunResult<Sample> simulate(const Scene& scene, const RunSettings& settings) {
    return observe::run<Sample>(scene, settings);
}

/// `base` with another final time, sampling interval and accuracy.
inline RunSettings settingsFor(RunSettings base, double finalTime, double dt, double accuracy) {
    base.finalTime = finalTime;
    base.dt = dt;
    base.accuracy = accuracy;
    return base;
}

/// A figure over many points kept at its worst - the fewest accuracy digits, or the largest drift - with the
/// comparison of measured and expected values that had it, which a failing test's reason shows beside the figure
/// (grading::worstPoint): "0.0 digits, need 10: y(4) = +88.4 m, expected -68.4 m".
///
///     WorstDigits worst;
///     for (const Sample& s : run.samples) {
///         const double exact = ...;
///         worst.add(accuracyDigits(s.y, exact), grading::at("y", s.time), s.y, exact, "m");
///     }
///     CHECK(atLeast(worst, grading::param("floor"), grading::param("target"), "digits at the worst sample"));
class WorstPoint {
public:
    /// Keeps `figure` if it is the first or the worst so far (NaN is the worst there is), with the comparison of
    /// `value` and `expected` that gave it: `what` ("y(4)") in `unit`, then `context` ("(dropped from 2.5 m)"), if
    /// any. Returns whether it was.
    bool add(double figure, const std::string& what, double value, double expected, const std::string& unit,
             const std::string& context = "") {
        if (!worse(figure)) return false;
        point_ = grading::compared(what, value, expected, unit) + (context.empty() ? "" : " " + context);
        return true;
    }
    /// add() with the comparison already written (a grading::compared of vectors, say).
    bool add(double figure, const std::string& comparison) {
        if (!worse(figure)) return false;
        point_ = comparison;
        return true;
    }
    /// A figure with no values to compare (nothing was measured: the check that says why is the reason).
    void add(double figure) {
        if (worse(figure)) point_.clear();
    }
    /// Another's worst (one scene's of several), in this one's place if it is worse, with `context` after it.
    void add(const WorstPoint& other, const std::string& context = "") {
        if (!other.any_ || !worse(other.figure_)) return;
        point_ = other.point_.empty() ? "" : other.point_ + (context.empty() ? "" : " " + context);
    }
    /// The worst figure (where nothing was added: kMaxDigits digits, a drift of 0).
    double figure() const { return figure_; }
    /// Its comparison; empty when nothing was added.
    const std::string& point() const { return point_; }

protected:
    WorstPoint(bool fewest, double none) : fewest_(fewest), figure_(none) {}

private:
    // Takes `figure` if it is the first or worse than the worst so far (NaN is the worst there is).
    bool worse(double figure) {
        if (std::isnan(figure)) figure = fewest_ ? 0.0 : INFINITY;
        if (any_ && !(fewest_ ? figure < figure_ : figure > figure_)) return false;
        any_ = true;
        figure_ = figure;
        return true;
    }

    bool fewest_;
    bool any_ = false;
    double figure_;
    std::string point_;
};

/// The fewest accuracy digits over many points (simlab/digits.h).
class WorstDigits : public WorstPoint {
public:
    WorstDigits() : WorstPoint(true, kMaxDigits) {}
};

/// The largest drift over many points: a relative departure from a value that should hold (an energy, say).
class WorstDrift : public WorstPoint {
public:
    WorstDrift() : WorstPoint(false, 0.0) {}
};

/// grading::atLeast on the fewest digits of `worst`, whose comparison a failing test's reason shows.
inline bool atLeast(const WorstDigits& worst, double floor, double target, const std::string& unit) {
    if (!worst.point().empty()) grading::worstPoint(worst.point());
    return grading::atLeast(worst.figure(), floor, target, unit);
}

/// grading::atMost on the largest drift of `worst`, whose comparison a failing test's reason shows.
inline bool atMost(const WorstDrift& worst, double allowed, const std::string& what) {
    if (!worst.point().empty()) grading::worstPoint(worst.point());
    return grading::atMost(worst.figure(), allowed, what);
}

/// Fails the test unless the simulation recorded something.
template <class Sample>
void requireSamples(const RunResult<Sample>& run) {
    INFO("the simulation recorded no samples");
    REQUIRE_FALSE(run.samples.empty());
}

/// The last sample; fails the test if there is none or it is not at `time`.
template <class Sample>
const Sample& lastSample(const RunResult<Sample>& run, double time) {
    requireSamples(run);
    const Sample& last = run.samples.back();
    INFO("the last sample is at t = " << last.time << " s, not at " << time << " s");
    REQUIRE(last.time == Approx(time).epsilon(1e-9));
    return last;
}
/// Not from a run that ends with the statement: the sample would be gone before it is read.
template <class Sample>
const Sample& lastSample(RunResult<Sample>&& run, double time) = delete;

/// The sample at `time` (to within a nanosecond); fails the test if there is none.
template <class Sample>
const Sample& sampleAt(const RunResult<Sample>& run, double time) {
    requireSamples(run);
    for (const Sample& s : run.samples) {
        if (std::abs(s.time - time) < 1e-9) return s;
    }
    INFO("no sample at t = " << time << " s");
    FAIL();
    return run.samples.front();
}
/// Not from a run that ends with the statement: the sample would be gone before it is read.
template <class Sample>
const Sample& sampleAt(RunResult<Sample>&& run, double time) = delete;

/// Samples at t = 0 and at every settings.sampleTime(k), up to the final time.
template <class Sample>
void checkSampleTimes(const RunResult<Sample>& run, const RunSettings& settings) {
    const std::size_t expected = settings.sampleCount() + 1;
    INFO("with dt = " << settings.dt << " s and a final time of " << settings.finalTime << " s there should be "
                      << expected << " samples; there were " << run.samples.size());
    REQUIRE(run.samples.size() == expected);
    for (std::size_t k = 0; k < run.samples.size(); ++k) {
        INFO("sample " << k << " is at t = " << run.samples[k].time << " s, expected " << settings.sampleTime(k));
        CHECK(run.samples[k].time == Approx(settings.sampleTime(k)).margin(1e-9));
    }
}

/// makeIntegrator gives the integrator asked for at the accuracy asked for, and takes fixed steps when asked.
template <class Sample, class Scene>
void checkIntegratorRequests(const Scene& scene, const RunSettings& base) {
    struct Request {
        const char* name;
        double accuracy;
    };
    for (const Request& request : {Request{"RungeKutta3", 1e-9}, Request{"Verlet", 1e-5}, Request{"CPodes", 1e-6}}) {
        RunSettings settings = base;
        settings.integrator = request.name;
        settings.accuracy = request.accuracy;
        const RunResult<Sample> run = simulate<Sample>(scene, settings);
        // Samples made without a step (written down, not simulated) have no integrator to ask: say that, not
        // "got  at accuracy nan".
        if (run.integrator.stepsTaken == 0 || !std::isfinite(run.integrator.accuracyInUse)) {
            FAIL_CHECK("asked for " << request.name
                                    << ": simulate() never stepped the integrator, so its samples "
                                       "did not come from a simulation");
            continue;
        }
        const std::string& method = run.integrator.method;
        const bool sameMethod =
            method == request.name || (std::string(request.name) == "CPodes" && method.rfind("CPodes", 0) == 0);
        INFO("asked for " << request.name << " at accuracy " << request.accuracy << ", got " << method
                          << " at accuracy " << run.integrator.accuracyInUse);
        CHECK(sameMethod);
        CHECK(run.integrator.accuracyInUse == Approx(request.accuracy));
    }
    RunSettings fixed = base;
    fixed.integrator = "RungeKutta2";
    fixed.fixedStep = true;
    const RunResult<Sample> run = simulate<Sample>(scene, fixed);
    INFO("asked for fixed steps of " << fixed.dt << " s over " << fixed.finalTime << " s (" << fixed.sampleCount()
                                     << " steps), the integrator took " << run.integrator.stepsTaken);
    CHECK(run.integrator.stepsTaken == fixed.sampleCount());
}

/// The model has `dof` degrees of freedom, one body with mass, and no more mobilities than it has degrees of
/// freedom: a scene's motions given by its mobilizers, not by a Free mobilizer held back with constraints. `scene`
/// says what the motion is ("a fall along y"); `advice` what models exactly that. A Free, Translation or Planar
/// mobilizer gets a feedback line.
inline void checkDegreesOfFreedom(const ModelInfo& info, int dof, const std::string& scene, const std::string& advice) {
    grading::measured(info.degreesOfFreedom(), "degrees of freedom", info.summary());
    for (const char* kind : {"Free", "Translation", "Planar", "Gimbal", "Ball"}) {
        if (info.uses(kind) && (info.degreesOfFreedom() != dof || info.mobilities != dof)) {
            grading::feedback(std::string("a ") + kind + " mobilizer allows motions " + scene +
                              " never calls for; " + advice);
            break;
        }
    }
    if (info.constraintEquations > 0) {
        grading::feedback("constraints take back motions the mobilizers gave; " + advice);
    }
    INFO(info.summary() << "; " << scene << " needs one body with " << dof
                        << (dof == 1 ? " degree" : " degrees") << " of freedom, given by its mobilizers");
    CHECK(info.massiveBodies() == 1);
    CHECK(info.degreesOfFreedom() == dof);
    CHECK(info.mobilities == dof);
}

/// The student's answer to the trade question, measured (see observe::choice) to `finalTime` and stopped past
/// `cap` evaluations. Fails the test unless the samples start at t = 0 and run forward in time.
template <class Sample, class Scene>
ChoiceRun<Sample> observeChoice(const Scene& scene, double finalTime, double cap) {
    ChoiceRun<Sample> result = observe::choice<Sample>(scene, finalTime, cap);
    INFO("the choice: " << result.choice.integrator
                        << (result.choice.fixedStep ? ", fixed step " : ", accuracy ")
                        << (result.choice.fixedStep ? result.choice.dt : result.choice.accuracy));
    REQUIRE(!result.samples.empty());
    CHECK(result.samples.front().time == 0.0);
    for (std::size_t i = 1; i < result.samples.size(); ++i) {
        REQUIRE(result.samples[i].time >= result.samples[i - 1].time);
    }
    REQUIRE(result.samples.back().time <= finalTime * (1 + 1e-12));
    // The counts come from the student's process: they must agree with each other and with the samples.
    const std::string inconsistency = inconsistencyOf(result);
    INFO(inconsistency);
    REQUIRE(inconsistency.empty());
    return result;
}

/// What the trade question earns on one of its scenes.
struct TradeCredit {
    double credit = 0;   ///< 0 to 1
    double ratio = NAN;  ///< the answer's evaluations over the front's cost where it was read (NaN: not read)
    double evaluations = NAN;  ///< the answer's, at its worst start, where it kept the digits asked for
    double digits = NAN;       ///< the fewest it kept at any step, there
    std::string line;    ///< what was measured, in words
};

/// Digits of a sample of `scene`'s run to `finalTime`, the worst of what the question counts (the lab's): made once
/// per scene, so that a reference the digits need is computed once.
template <class Sample, class Scene>
using TradeDigits = std::function<std::function<double(const Sample&)>(const Scene& scene, double finalTime)>;

/// The trade question on scene `s` of `q`. The student's cheapestSettings() is measured from each of the question's
/// starts (the scene's number at q.nudge moved by 0, 1, ... units in its last place) and kept at its worst: the
/// fewest digits at any step, the most evaluations. Short of q.digits it earns nothing. Otherwise its evaluations
/// are set against the scene's work-precision front read at the digits it keeps (counted up to the rubric's
/// `beyond` digits more than asked: what it keeps beyond that, nobody asked for): full credit up to the rubric's
/// full_within times the front's cost, less in proportion to the logarithm up to none_past times, and nothing
/// beyond (the run is stopped there).
template <class Sample, class Scene>
TradeCredit tradeCredit(const trade::Question& q, const trade::Scene& s, const TradeDigits<Sample, Scene>& digitsOf) {
    const double beyond = grading::param("beyond"), fullWithin = grading::param("full_within");
    const double nonePast = grading::param("none_past");
    if (s.front.empty()) {
        throw std::logic_error("the trade question's scene '" + s.name + "' has no front (simlab study trade " + q.lab +
                               " --fronts makes it)");
    }
    const double cap = trade::cap(s.front, q.digits, beyond, nonePast);  // the most that can earn anything
    TradeCredit result;
    double worst = kMaxDigits, evaluations = 0;
    RunSettings choice;
    for (int k = 0; k < q.starts; ++k) {
        const Scene scene = wire::readOver(Scene{}, trade::nudged(s.scene, q.nudge, k), "the trade question's scene");
        const ChoiceRun<Sample> run = observeChoice<Sample>(scene, s.finalTime, cap);
        choice = run.choice;
        const std::string setting = describeRun(choice);
        if (!trade::allows(q, choice.integrator, choice.fixedStep)) {
            std::string allowed;
            for (const std::string& name : q.integrators) allowed += (allowed.empty() ? "" : " or ") + name;
            result.line = setting + ": the question asks for " + (allowed.empty() ? "an integrator" : allowed) +
                          (q.fixedStepOnly ? " at fixed steps" : "");
            return result;
        }
        evaluations = std::max(evaluations, static_cast<double>(run.run.integrator.realizations));
        if (run.run.status != "ok") {
            result.line = setting + ": " + run.run.status + ", " + run.run.message;
            return result;
        }
        const std::function<double(const Sample&)> digits = digitsOf(scene, s.finalTime);
        for (const Sample& sample : run.samples) worst = std::min(worst, digits(sample));
    }
    const std::string setting = describeRun(choice);
    const std::string starts = q.starts > 1 ? " (the worst of " + std::to_string(q.starts) + " starts)" : "";
    std::ostringstream line;
    if (!(worst >= q.digits)) {
        line << setting << " keeps " << grading::show(worst) << " digits over the run" << starts << ", need "
             << grading::show(q.digits);
        result.line = line.str();
        return result;
    }
    const trade::Score score = trade::score(s.front, q.digits, worst, evaluations, beyond, fullWithin, nonePast);
    result.ratio = score.ratio;
    result.credit = score.credit;
    result.evaluations = evaluations;
    result.digits = worst;
    line << setting << ": " << grading::show(worst) << " digits" << starts << " for "
         << static_cast<long long>(evaluations) << " evaluations, " << grading::show(score.ratio)
         << " x the front at " << grading::show(score.readAt) << " digits ("
         << static_cast<long long>(std::ceil(score.frontCost)) << "); full credit up to " << grading::show(fullWithin)
         << " x";
    result.line = line.str();
    return result;
}

/// The scene of `q` the running student answers on: their own from its pool where the rubric gives each student one
/// ([variants]), else the question's.
inline const trade::Scene& studentScene(const trade::Question& q) {
    const grading::StudentVariant v = grading::studentVariant();
    return trade::sceneFor(q, v.on, v.seed, v.student);
}

/// Points for the trade question on scene `s` of `q` (tradeCredit): the figure is the cost against the front. An
/// answer that keeps the digits asked for goes on the leaderboard: its cost against the front first, then its
/// evaluations and the digits it kept (to a tenth, counted up to `beyond` past those asked, as the front is read).
template <class Sample, class Scene>
void gradeTrade(const trade::Question& q, const trade::Scene& s, const TradeDigits<Sample, Scene>& digitsOf) {
    TradeCredit c = tradeCredit<Sample, Scene>(q, s, digitsOf);
    if (s.name != "question") c.line = "on your scene (" + s.name + "): " + c.line;
    grading::measured(c.ratio, "x the front", c.line);
    if (std::isfinite(c.evaluations) && std::isfinite(c.ratio)) {
        const double kept = std::min(c.digits, q.digits + grading::param("beyond"));
        // The cost against the front leads: it is the one figure comparable across students' scenes (a partial
        // answer on a cheap scene may take fewer evaluations than the front of a dear one).
        grading::leaderboard("trade: x the front", std::round(c.ratio * 100) / 100, "asc");
        grading::leaderboard("trade: evaluations", c.evaluations, "asc");
        grading::leaderboard("trade: digits kept", std::floor(kept * 10) / 10, "desc");
    }
    if (c.credit >= 1) return;
    if (c.credit > 0) grading::partialCredit(c.credit);
    FAIL_CHECK(c.line);
}

/// Points for the trade question on every scene of `q` (its hidden variants, say): the mean of their credits; the
/// figure is the largest cost against the front among the scenes where the answer kept the digits.
template <class Sample, class Scene>
void gradeTradeVariants(const trade::Question& q, const TradeDigits<Sample, Scene>& digitsOf) {
    REQUIRE_FALSE(q.scenes.empty());
    double credit = 0, ratio = NAN;
    std::string lines;
    for (const trade::Scene& s : q.scenes) {
        const TradeCredit c = tradeCredit<Sample, Scene>(q, s, digitsOf);
        credit += c.credit / static_cast<double>(q.scenes.size());
        if (std::isfinite(c.ratio)) ratio = std::isnan(ratio) ? c.ratio : std::max(ratio, c.ratio);
        lines += (lines.empty() ? "" : "; ") + s.name + ": " + c.line;
        if (c.credit < 1) grading::feedback(s.name + ": " + c.line);
    }
    grading::measured(ratio, "x the front", lines);
    if (credit >= 1) return;
    if (credit > 0) grading::partialCredit(credit);
    FAIL_CHECK("the answer earns " << grading::show(100 * credit) << " % of the points over the scenes");
}

}  // namespace simlab::testing
