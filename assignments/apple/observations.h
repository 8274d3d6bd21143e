// What the grader observes of a student's apple: the JSON form of the Scene it asks about and of the Samples
// that come back (see simlab/wire.h). Shared by the probe, which answers, and the judge, which asks.
#pragma once

#include "apple/NewtonsApple.h"
#include "simlab/wire.h"

namespace apple {

SIMLAB_WIRE(Scene, mass, gravity, dropHeight, radius)
SIMLAB_WIRE(Sample, time, yLocation, yVelocity, mechanicalEnergy)

}  // namespace apple
