// The ground hit, the course's way: run the student's simulation until their event handler ends it at the
// ground, and read what it recorded. The lab program and the grader both use this.
#pragma once

#include <algorithm>
#include <cstdio>
#include <functional>
#include <stdexcept>

#include "projectile/ProjectileMotion.h"
#include "projectile/exact.h"
#include "simlab/driver.h"

namespace projectile {

struct Landing {
    GroundHit hit;                      ///< what the student's handler recorded (found = false if nothing)
    double endTime = 0;                 ///< s, the time of the last sample: where the simulation stopped
    simlab::IntegratorStats integrator;
};

/// Simulate `scene` with `run` (its dt and integrator settings) for up to twice the exact flight time plus a
/// second: a handler that ends the simulation at the ground stops it long before that. The samples are only where
/// the simulation may stop, so with error control their interval is fitted to the flight: at most a twentieth of
/// it, so that the ball is seen in the air before it comes down (a flight shorter than dt would otherwise start
/// and end inside the first sampling interval), and no more than a hundred thousand of them over a flight of
/// days. At fixed steps dt is the step, and a flight it cannot resolve is an error (std::invalid_argument).
inline Landing simulateLanding(const Scene& scene, simlab::RunSettings run,
                               const std::function<void(const Sample&)>& onSample = {}) {
    const double tStar = exact::flightTime(scene);
    run.finalTime = 2 * tStar + std::min(1.0, 100 * std::min(run.dt, tStar / 20));
    if (!run.fixedStep) {
        run.dt = std::max(std::min(run.dt, tStar / 20), run.finalTime / 1e5);
    } else if (run.dt > tStar / 4) {
        char what[200];
        std::snprintf(what, sizeof what, "the flight lasts t* = %.3g s, too short for fixed steps of --dt %g s to "
                      "see it; use --dt %.2g or smaller", tStar, run.dt, tStar / 20);
        throw std::invalid_argument(what);
    } else if (run.finalTime / run.dt > 1e7) {
        char what[200];
        std::snprintf(what, sizeof what, "the flight lasts t* = %.3g s: at fixed steps of --dt %g s that is %.2g "
                      "steps, over ten million; use a larger --dt", tStar, run.dt, tStar / run.dt);
        throw std::invalid_argument(what);
    }
    Model model;
    const simlab::RunResult<Sample> result = simlab::run<Sample>(scene, model, run, onSample);
    return {model.groundHit, result.samples.empty() ? 0 : result.samples.back().time, result.integrator};
}

}  // namespace projectile
