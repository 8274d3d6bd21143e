// Newton's apple: the tests only an instructor's grading runs. They change the scene and the settings, so a
// file that types in the lab's answer instead of simulating it passes the visible tests and fails these.
#include "apple_testing.h"

namespace apple::testing {

namespace {
// The worst of several runs decides: every variant has to be right.
WorstDigits worstDigits(const std::vector<Scene>& scenes, const std::vector<simlab::RunSettings>& settings) {
    WorstDigits worst;
    for (std::size_t i = 0; i < scenes.size(); ++i) {
        worst.add(finalDigits(scenes[i], settings[i]), "(dropped from " + grading::show(scenes[i].dropHeight) +
                                                           " m, g = " + grading::show(scenes[i].gravity) + " m/s^2)");
    }
    return worst;
}

Scene scene(double dropHeight, double gravity, double mass = 0.142) {
    Scene s;
    s.dropHeight = dropHeight;
    s.gravity = gravity;
    s.mass = mass;
    return s;
}
}  // namespace

TEST_CASE("hidden: drops from other heights follow y = h - g t^2/2", "[apple][hidden]") {
    const WorstDigits digits = worstDigits({scene(2.5, 9.8), scene(37, 9.8), scene(1200, 9.8)},
                                      {settingsFor(0.5, 0.01), settingsFor(2, 0.01), settingsFor(12, 0.05)});
    CHECK(atLeast(digits, grading::param("floor"), grading::param("target"), "digits at the worst height"));
}

TEST_CASE("hidden: other gravity fields and none at all are simulated", "[apple][hidden]") {
    // The Moon, Jupiter, and free space, where the apple stays put.
    const WorstDigits digits = worstDigits({scene(10, 1.62), scene(10, 24.79), scene(10, 0)},
                                      {settingsFor(3, 0.01), settingsFor(1, 0.01), settingsFor(3, 0.01)});
    CHECK(atLeast(digits, grading::param("floor"), grading::param("target"), "digits at the worst field"));
}

TEST_CASE("hidden: other masses keep the energy at m g h", "[apple][hidden]") {
    WorstDrift worst;
    for (const double mass : {0.05, 3.2}) {
        const Scene s = scene(10, 9.8, mass);
        const Run run = simulate(s);
        lastSample(run, defaultRunSettings().finalTime);  // the whole fall, not an empty run
        worst.add(energyDrift(s, run), "(m = " + grading::show(mass) + " kg)");
    }
    CHECK(atMost(worst, grading::param("tolerance") * defaultRunSettings().accuracy, "relative energy drift"));
}

TEST_CASE("hidden: extreme settings keep the fall accurate", "[apple][hidden]") {
    // Tight accuracy with fine sampling, loose accuracy with a dt that does not divide the final time, and a
    // long fall with coarse sampling.
    simlab::RunSettings tight = settingsFor(1, 0.001, 1e-12), loose = settingsFor(1, 0.3, 1e-3),
                        longFall = settingsFor(100, 1, 1e-7);
    const WorstDigits digits =
        worstDigits({scene(3, 9.81), scene(3, 9.81), scene(50000, 9.81)}, {tight, loose, longFall});
    CHECK(atLeast(digits, grading::param("floor"), grading::param("target"), "digits at the worst setting"));
}

TEST_CASE("hidden: the trade's step keeps its digits on other falls like the question's", "[apple][hidden][trade]") {
    // The same answer on falls with the question's h/g and duration (on the Moon, on Jupiter): Euler's error in y
    // is g t dt / 2 against a height that scales with g, so the same step keeps the same digits there.
    static const simlab::trade::Question variants = simlab::trade::parseQuestion(
#include "trade_hidden.inc"
        , "the apple's trade-hidden.json");
    gradeTradeVariants<Sample, Scene>(variants, tradeDigits);
}

}  // namespace apple::testing
