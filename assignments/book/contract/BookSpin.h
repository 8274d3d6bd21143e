// The spinning book: the contract between a student's BookSpin.cpp and the course.
//
// The same five functions as the earlier labs (buildModel -> initialState -> makeIntegrator -> simulate, which
// calls sample), for a book spinning freely about its center: no gravity torque, no air; and cheapestSettings (at
// the end), your answer to the trade question. Do not edit this header.
//
// Frames and names. G is Ground; B is the book, with its origin at the book's center and its axes along the
// book's edges: x along its height, y along its width, z through its thickness. These are the book's central
// principal axes. w_GB is B's angular velocity in G; w_B is that vector expressed in B, whose components
// (wx, wy, wz) the handout calls the b_x, b_y, b_z measures of the angular velocity. H_B is the book's angular
// momentum about its center, expressed in B; H_G the same vector expressed in G. R_GB rotates B's components
// into G's: H_G = R_GB * H_B. SI units.
#pragma once

#include <memory>

#include "Simbody.h"
#include "simlab/multibody_model.h"
#include "simlab/recorder.h"
#include "simlab/run_settings.h"

namespace book {

/// The scene: a uniform book, spun and let go.
struct Scene {
    double mass = 0.4;                               ///< kg
    SimTK::Vec3 dimensions{0.20, 0.30, 0.05};        ///< m: height (x), width (y), thickness (z)
    SimTK::Vec3 w_B0{0.2, 7.0, 0.2};                 ///< rad/s: w_B at t = 0 (the default spins about y)
};

/// One row of results, read from a State.
struct Sample {
    double time = 0;                  ///< s
    SimTK::Vec3 w_B{0};               ///< rad/s: (wx, wy, wz)
    SimTK::Vec3 H_B{0};               ///< kg m^2/s: (Hx, Hy, Hz)
    SimTK::Vec3 H_G{0};               ///< kg m^2/s: H in Ground
    double Hmag = 0;                  ///< kg m^2/s: |H|
    double kineticEnergy = 0;         ///< J: K
};

/// The Simbody model. buildModel adds the book (a body with the mass properties of a uniform brick, on a
/// mobilizer that lets it turn about its center) to `matter`. Nothing needs adding to `forces`: the book is
/// torque-free.
struct Model : simlab::MultibodyModel {
    SimTK::MobilizedBody book;  ///< the book's mobilized body; buildModel sets it
};

/// The book program's defaults: RungeKuttaMerson at accuracy 1e-10 (enough for 8 digits of w(4) in every spin),
/// sampled every 0.01 s for 4 s.
inline simlab::RunSettings defaultRunSettings() {
    simlab::RunSettings run;
    run.accuracy = 1e-10;
    run.finalTime = 4.0;
    return run;
}

/// Add the book for this scene. Do not realize the topology here.
void buildModel(const Scene& scene, Model& model);

/// Realize the topology and return the state at t = 0: the book's axes along Ground's, spinning at w_B0.
SimTK::State initialState(const Scene& scene, const Model& model);

/// The integrator `run` asks for, at its accuracy (and fixed steps of run.dt when run.fixedStep is set).
std::unique_ptr<SimTK::Integrator> makeIntegrator(const Model& model, const simlab::RunSettings& run);

/// Read one row of results from `state`.
Sample sample(const Model& model, const SimTK::State& state);

/// Step from `initial` to run.finalTime, recording sample(...) at t = 0 and at every run.sampleTime(k).
void simulate(const Model& model, SimTK::Integrator& integrator, const SimTK::State& initial,
              const simlab::RunSettings& run, simlab::Recorder<Sample>& recorder);

/// The trade: the integrator and its accuracy (or its fixed step) that keeps 8 accurate digits of w_B at every step
/// of the trade question's spin about an intermediate axis (the one that tumbles) for the fewest evaluations - a book
/// and a spin that are not the lab's default ones: `simlab study trade book --question` says which they are and
/// studies them (in the student bundle, add `--file BookSpin.cpp`). The grader measures your choice on your model
/// from three starts a hair apart, keeps the worst, and holds its evaluations to the work-precision front at the
/// digits it keeps: full credit up to twice the front's cost. Hidden tests hold the same choice to other books.
simlab::RunSettings cheapestSettings();

}  // namespace book
