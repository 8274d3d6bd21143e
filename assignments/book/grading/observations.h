// What the grader observes of a student's book: the JSON form of the Scene it asks about, of the Samples that
// come back, and of the book's mass properties as the student's model gives them (see simlab/wire.h). Shared by
// the probe, which answers, and the judge, which asks.
#pragma once

#include "book/contract/BookSpin.h"
#include "simlab/wire_types.h"

namespace book {

/// The book body's mass properties in the student's model: its mass, the location of its mass center in the
/// body frame, and its central inertia's moments (Ixx, Iyy, Izz) and products (Ixy, Ixz, Iyz).
struct MassObservation {
    double mass = 0;
    SimTK::Vec3 center{0}, moments{0}, products{0};
};

SIMLAB_WIRE(Scene, mass, dimensions, w_B0)
SIMLAB_WIRE(Sample, time, w_B, H_B, H_G, Hmag, kineticEnergy)
SIMLAB_WIRE(MassObservation, mass, center, moments, products)

/// The course's own reading of `state`: what a correct sample() returns, taken from the model the student built
/// without calling their sample(). The trade question and the study measure digits with it, so that they are the
/// digits of the state the integrator reached, not of what a sample() says. H is the system's angular momentum
/// about its mass center, which is the book's.
inline Sample readState(const Model& model, const SimTK::State& state) {
    model.system.realize(state, SimTK::Stage::Velocity);
    const SimTK::Rotation& R_GB = model.book.getBodyRotation(state);
    const SimTK::Vec3 w_B = ~R_GB * model.book.getBodyAngularVelocity(state);
    const SimTK::Vec3 H_G = model.matter.calcSystemCentralMomentum(state)[0];
    return {state.getTime(), w_B, ~R_GB * H_G, H_G, H_G.norm(), model.matter.calcKineticEnergy(state)};
}

}  // namespace book
