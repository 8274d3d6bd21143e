// What the apple's visible and hidden tests share: running a student's simulation and measuring it.
#pragma once

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "apple/NewtonsApple.h"
#include "apple/exact.h"
#include "simlab/digits.h"
#include "simlab/driver.h"
#include "simlab/grading.h"

namespace apple::testing {

namespace grading = simlab::grading;
using Run = simlab::RunResult<Sample>;

/// The student's simulation of `scene`, driven as the apple program drives it.
inline Run simulate(const Scene& scene, const simlab::RunSettings& settings = defaultRunSettings()) {
    Model model;
    return simlab::run<Sample>(scene, model, settings);
}

inline simlab::RunSettings settingsFor(double finalTime, double dt, double accuracy = 1e-7) {
    simlab::RunSettings run = defaultRunSettings();
    run.finalTime = finalTime;
    run.dt = dt;
    run.accuracy = accuracy;
    return run;
}

/// Fails the test unless the simulation recorded something.
inline void requireSamples(const Run& run) {
    INFO("the simulation recorded no samples");
    REQUIRE_FALSE(run.samples.empty());
}

/// The last sample; fails the test if there is none or it is not at the final time.
inline const Sample& finalSample(const Run& run, const simlab::RunSettings& settings) {
    requireSamples(run);
    const Sample& last = run.samples.back();
    INFO("the last sample is at t = " << last.time << " s, not at the final time " << settings.finalTime << " s");
    REQUIRE(last.time == Approx(settings.finalTime).epsilon(1e-9));
    return last;
}

/// Digits of y at the final time against y = h - g t^2/2.
inline double finalDigits(const Scene& scene, const simlab::RunSettings& settings) {
    const Run run = simulate(scene, settings);
    const Sample& last = finalSample(run, settings);
    return simlab::accuracyDigits(last.yLocation, exact::yLocation(scene, last.time));
}

/// Largest relative departure of the sampled mechanical energy from m g h.
inline double energyDrift(const Scene& scene, const Run& run) {
    const double expected = exact::mechanicalEnergy(scene);
    double drift = 0;
    for (const Sample& s : run.samples) {
        const double relative = std::abs(s.mechanicalEnergy - expected) / std::abs(expected);
        drift = std::isnan(relative) ? INFINITY : std::max(drift, relative);
    }
    return drift;
}

}  // namespace apple::testing
