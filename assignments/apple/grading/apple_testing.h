// What the apple's visible and hidden tests share: observing a student's simulation and measuring it.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "apple/contract/NewtonsApple.h"
#include "apple/program/exact.h"
#include "apple/grading/observations.h"
#include "apple/program/run_plot.h"
#include "simlab/digits.h"
#include "simlab/harness/testing.h"

namespace apple::testing {

namespace grading = simlab::grading;
using namespace simlab::testing;
using Run = simlab::RunResult<Sample>;

inline Run simulate(const Scene& scene, const simlab::RunSettings& settings = defaultRunSettings()) {
    return simlab::testing::simulate<Sample>(scene, settings);
}

inline simlab::RunSettings settingsFor(double finalTime, double dt, double accuracy = 1e-7) {
    return simlab::testing::settingsFor(defaultRunSettings(), finalTime, dt, accuracy);
}

/// Digits of y at the final time against y = h - g t^2/2, and the two values.
inline WorstDigits finalDigits(const Scene& scene, const simlab::RunSettings& settings) {
    const Run run = simulate(scene, settings);
    const Sample& last = lastSample(run, settings.finalTime);
    const double expected = exact::yLocation(scene, last.time);
    WorstDigits digits;
    digits.add(simlab::accuracyDigits(last.yLocation, expected), grading::at("y", last.time), last.yLocation, expected,
               "m");
    return digits;
}

/// The trade question (tests/trade-question.json): the scene it is asked on, the digits, and the front.
inline const simlab::trade::Question& tradeQuestion() {
    static const simlab::trade::Question question = simlab::trade::parseQuestion(
#include "trade_question.inc"
        , "the apple's trade-question.json");
    return question;
}

/// What the trade question counts of a sample of a fall to `finalTime`: the digits of y and vy.
inline std::function<double(const Sample&)> tradeDigits(const Scene& scene, double finalTime) {
    return [scene, finalTime](const Sample& s) { return exact::sampleDigits(scene, s, finalTime); };
}

/// Largest relative departure of the sampled mechanical energy from m g h, and where.
inline WorstDrift energyDrift(const Scene& scene, const Run& run) {
    const double expected = exact::mechanicalEnergy(scene);
    WorstDrift drift;
    for (const Sample& s : run.samples) {
        drift.add(std::abs(s.mechanicalEnergy - expected) / std::abs(expected), grading::at("E", s.time),
                  s.mechanicalEnergy, expected, "J");
    }
    return drift;
}

}  // namespace apple::testing
