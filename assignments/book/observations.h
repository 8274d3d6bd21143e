// What the grader observes of a student's book: the JSON form of the Scene it asks about, of the Samples that
// come back, and of the book's mass properties as the student's model gives them (see simlab/wire.h). Shared by
// the probe, which answers, and the judge, which asks.
#pragma once

#include "book/BookSpin.h"
#include "simlab/wire.h"

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

}  // namespace book
