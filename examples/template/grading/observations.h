// What the grader observes of a student's lab: the JSON form of the Scene it asks about and of the Samples that
// come back (see simlab/wire.h). Shared by the probe, which answers, and the judge, which asks.
//
// CHANGE: list every field of your Scene and of your Sample, in any order. A field left out never crosses to the
// judge: the tests could not vary it, or would read it as zero.
#pragma once

#include "mylab/contract/MyLab.h"
#include "simlab/wire_types.h"

namespace mylab {

SIMLAB_WIRE(Scene, mass_kg, stiffness_Npm, releasePosition_m, blockSize_m)
SIMLAB_WIRE(Sample, time, x_m, xDot_mps, mechanicalEnergy_J)

}  // namespace mylab
