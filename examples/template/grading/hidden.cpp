// A block on a spring: the test only an instructor's grading runs (the student's copy of the lab leaves this file
// out). It changes the scene, so a file that types in the default scene's numbers instead of reading the Scene
// passes the visible tests and fails this one.
//
// CHANGE: the cases to other values of your scene's numbers, each with settings that a correct simulation passes
// with room to spare.
#include <algorithm>

#include "mylab/contract/MyLab.h"
#include "mylab/grading/observations.h"
#include "mylab/program/exact.h"
#include "simlab/harness/testing.h"

namespace mylab::testing {

namespace grading = simlab::grading;

// A hidden test: the digits test again, at the worst of scenes the student never saw.
TEST_CASE("hidden: other masses and stiffnesses oscillate as the exact block", "[mylab][hidden]") {
    // omega = 20 rad/s, a light block on a stiff spring: 16 periods in 5 s, whose errors add up; omega = 0.71
    // rad/s, a heavy block on a soft one: not even one period; and a release three times as far, on the other side
    // of the rest position. All at a tighter accuracy than the default, where the reference keeps 7 digits or more.
    struct Case {
        double mass_kg, stiffness_Npm, releasePosition_m;
    };
    simlab::RunSettings settings = defaultRunSettings();
    settings.accuracy = 1e-11;
    double worst = simlab::kMaxDigits;
    for (const Case& c : {Case{0.5, 200, 0.1}, Case{10, 5, 0.1}, Case{1, 30, -0.3}}) {
        Scene scene;
        scene.mass_kg = c.mass_kg, scene.stiffness_Npm = c.stiffness_Npm, scene.releasePosition_m = c.releasePosition_m;
        const simlab::RunResult<Sample> run = simlab::testing::simulate<Sample>(scene, settings);
        simlab::testing::lastSample(run, settings.finalTime);
        const double digits = exact::worstDigits(scene, run.samples);
        if (digits < grading::param("target")) {
            grading::feedback("m = " + grading::show(scene.mass_kg) + " kg, k = " + grading::show(scene.stiffness_Npm) +
                              " N/m, x0 = " + grading::show(scene.releasePosition_m) + " m: " + grading::show(digits) +
                              " digits of x");
        }
        worst = std::min(worst, digits);
    }
    CHECK(grading::atLeast(worst, grading::param("floor"), grading::param("target"), "digits at the worst scene"));
}

}  // namespace mylab::testing
