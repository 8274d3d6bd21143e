// Projectile motion: the contract between a student's ProjectileMotion.cpp and the course.
//
// The same five functions as Newton's apple (buildModel -> initialState -> makeIntegrator -> simulate, which
// calls sample), for a baseball flying in the vertical x-y plane of Ground. One thing is new: buildModel also adds
// an event handler that watches the ball's height, and when it comes back down through y = 0 records the time
// and range of the ground hit in model.groundHit and ends the simulation. cheapestSettings (at the end) is your
// answer to the trade question. Do not edit this header.
//
// Frames and names. G is Ground (x right, y up); B is the ball. p_GB is the position of B's origin from G's
// origin, expressed in G; v_GB its velocity in G. SI units, angles in degrees where a name says so.
#pragma once

#include <cmath>
#include <memory>

#include "Simbody.h"
#include "simlab/multibody_model.h"
#include "simlab/recorder.h"
#include "simlab/run_settings.h"

namespace projectile {

/// The scene: a baseball hit from Ground's origin. Gravity points along -y of Ground.
struct Scene {
    double mass = 0.142;                 ///< kg (5 oz)
    double radiusOfGyration = 0.023114;  ///< m (0.91 in): the ball's moment of inertia is mass * k^2
    double gravity = 9.8;                ///< m/s^2
    double launchSpeed = 44.7;           ///< m/s (100 mph)
    double launchAngleDegrees = 35;      ///< degrees above the horizontal (+x), in (0, 90]
    double groundHitWindow = 1e-6;       ///< s: Simbody must localize the ground hit to within this time window
};

/// One row of results, read from a State.
struct Sample {
    double time = 0;              ///< s
    double x = 0;                 ///< m, x of p_GB
    double y = 0;                 ///< m, y of p_GB: the height above the ground
    double xVelocity = 0;         ///< m/s, x of v_GB
    double yVelocity = 0;         ///< m/s, y of v_GB
    double mechanicalEnergy = 0;  ///< J, kinetic plus gravitational potential energy (zero at y = 0)
};

/// Where and when the ball came back to the ground, as the event handler found it.
struct GroundHit {
    bool found = false;
    double time = NAN;  ///< s
    double x = NAN;     ///< m, the range
};

/// The Simbody model. buildModel adds the ball and its mobilizers to `matter`, gravity to `forces`, and the
/// ground-hit event handler to `system`; the handler writes to `groundHit`.
struct Model : simlab::MultibodyModel {
    SimTK::MobilizedBody ball;  ///< the ball's mobilized body; buildModel sets it
    GroundHit groundHit;        ///< filled in by the event handler when the ball lands
};

/// The projectile program's defaults: RungeKuttaMerson at accuracy 1e-7, sampled every 0.01 s for 5.23 s.
inline simlab::RunSettings defaultRunSettings() {
    simlab::RunSettings run;
    run.finalTime = 5.23;
    return run;
}

/// Add the ball, gravity and the ground-hit event handler for this scene. Do not realize the topology here.
void buildModel(const Scene& scene, Model& model);

/// Realize the topology and return the state at t = 0: the ball at Ground's origin with the launch velocity.
SimTK::State initialState(const Scene& scene, const Model& model);

/// The integrator `run` asks for, at its accuracy (and fixed steps of run.dt when run.fixedStep is set).
std::unique_ptr<SimTK::Integrator> makeIntegrator(const Model& model, const simlab::RunSettings& run);

/// Read one row of results from `state`.
Sample sample(const Model& model, const SimTK::State& state);

/// Step from `initial`, recording sample(...) at t = 0 and at every run.sampleTime(k) up to run.finalTime, or
/// up to the moment the ground-hit event ends the simulation (then record that state last).
void simulate(const Model& model, SimTK::Integrator& integrator, const SimTK::State& initial,
              const simlab::RunSettings& run, simlab::Recorder<Sample>& recorder);

/// The trade: the integrator and its accuracy (or its fixed step) that keeps 10 accurate digits of x, y and their
/// speeds at every step of the trade question's flight, to the ground hit, for the fewest evaluations - a throw that
/// is not the lab's default one: `simlab study trade projectile --question` says which it is and studies it (in the
/// student bundle, add `--file ProjectileMotion.cpp`). The grader measures your choice on your model from three
/// starts a hair apart, keeps the worst, and holds its evaluations to the work-precision front at the digits it
/// keeps: full credit up to twice the front's cost. Hidden tests hold the same choice to other throws.
simlab::RunSettings cheapestSettings();

}  // namespace projectile
