// A pendulum's swing: the contract between a student's Pendulum.cpp and the course.
//
// The course's `pendulum` program and the grader call the functions below in this order:
//
//     buildModel -> initialState -> makeIntegrator -> simulate (which calls sample at each sampling time)
//
// You write all five in Pendulum.cpp. Do not edit this header: the grader compiles your file against it, and
// varies the Scene and the RunSettings to check that your code simulates rather than recites.
//
// Frames and names. G is Ground, the Newtonian frame: x right, y up, z out of the page. The pivot is at G's
// origin. B is the bob. theta_rad is the rod's angle from the downward vertical (-y of G), counterclockwise about
// z positive; p_GB is the bob's position from the pivot, expressed in G: (L sin theta, -L cos theta, 0).
// SI units throughout, angles in radians except where a name ends in _deg.
#pragma once

#include <memory>

#include "Simbody.h"
#include "simlab/multibody_model.h"
#include "simlab/recorder.h"
#include "simlab/run_settings.h"

namespace pendulum {

/// The physical scene: a point mass on a massless rigid rod, hinged at G's origin. Gravity points along -y of G.
struct Scene {
    double mass_kg = 1.0;            ///< the bob, all its mass at one point
    double length_m = 1.0;           ///< L: from the pivot to the bob
    double gravity_mps2 = 9.81;      ///< g: magnitude of the gravitational acceleration
    double releaseAngle_deg = 150;   ///< theta at t = 0, in degrees from the downward vertical; released from rest
    double bobRadius_m = 0.05;       ///< how big the program draws the bob (it has no size in the physics)
};

/// One row of results, read from a State at one sampling time.
struct Sample {
    double time = 0;                ///< s
    double theta_rad = 0;           ///< the rod's angle from the downward vertical
    double thetaDot_radps = 0;      ///< its rate, d theta / dt
    double mechanicalEnergy_J = 0;  ///< kinetic plus gravitational potential energy (zero at the pivot's height)
};

/// The Simbody model. The course makes the system and its two subsystems (`system`, `matter`, `forces`);
/// buildModel adds the bob on its hinge to `matter`, and gravity to `forces`.
struct Model : simlab::MultibodyModel {
    SimTK::MobilizedBody bob;  ///< the bob's mobilized body; buildModel sets it
};

/// What `pendulum` runs unless told otherwise: 10 s (nearly three periods at 150 degrees) sampled every 0.01 s,
/// RungeKuttaMerson at accuracy 1e-7.
inline simlab::RunSettings defaultRunSettings() {
    simlab::RunSettings run;
    run.finalTime = 10.0;
    return run;
}

/// Puts the scene into `model`: the bob's body on its hinge at G's origin, and gravity. Leaves the topology
/// unrealized, since the course may attach a visualizer once this returns.
void buildModel(const Scene& scene, Model& model);

/// Realizes the topology and gives back the state at t = 0, with the bob at rest at the release angle.
SimTK::State initialState(const Scene& scene, const Model& model);

/// Makes the integrator named by run.integrator (simlab::integratorNamed knows them all) at run.accuracy; with
/// run.fixedStep it steps at exactly run.dt instead.
std::unique_ptr<SimTK::Integrator> makeIntegrator(const Model& model, const simlab::RunSettings& run);

/// What one row of results holds at the time of `state`.
Sample sample(const Model& model, const SimTK::State& state);

/// Advances `initial` to run.finalTime with `integrator`, handing `recorder` the sample at t = 0 and one at each
/// run.sampleTime(k), k = 1 ... run.sampleCount().
void simulate(const Model& model, SimTK::Integrator& integrator, const SimTK::State& initial,
              const simlab::RunSettings& run, simlab::Recorder<Sample>& recorder);

}  // namespace pendulum
