// What the grader observes of a student's projectile: the JSON form of the Scene it asks about, of the Samples
// that come back and of the ground hit their event handler finds (see simlab/wire.h). Shared by the probe, which
// answers, and the judge, which asks.
#pragma once

#include "projectile/contract/ProjectileMotion.h"
#include "projectile/program/landing.h"
#include "simlab/wire_types.h"

namespace projectile {

SIMLAB_WIRE(Scene, mass, radiusOfGyration, gravity, launchSpeed, launchAngleDegrees, groundHitWindow)
SIMLAB_WIRE(Sample, time, x, y, xVelocity, yVelocity, mechanicalEnergy)
SIMLAB_WIRE(GroundHit, found, time, x)
SIMLAB_WIRE(Landing, hit, endTime, integrator)

/// The course's own reading of `state`: what a correct sample() returns, taken from the model the student built
/// without calling their sample(). The trade question and the study measure digits with it, so that they are the
/// digits of the state the integrator reached, not of what a sample() says.
inline Sample readState(const Model& model, const SimTK::State& state) {
    model.system.realize(state, SimTK::Stage::Dynamics);
    const SimTK::Vec3 p_GB = model.ball.getBodyOriginLocation(state);
    const SimTK::Vec3 v_GB = model.ball.getBodyOriginVelocity(state);
    return {state.getTime(), p_GB[SimTK::XAxis], p_GB[SimTK::YAxis], v_GB[SimTK::XAxis], v_GB[SimTK::YAxis],
            model.system.calcEnergy(state)};
}

}  // namespace projectile
