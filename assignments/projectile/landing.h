// The ground hit, the course's way: run the student's simulation until their event handler ends it at the
// ground, and read what it recorded. The lab program and the grader both use this.
#pragma once

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
/// second: a handler that ends the simulation at the ground stops it long before that.
inline Landing simulateLanding(const Scene& scene, simlab::RunSettings run) {
    run.finalTime = 2 * exact::flightTime(scene) + 1;
    Model model;
    const simlab::RunResult<Sample> result = simlab::run<Sample>(scene, model, run);
    return {model.groundHit, result.samples.empty() ? 0 : result.samples.back().time, result.integrator};
}

}  // namespace projectile
