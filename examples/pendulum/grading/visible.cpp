// A pendulum's swing: the tests a student's self-check runs. Points and thresholds are in rubric.toml.
#include "pendulum_testing.h"

namespace pendulum::testing {

TEST_CASE("the bob starts at rest at the release angle", "[pendulum][initial]") {
    const Scene scene;
    const Run run = simulate(scene);
    requireSamples(run);
    const Sample& first = run.samples.front();
    const double theta0_rad = exact::releaseAngle_rad(scene);
    INFO("first sample: t = " << first.time << " s, theta = " << first.theta_rad << " rad, theta' = "
                              << first.thetaDot_radps << " rad/s; expected t = 0, theta = " << theta0_rad
                              << " rad (" << scene.releaseAngle_deg << " degrees), theta' = 0");
    CHECK(first.time == 0.0);
    CHECK(first.theta_rad == Approx(theta0_rad).epsilon(1e-12));
    CHECK(first.thetaDot_radps == Approx(0.0).margin(1e-12));
}

TEST_CASE("samples run from t = 0 to the final time every dt", "[pendulum][sampling]") {
    const simlab::RunSettings settings = settingsFor(/*finalTime=*/2.0, /*dt=*/0.25);
    checkSampleTimes(simulate(Scene{}, settings), settings);
}

TEST_CASE("the integrator is the one asked for at the accuracy asked for", "[pendulum][integrator]") {
    // One second, sampled every 0.05 s: 20 steps when fixed.
    checkIntegratorRequests<Sample>(Scene{}, settingsFor(1.0, 0.05));
}

TEST_CASE("the model is one bob on a Pin: one degree of freedom", "[pendulum][model]") {
    const simlab::ModelInfo info = simlab::observe::model(Scene{});
    checkDegreesOfFreedom(info, 1, "a swing in the x-y plane about the pivot",
                          "a Pin at the pivot gives the bob exactly its one motion");
    INFO(info.summary() << "; a swing about a fixed axis is a Pin's motion");
    CHECK(info.uses("Pin"));
}

TEST_CASE("theta follows the exact elliptic swing at every sample", "[pendulum][theta]") {
    // sin(theta / 2) = k sn(K - w0 t, k) with k = sin(theta0 / 2): errors count against theta0.
    const Scene scene;
    const simlab::RunSettings settings = defaultRunSettings();
    const Run run = simulate(scene, settings);
    if (!run.samples.empty()) {  // the run as the feedback page shows it, whatever this test finds of it
        grading::attachPlot("your-run.svg", runPlot(scene, "your run: " + simlab::describeRun(settings), run.samples));
    }
    lastSample(run, settings.finalTime);
    CHECK(grading::atLeast(thetaDigits(scene, run), grading::param("floor"), grading::param("target"),
                           "digits at the worst sample"));
}

TEST_CASE("the swing's energy stays at its value at release", "[pendulum][energy]") {
    // Only gravity does work, and it is conservative: m L^2 theta'^2 / 2 - m g L cos theta keeps its value at
    // release, -m g L cos theta0, to about the accuracy the integrator was asked for (against m g L, since the
    // energy itself is zero for a release at 90 degrees).
    const Scene scene;
    const simlab::RunSettings settings = defaultRunSettings();
    const Run run = simulate(scene, settings);
    lastSample(run, settings.finalTime);
    const double allowed = grading::param("tolerance") * settings.accuracy;
    CHECK(grading::atMost(energyDrift(scene, run), allowed, "energy drift over m g L"));
}

TEST_CASE("the period the samples show is T = 4 K(k) sqrt(L / g)", "[pendulum][period]") {
    // The turning points (theta' = 0) come every half period: about 2.8 periods in the lab's 10 s.
    const Scene scene;
    const simlab::RunSettings settings = defaultRunSettings();
    const Run run = simulate(scene, settings);
    lastSample(run, settings.finalTime);
    const MeasuredPeriod measured = measuredPeriod(run.samples);
    INFO(describePeriod(scene, measured));
    CHECK(grading::atLeast(periodDigits(scene, measured), grading::param("floor"), grading::param("target"),
                           "digits of the period"));
}

}  // namespace pendulum::testing
