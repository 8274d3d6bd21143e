// A pendulum's swing: the tests only an instructor's grading runs. They change the scene, so a file that types in
// the lab's swing instead of simulating it passes the visible tests and fails these.
#include "pendulum_testing.h"

namespace pendulum::testing {

namespace {
// The worst of theta's digits and the period's over several scenes, each run to its own final time: every one
// has to be right.
double worstDigits(const std::vector<Scene>& scenes, const std::vector<simlab::RunSettings>& settings) {
    double worst = simlab::kMaxDigits;
    for (std::size_t i = 0; i < scenes.size(); ++i) {
        const Run run = simulate(scenes[i], settings[i]);
        lastSample(run, settings[i].finalTime);
        const MeasuredPeriod measured = measuredPeriod(run.samples);
        const double theta = thetaDigits(scenes[i], run), period = periodDigits(scenes[i], measured);
        if (std::min(theta, period) < grading::param("target")) {
            grading::feedback(describePeriod(scenes[i], measured) + ": " + grading::show(theta) +
                              " digits of theta, " + grading::show(period) + " of the period");
        }
        worst = std::min({worst, theta, period});
    }
    return worst;
}
}  // namespace

TEST_CASE("hidden: releases from 10 to 179 degrees swing as the exact pendulum",
          "[pendulum][hidden]") {
    // 10 degrees is nearly the small-swing pendulum (T = 2.010 s against 2 pi sqrt(L / g) = 2.006 s); at 179
    // degrees the bob lingers near the top and T = 7.826 s, growing like ln(4 / cos(theta0 / 2)) towards 180.
    // There an error in energy of e m g L moves the period by some 4000 e seconds, and theta' reaches 2 w0 at the
    // bottom: that run asks for a tighter accuracy.
    const double digits = worstDigits({sceneWith(10), sceneWith(90), sceneWith(179)},
                                      {settingsFor(6, 0.01), settingsFor(6, 0.01), settingsFor(20, 0.01, 1e-11)});
    CHECK(grading::atLeast(digits, grading::param("floor"), grading::param("target"), "digits at the worst swing"));
}

TEST_CASE("hidden: other lengths and gravity fields swing as the exact pendulum", "[pendulum][hidden]") {
    // A short pendulum on Earth, a long one on the Moon, a metre on Jupiter: T scales with sqrt(L / g).
    const double digits = worstDigits({sceneWith(120, 0.25, 9.81), sceneWith(120, 2.5, 1.62), sceneWith(60, 1, 24.79)},
                                      {settingsFor(4, 0.005), settingsFor(30, 0.02), settingsFor(3, 0.005)});
    CHECK(grading::atLeast(digits, grading::param("floor"), grading::param("target"), "digits at the worst scene"));
}

TEST_CASE("hidden: other masses keep the energy at its value at release", "[pendulum][hidden]") {
    double worst = 0;
    for (const double mass_kg : {0.05, 7.0}) {
        const Scene s = sceneWith(150, 1.0, 9.81, mass_kg);
        const Run run = simulate(s);
        lastSample(run, defaultRunSettings().finalTime);  // the whole swing, not an empty run
        worst = std::max(worst, energyDrift(s, run));
    }
    CHECK(grading::atMost(worst, grading::param("tolerance") * defaultRunSettings().accuracy,
                          "energy drift over m g L"));
}

}  // namespace pendulum::testing
