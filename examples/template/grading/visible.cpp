// A block on a spring: the tests a student's self-check runs, one of each kind a lab usually needs. Each
// TEST_CASE's name is a [[test]] of rubric.toml, which holds its points and thresholds.
//
// CHANGE: the scene and the measures in each test to your lab's, keeping each name equal to its rubric entry.
// Keep the pattern: observe the student's run (simulate, simlab::observe::model), measure it against the exact
// solution here in the judge, and let grading::atLeast / atMost turn the measure into credit.
#include <algorithm>
#include <cmath>

#include "mylab/contract/MyLab.h"
#include "mylab/grading/observations.h"
#include "mylab/program/exact.h"
#include "simlab/harness/testing.h"

namespace mylab::testing {

namespace grading = simlab::grading;
using namespace simlab::testing;
using Run = simlab::RunResult<Sample>;

// A model test: the scene has exactly the degrees of freedom it needs, given by the right mobilizer.
// CHANGE: the count, the words, and the mobilizer your scene calls for ("Pin", "Slider", ...).
TEST_CASE("the model is one block on a Slider: one degree of freedom", "[mylab][model]") {
    const simlab::ModelInfo info = simlab::observe::model(Scene{});
    checkDegreesOfFreedom(info, 1, "a slide along the rail", "a Slider gives the block exactly its one motion");
    INFO(info.summary() << "; a translation along a fixed axis is a Slider's motion");
    CHECK(info.uses("Slider"));
}

// A digits test: how many digits of the simulated x agree with the exact one, at the worst sample.
// CHANGE: the quantity and its exact value. Count its errors against a scale that stays away from zero (here x0),
// never relative to a value that passes through zero.
TEST_CASE("x follows the exact oscillation x0 cos(omega t) at every sample", "[mylab][digits]") {
    const Scene scene;
    const simlab::RunSettings settings = defaultRunSettings();
    const Run run = simlab::testing::simulate<Sample>(scene, settings);
    lastSample(run, settings.finalTime);  // the whole run, not an empty or a short one
    CHECK(grading::atLeast(exact::worstDigits(scene, run.samples), grading::param("floor"), grading::param("target"),
                           "digits of x at the worst sample, against x0"));
}

// A conserved-quantity test: the energy keeps its value at release, to about the integrator's accuracy.
// CHANGE: your scene's conserved quantity and the scale its drift is measured against. Checking both the value the
// student samples and the value the physics gives their x and x' catches a wrong mass or stiffness too.
TEST_CASE("the energy stays at k x0^2 / 2", "[mylab][energy]") {
    const Scene scene;
    const simlab::RunSettings settings = defaultRunSettings();
    const Run run = simlab::testing::simulate<Sample>(scene, settings);
    lastSample(run, settings.finalTime);
    const double expected_J = exact::mechanicalEnergy_J(scene);
    double drift = 0;
    for (const Sample& s : run.samples) {
        const double sampled = std::abs(s.mechanicalEnergy_J - expected_J);
        const double ofMotion = std::abs(exact::energyOf_J(scene, s.x_m, s.xDot_mps) - expected_J);
        const double worst = std::max(sampled, ofMotion) / expected_J;
        drift = std::isnan(worst) ? INFINITY : std::max(drift, worst);
    }
    CHECK(grading::atMost(drift, grading::param("tolerance") * settings.accuracy, "energy drift over k x0^2 / 2"));
}

}  // namespace mylab::testing
