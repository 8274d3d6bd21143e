// Newton's apple: the tests a student's self-check runs. Points and thresholds are in ../rubric.toml.
#include "apple_testing.h"

namespace apple::testing {

TEST_CASE("the apple starts at rest at the drop height", "[apple][initial]") {
    const Scene scene;
    const Run run = simulate(scene);
    requireSamples(run);
    const Sample& first = run.samples.front();
    INFO("first sample: t = " << first.time << " s, y = " << first.yLocation << " m, y' = " << first.yVelocity
                              << " m/s; expected t = 0, y = " << scene.dropHeight << " m, y' = 0");
    CHECK(first.time == 0.0);
    CHECK(first.yLocation == Approx(scene.dropHeight).epsilon(1e-12));
    CHECK(first.yVelocity == Approx(0.0).margin(1e-12));
}

TEST_CASE("samples run from t = 0 to the final time every dt", "[apple][sampling]") {
    const simlab::RunSettings settings = settingsFor(/*finalTime=*/2.0, /*dt=*/0.25);
    checkSampleTimes(simulate(Scene{}, settings), settings);
}

TEST_CASE("the integrator is the one asked for at the accuracy asked for", "[apple][integrator]") {
    // One second, sampled every 0.05 s: 20 steps when fixed.
    checkIntegratorRequests<Sample>(Scene{}, settingsFor(1.0, 0.05));
}

TEST_CASE("y at the final time has the target accuracy digits", "[apple][accuracy]") {
    // y(4) = 10 - 4.9 * 4^2 = -68.4 m exactly; a double carries about 15.7 digits.
    const Scene scene;
    CHECK(atLeast(finalDigits(scene, defaultRunSettings()), grading::param("floor"), grading::param("target"),
                  "digits"));
}

TEST_CASE("the velocity follows v = -g t at every sample", "[apple][velocity]") {
    const Scene scene;
    const simlab::RunSettings settings = defaultRunSettings();
    const Run run = simulate(scene, settings);
    if (!run.samples.empty()) {  // the run as the feedback page shows it, whatever this test finds of it
        grading::attachPlot("your-run.svg", runPlot(scene, "your run: " + simlab::describeRun(settings), run.samples));
    }
    lastSample(run, settings.finalTime);
    // Errors relative to the final speed g T, so the sample at rest (v = 0) counts like the others.
    const double scale = scene.gravity * settings.finalTime;
    WorstDigits worst;
    for (const Sample& s : run.samples) {
        const double expected = exact::yVelocity(scene, s.time);
        worst.add(simlab::accuracyDigits(s.yVelocity, expected, scale), grading::at("v", s.time), s.yVelocity, expected,
                  "m/s");
    }
    CHECK(atLeast(worst, grading::param("floor"), grading::param("target"), "digits at the worst sample"));
}

TEST_CASE("the mechanical energy stays at m g h", "[apple][energy]") {
    // Only gravity acts and it is conservative: kinetic + potential energy keeps its initial value m g h,
    // to about the accuracy the integrator was asked for.
    const Scene scene;
    const simlab::RunSettings settings = defaultRunSettings();
    const Run run = simulate(scene, settings);
    lastSample(run, settings.finalTime);
    const double allowed = grading::param("tolerance") * settings.accuracy;
    CHECK(atMost(energyDrift(scene, run), allowed, "relative energy drift"));
}

TEST_CASE("the model has only the one degree of freedom a fall needs", "[apple][model]") {
    checkDegreesOfFreedom(simlab::observe::model(Scene{}), 1, "a fall along y",
                          "a Slider along Ground's y gives the apple exactly its one motion");
}

TEST_CASE("the trade: the fewest explicit Euler steps that keep 3 digits of the question's fall", "[apple][trade]") {
    // cheapestSettings(), measured on the student's own model as `simlab study trade apple --question` measures a
    // setting - every step's y and vy count - from each of the question's starts, against the front of explicit
    // Euler's fixed steps on the question's fall (not the lab's default one).
    gradeTrade<Sample, Scene>(tradeQuestion(), studentScene(tradeQuestion()), tradeDigits);
}

}  // namespace apple::testing
