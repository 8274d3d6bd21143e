// What the grader observes of a student's pendulum: the JSON form of the Scene it asks about and of the Samples
// that come back (see simlab/wire.h). Shared by the probe, which answers, and the judge, which asks.
#pragma once

#include "pendulum/contract/Pendulum.h"
#include "simlab/wire_types.h"

namespace pendulum {

SIMLAB_WIRE(Scene, mass_kg, length_m, gravity_mps2, releaseAngle_deg, bobRadius_m)
SIMLAB_WIRE(Sample, time, theta_rad, thetaDot_radps, mechanicalEnergy_J)

}  // namespace pendulum
