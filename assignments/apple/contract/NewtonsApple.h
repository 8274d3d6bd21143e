// Newton's apple: the contract between a student's NewtonsApple.cpp and the course.
//
// The course's `apple` program and the grader both call the functions below, in this order:
//
//     buildModel -> initialState -> makeIntegrator -> simulate (which calls sample at each sampling time)
//
// You write all five in NewtonsApple.cpp, and cheapestSettings (at the end), your answer to the trade question.
// Do not edit this header: the grader compiles your file against it, and varies the Scene and the RunSettings to
// check that your code simulates rather than recites.
//
// Frames and names. G is Ground, the Newtonian frame: its x axis points right, its y axis up. A is the apple.
// Simbody names a quantity by its frames: p_GA is the position of A's origin from G's origin, expressed in G;
// v_GA is the velocity of A's origin in G, expressed in G. SI units throughout.
#pragma once

#include <memory>

#include "Simbody.h"
#include "simlab/multibody_model.h"
#include "simlab/recorder.h"
#include "simlab/run_settings.h"

namespace apple {

/// The physical scene. Gravity points along -y of Ground.
struct Scene {
    double mass = 0.142;       ///< kg, a 5 oz apple
    double gravity = 9.8;      ///< m/s^2, magnitude of the gravitational acceleration
    double dropHeight = 10.0;  ///< m, height of the apple's center above Ground's origin at t = 0
    double radius = 0.036576;  ///< m, the apple as a uniform sphere (radius of gyration 2.3114 cm)
};

/// One row of results, read from a State at one sampling time.
struct Sample {
    double time = 0;              ///< s
    double yLocation = 0;         ///< m, y of p_GA: the apple's height above Ground's origin
    double yVelocity = 0;         ///< m/s, y of v_GA
    double mechanicalEnergy = 0;  ///< J, kinetic plus gravitational potential energy (zero at y = 0)
};

/// The Simbody model. The course makes the system and its two subsystems (`system`, `matter`, `forces`);
/// buildModel adds the apple (a body with its mass properties, on a mobilizer that connects it to Ground) to
/// `matter`, and gravity to `forces`.
struct Model : simlab::MultibodyModel {
    SimTK::MobilizedBody apple;  ///< the apple's mobilized body; buildModel sets it
};

/// The apple program's defaults: RungeKuttaMerson at accuracy 1e-7, sampled every 0.01 s for 4 s.
inline simlab::RunSettings defaultRunSettings() {
    simlab::RunSettings run;
    run.finalTime = 4.0;
    return run;
}

/// Add the apple and gravity to `model` for this scene. Do not realize the topology here: the course may add
/// things (a visualizer) between buildModel and initialState.
void buildModel(const Scene& scene, Model& model);

/// Realize the model's topology and return the state at t = 0: the apple at rest at the drop height.
SimTK::State initialState(const Scene& scene, const Model& model);

/// The integrator `run` asks for (see simlab::integratorNamed), set to its accuracy, and to fixed steps of
/// run.dt when run.fixedStep is set.
std::unique_ptr<SimTK::Integrator> makeIntegrator(const Model& model, const simlab::RunSettings& run);

/// Read one row of results from `state`.
Sample sample(const Model& model, const SimTK::State& state);

/// Step from `initial` to run.finalTime, recording sample(...) at t = 0 and at every run.sampleTime(k).
void simulate(const Model& model, SimTK::Integrator& integrator, const SimTK::State& initial,
              const simlab::RunSettings& run, simlab::Recorder<Sample>& recorder);

/// The trade: with explicit Euler at fixed steps, the largest step - the fewest evaluations - that keeps 3 accurate
/// digits of y and vy at every step of the trade question's fall, which is not the lab's default one: `simlab study
/// trade apple --question` says which it is and studies it (in the student bundle, add `--file NewtonsApple.cpp`).
/// Return ExplicitEuler with fixedStep set and the step in dt. The grader measures the step on your model from three
/// starts a hair apart, keeps the worst, and holds its evaluations to the fewest that keep the digits there: full
/// credit up to twice as many. Hidden tests hold the same step to other falls like the question's.
simlab::RunSettings cheapestSettings();

}  // namespace apple
