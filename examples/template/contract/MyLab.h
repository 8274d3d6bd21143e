// A block on a spring: the contract between a student's MyLab.cpp and the course.
//
// The course's program and the grader call the functions below in this order:
//
//     buildModel -> initialState -> makeIntegrator -> simulate (which calls sample at each sampling time)
//
// You write all five in MyLab.cpp. Do not edit this header: the grader compiles your file against it, and varies
// the Scene and the RunSettings to check that your code simulates rather than recites.
//
// Frames and names. G is Ground, the Newtonian frame: x along the rail, y up, z out of the page. B is the block.
// x_m is the position of B's origin along G's x axis, measured from the spring's rest position (G's origin).
// SI units throughout; each name ends in its unit.
//
// CHANGE: the Scene (your scene's numbers, with their defaults), the Sample (what one row of results holds) and the
// Model's mobilized bodies. Keep the five functions and their signatures: the course's driver, the probe and the
// tests call exactly these.
#pragma once

#include <memory>

#include "Simbody.h"
#include "simlab/multibody_model.h"
#include "simlab/recorder.h"
#include "simlab/run_settings.h"

namespace mylab {

/// The physical scene: a block on a horizontal rail, held by a linear spring to its rest position at G's origin.
struct Scene {
    double mass_kg = 2.0;             ///< m: the block
    double stiffness_Npm = 50.0;      ///< k: the spring, N/m
    double releasePosition_m = 0.1;   ///< x0: where the block is let go, at rest, at t = 0
    double blockSize_m = 0.05;        ///< how big the program draws the block (it has no size in the physics)
};

/// One row of results, read from a State at one sampling time.
struct Sample {
    double time = 0;                ///< s
    double x_m = 0;                 ///< the block's position along the rail, from the spring's rest position
    double xDot_mps = 0;            ///< its velocity, dx/dt
    double mechanicalEnergy_J = 0;  ///< kinetic plus the spring's potential energy
};

/// The Simbody model. The course makes the system and its two subsystems (`system`, `matter`, `forces`);
/// buildModel adds the block on its rail to `matter`, and the spring to `forces`.
struct Model : simlab::MultibodyModel {
    SimTK::MobilizedBody block;  ///< the block's mobilized body; buildModel sets it
};

/// What the program runs unless told otherwise: 5 s (about four periods) sampled every 0.01 s, RungeKuttaMerson
/// at accuracy 1e-7.
inline simlab::RunSettings defaultRunSettings() {
    simlab::RunSettings run;
    run.finalTime = 5.0;
    return run;
}

/// Puts the scene into `model`: the block's body on its rail, and the spring. Leaves the topology unrealized, since
/// the course may attach a visualizer once this returns.
void buildModel(const Scene& scene, Model& model);

/// Realizes the topology and gives back the state at t = 0, with the block at rest at the release position.
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

}  // namespace mylab
