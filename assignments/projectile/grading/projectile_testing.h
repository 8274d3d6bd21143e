// What the projectile's visible and hidden tests share.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "projectile/contract/ProjectileMotion.h"
#include "projectile/program/exact.h"
#include "projectile/program/landing.h"
#include "projectile/grading/observations.h"
#include "projectile/program/run_plot.h"
#include "simlab/digits.h"
#include "simlab/harness/testing.h"

namespace projectile::testing {

namespace grading = simlab::grading;
using namespace simlab::testing;
using Run = simlab::RunResult<Sample>;

inline Run simulate(const Scene& scene, const simlab::RunSettings& settings = defaultRunSettings()) {
    return simlab::testing::simulate<Sample>(scene, settings);
}

/// The trade question (tests/trade-question.json): the scene it is asked on, the digits, and the front.
inline const simlab::trade::Question& tradeQuestion() {
    static const simlab::trade::Question question = simlab::trade::parseQuestion(
#include "trade_question.inc"
        , "the projectile's trade-question.json");
    return question;
}

/// What the trade question counts of a sample of a flight: the digits of x, y and their speeds.
inline std::function<double(const Sample&)> tradeDigits(const Scene& scene, double) {
    return [scene](const Sample& s) { return exact::flightDigits(scene, s); };
}

inline simlab::RunSettings settingsFor(double finalTime, double dt, double accuracy = 1e-7) {
    return simlab::testing::settingsFor(defaultRunSettings(), finalTime, dt, accuracy);
}

inline Scene launch(double angleDegrees, double speed, double gravity = 9.8) {
    Scene s;
    s.launchAngleDegrees = angleDegrees;
    s.launchSpeed = speed;
    s.gravity = gravity;
    return s;
}

/// Worst digits, over the samples, of the height on the parabola y(x) that the launch defines, and where; errors are
/// relative to the flight's peak height, so samples near the ground count like the others.
inline WorstDigits parabolaDigits(const Scene& scene, const Run& run) {
    requireSamples(run);
    WorstDigits worst;
    for (const Sample& s : run.samples) {
        const double expected = exact::yOfX(scene, s.x);
        worst.add(simlab::accuracyDigits(s.y, expected, exact::maxHeight(scene)), "y(x = " + grading::show(s.x) + " m)",
                  s.y, expected, "m");
    }
    return worst;
}

/// The student's simulation of `scene` run until their event handler ends it at the ground (simulateLanding),
/// launched from `depth` metres below the ground's level when it is not zero.
inline Landing observeLanding(const Scene& scene, const simlab::RunSettings& run, double depth = 0) {
    nlohmann::json arguments = {{"scene", simlab::wire::toJson(scene)}, {"settings", simlab::wire::toJson(run)}};
    if (depth != 0) arguments["depth"] = depth;
    return simlab::observe::decode<Landing>(simlab::observe::ask("landing", arguments), "landing");
}

/// The ground hit's digits of time and of range (relative to v0 t*, so a vertical launch counts too), and the values,
/// 0 digits if the student's handler recorded none. Sampled every `dt`: an event handler does not care, a scan of
/// samples does.
struct HitDigits {
    WorstDigits time, range;
};
inline HitDigits groundHitDigits(const Scene& scene, double dt) {
    simlab::RunSettings run = defaultRunSettings();
    run.dt = dt;
    const Landing landing = observeLanding(scene, run);
    {  // said only where nothing was recorded, not beside a later check on what was
        INFO("no ground hit was recorded (the simulation ran to t = " << landing.endTime << " s)");
        CHECK(landing.hit.found);
    }
    HitDigits digits;
    if (!landing.hit.found) {  // none: the check above says why
        digits.time.add(0.0);
        digits.range.add(0.0);
        return digits;
    }
    const double tStar = exact::flightTime(scene), xStar = exact::range(scene);
    digits.time.add(simlab::accuracyDigits(landing.hit.time, tStar), "t*", landing.hit.time, tStar, "s");
    digits.range.add(simlab::accuracyDigits(landing.hit.x, xStar, scene.launchSpeed * tStar), "x*", landing.hit.x,
                     xStar, "m");
    return digits;
}

}  // namespace projectile::testing
