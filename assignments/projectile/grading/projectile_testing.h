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

/// Worst digits, over the samples, of the height on the parabola y(x) that the launch defines; errors are
/// relative to the flight's peak height, so samples near the ground count like the others.
inline double parabolaDigits(const Scene& scene, const Run& run) {
    requireSamples(run);
    double worst = simlab::kMaxDigits;
    for (const Sample& s : run.samples) {
        worst = std::min(worst, simlab::accuracyDigits(s.y, exact::yOfX(scene, s.x), exact::maxHeight(scene)));
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

/// The ground hit's digits of time and of range (relative to v0 t*, so a vertical launch counts too), 0 if the
/// student's handler recorded none. Sampled every `dt`: an event handler does not care, a scan of samples does.
struct HitDigits {
    double time = 0, range = 0;
};
inline HitDigits groundHitDigits(const Scene& scene, double dt) {
    simlab::RunSettings run = defaultRunSettings();
    run.dt = dt;
    const Landing landing = observeLanding(scene, run);
    {  // said only where nothing was recorded, not beside a later check on what was
        INFO("no ground hit was recorded (the simulation ran to t = " << landing.endTime << " s)");
        CHECK(landing.hit.found);
    }
    if (!landing.hit.found) return {};
    const double tStar = exact::flightTime(scene);
    return {simlab::accuracyDigits(landing.hit.time, tStar),
            simlab::accuracyDigits(landing.hit.x, exact::range(scene), scene.launchSpeed * tStar)};
}

}  // namespace projectile::testing
