// What the grader observes of a student's apple: the JSON form of the Scene it asks about and of the Samples
// that come back (see simlab/wire.h). Shared by the probe, which answers, and the judge, which asks.
#pragma once

#include "apple/contract/NewtonsApple.h"
#include "simlab/wire_types.h"

namespace apple {

SIMLAB_WIRE(Scene, mass, gravity, dropHeight, radius)
SIMLAB_WIRE(Sample, time, yLocation, yVelocity, mechanicalEnergy)

/// The course's own reading of `state`: what a correct sample() returns, taken from the model the student built
/// without calling their sample(). The trade question and the study measure digits with it, so that they are the
/// digits of the state the integrator reached, not of what a sample() says.
inline Sample readState(const Model& model, const SimTK::State& state) {
    model.system.realize(state, SimTK::Stage::Dynamics);
    const SimTK::Vec3 p_GA = model.apple.getBodyOriginLocation(state);
    const SimTK::Vec3 v_GA = model.apple.getBodyOriginVelocity(state);
    return {state.getTime(), p_GA[SimTK::YAxis], v_GA[SimTK::YAxis], model.system.calcEnergy(state)};
}

}  // namespace apple
