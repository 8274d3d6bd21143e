// Projectile motion: the tests only an instructor's grading runs. Other launches, so a file that types in the
// lab's numbers passes the visible tests and fails these.
#include "projectile_testing.h"

namespace projectile::testing {

TEST_CASE("hidden: launches from shallow to straight up land where they should", "[projectile][hidden]") {
    // A gentle 20-degree hit at 25 m/s, a line drive at 5 degrees, a pop-up at 75, and straight up.
    WorstDigits worst;
    for (const Scene& scene : {launch(20, 25), launch(5, 44.7), launch(75, 44.7), launch(90, 30)}) {
        const HitDigits digits = groundHitDigits(scene, 0.25);
        const std::string context = "(" + grading::show(scene.launchAngleDegrees) + " degrees at " +
                                    grading::show(scene.launchSpeed) + " m/s)";
        worst.add(digits.time, context);
        worst.add(digits.range, context);
    }
    CHECK(atLeast(worst, grading::param("floor"), grading::param("target"), "digits at the worst launch"));
}

TEST_CASE("hidden: other speeds and gravity fly the right parabola", "[projectile][hidden]") {
    // A soft throw on the Moon and a hard one on Jupiter, each sampled to just before it lands.
    WorstDigits worst;
    for (const Scene& scene : {launch(35, 10, 1.62), launch(50, 120, 24.79)}) {
        const double flight = exact::flightTime(scene);
        const Run run = simulate(scene, settingsFor(0.95 * flight, flight / 200));
        lastSample(run, 0.95 * flight);
        worst.add(parabolaDigits(scene, run), "(" + grading::show(scene.launchSpeed) + " m/s with g = " +
                                                  grading::show(scene.gravity) + " m/s^2)");
    }
    CHECK(atLeast(worst, grading::param("floor"), grading::param("target"), "digits at the worst launch"));
}

TEST_CASE("hidden: the trade's answer holds on other throws", "[projectile][hidden][trade]") {
    // The same answer on a faster, flatter throw and a slower, steeper one: a setting near the front on one
    // parabola is near it on the next; one tuned to land just so on the question's is not.
    static const simlab::trade::Question variants = simlab::trade::parseQuestion(
#include "trade_hidden.inc"
        , "the projectile's trade-hidden.json");
    gradeTradeVariants<Sample, Scene>(variants, tradeDigits);
}

}  // namespace projectile::testing
