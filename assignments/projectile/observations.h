// What the grader observes of a student's projectile: the JSON form of the Scene it asks about, of the Samples
// that come back and of the ground hit their event handler finds (see simlab/wire.h). Shared by the probe, which
// answers, and the judge, which asks.
#pragma once

#include "projectile/ProjectileMotion.h"
#include "projectile/landing.h"
#include "simlab/wire.h"

namespace projectile {

SIMLAB_WIRE(Scene, mass, radiusOfGyration, gravity, launchSpeed, launchAngleDegrees, groundHitWindow)
SIMLAB_WIRE(Sample, time, x, y, xVelocity, yVelocity, mechanicalEnergy)
SIMLAB_WIRE(GroundHit, found, time, x)
SIMLAB_WIRE(Landing, hit, endTime, integrator)

}  // namespace projectile
