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
    const Scene scene;
    const simlab::RunSettings settings = settingsFor(/*finalTime=*/2.0, /*dt=*/0.25);
    const Run run = simulate(scene, settings);
    const std::size_t expected = settings.sampleCount() + 1;
    INFO("with dt = 0.25 s and a final time of 2 s there should be " << expected << " samples, at t = 0, 0.25, "
         "..., 2 s; there were " << run.samples.size());
    REQUIRE(run.samples.size() == expected);
    for (std::size_t k = 0; k < run.samples.size(); ++k) {
        INFO("sample " << k << " is at t = " << run.samples[k].time << " s, expected " << settings.sampleTime(k));
        CHECK(run.samples[k].time == Approx(settings.sampleTime(k)).margin(1e-9));
    }
}

TEST_CASE("the integrator is the one asked for at the accuracy asked for", "[apple][integrator]") {
    const Scene scene;
    struct Request {
        const char* name;
        double accuracy;
    };
    for (const Request& request : {Request{"RungeKutta3", 1e-9}, Request{"Verlet", 1e-5}, Request{"CPodes", 1e-6}}) {
        simlab::RunSettings settings = settingsFor(1.0, 0.1, request.accuracy);
        settings.integrator = request.name;
        const Run run = simulate(scene, settings);
        const std::string& method = run.integrator.method;
        const bool sameMethod = method == request.name || (std::string(request.name) == "CPodes" &&
                                                           method.rfind("CPodes", 0) == 0);
        INFO("asked for " << request.name << " at accuracy " << request.accuracy << ", got " << method
                          << " at accuracy " << run.integrator.accuracyInUse);
        CHECK(sameMethod);
        CHECK(run.integrator.accuracyInUse == Approx(request.accuracy));
    }
    // Fixed steps: one step per sampling interval.
    simlab::RunSettings fixed = settingsFor(1.0, 0.05);
    fixed.integrator = "RungeKutta2";
    fixed.fixedStep = true;
    const Run run = simulate(scene, fixed);
    INFO("asked for fixed steps of 0.05 s over 1 s (20 steps), the integrator took " << run.integrator.stepsTaken);
    CHECK(run.integrator.stepsTaken == fixed.sampleCount());
}

TEST_CASE("y at the final time has the target accuracy digits", "[apple][accuracy]") {
    // y(4) = 10 - 4.9 * 4^2 = -68.4 m exactly; a double carries about 15.7 digits.
    const Scene scene;
    const double digits = finalDigits(scene, defaultRunSettings());
    CHECK(grading::atLeast(digits, grading::param("floor"), grading::param("target"), "digits"));
}

TEST_CASE("the velocity follows v = -g t at every sample", "[apple][velocity]") {
    const Scene scene;
    const simlab::RunSettings settings = defaultRunSettings();
    const Run run = simulate(scene, settings);
    finalSample(run, settings);
    // Errors relative to the final speed g T, so the sample at rest (v = 0) counts like the others.
    const double scale = scene.gravity * settings.finalTime;
    double worst = simlab::kMaxDigits;
    for (const Sample& s : run.samples) {
        worst = std::min(worst, simlab::accuracyDigits(s.yVelocity, exact::yVelocity(scene, s.time), scale));
    }
    CHECK(grading::atLeast(worst, grading::param("floor"), grading::param("target"), "digits at the worst sample"));
}

TEST_CASE("the mechanical energy stays at m g h", "[apple][energy]") {
    // Only gravity acts and it is conservative: kinetic + potential energy keeps its initial value m g h,
    // to about the accuracy the integrator was asked for.
    const Scene scene;
    const simlab::RunSettings settings = defaultRunSettings();
    const Run run = simulate(scene, settings);
    finalSample(run, settings);
    const double allowed = grading::param("tolerance") * settings.accuracy;
    CHECK(grading::atMost(energyDrift(scene, run), allowed, "relative energy drift"));
}

TEST_CASE("the model has only the one degree of freedom a fall needs", "[apple][model]") {
    const Scene scene;
    Model model;
    buildModel(scene, model);
    const simlab::ModelInfo info = simlab::describeModel(model.matter, initialState(scene, model));
    grading::measured(info.degreesOfFreedom(), "degrees of freedom", info.summary());
    if (info.uses("Free") || info.uses("Translation")) {
        grading::feedback("a " + std::string(info.uses("Free") ? "Free" : "Translation (Cartesian)") +
                          " mobilizer lets the apple move in ways the scene never asks for; a Slider along Ground's y "
                          "gives it exactly its one motion");
    }
    INFO(info.summary() << "; the fall needs one body with one translational degree of freedom");
    CHECK(info.bodies == 1);
    CHECK(info.degreesOfFreedom() == 1);
}

}  // namespace apple::testing
