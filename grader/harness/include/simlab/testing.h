// What every assignment's grader tests share: observing a student's simulation, and the checks that are the
// same from one lab to the next (samples present, the integrator honoured, the degrees of freedom the scene
// needs). Each assignment's tests call these inside their own TEST_CASEs, under their own names. The tests run
// in the judge, which never holds student code: what they know of it, they observe (simlab/observe.h).
#pragma once

#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "simlab/driver.h"
#include "simlab/grading.h"
#include "simlab/observe.h"
#include "simlab/run_settings.h"

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
/// the rubric's none_past times its `cheapest` evaluations. Fails the test unless the samples start at t = 0 and
/// run forward in time.
template <class Sample, class Scene>
ChoiceRun<Sample> observeChoice(const Scene& scene, double finalTime) {
    const double cap = grading::param("none_past") * grading::param("cheapest");
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

/// Points for the trade question. `digits`, the worst over the run, must reach the rubric's `digits`; then the
/// cost in evaluations earns full credit up to full_within times the study's `cheapest`, less in proportion to its
/// logarithm up to none_past times, and nothing beyond (a run stopped there never finishes). Returns true for
/// full credit.
template <class Sample>
bool gradeTrade(const ChoiceRun<Sample>& result, double digits) {
    const double target = grading::param("digits"), cheapest = grading::param("cheapest");
    const double fullWithin = grading::param("full_within"), nonePast = grading::param("none_past");
    const RunSettings& c = result.choice;
    const std::string setting = describeRun(c);
    const double evaluations = result.run.integrator.realizations;
    const double ratio = evaluations / cheapest;
    // Every outcome is measured as the cost against the cheapest, so that a class's figures for this test are one
    // quantity; the line says the rest.
    if (result.run.status != "ok") {
        grading::measured(ratio, "x the cheapest", setting + ": " + result.run.status + ", " + result.run.message);
        FAIL_CHECK("the run did not finish: " << result.run.message);
        return false;
    }
    if (!(digits >= target)) {
        grading::measured(ratio, "x the cheapest", setting + " keeps " + grading::show(digits) +
                                                       " digits over the run, need " + grading::show(target));
        FAIL_CHECK("too few digits");
        return false;
    }
    std::ostringstream line;
    line << setting << ": " << grading::show(digits) << " digits for " << static_cast<long long>(evaluations)
         << " evaluations, " << grading::show(ratio) << " x the cheapest found (" << static_cast<long long>(cheapest)
         << "); full credit up to " << grading::show(fullWithin) << " x";
    grading::measured(ratio, "x the cheapest", line.str());
    if (ratio <= fullWithin) return true;
    if (ratio < nonePast) grading::partialCredit(1 - std::log(ratio / fullWithin) / std::log(nonePast / fullWithin));
    FAIL_CHECK("dearer than " << fullWithin << " x the cheapest setting found");
    return false;
}

}  // namespace simlab::testing
