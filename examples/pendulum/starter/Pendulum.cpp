// A pendulum's swing, simulated with Simbody.
//
// HOW TO USE THIS FILE
// Every place where you write code holds a line
//
//     SIMLAB_TODO("what to write here");
//
// As shipped the file compiles and runs, and the program stops at the first marker it reaches with that
// message (the grader shows it too). Replace each marker with your code; there are four. The stepping loop in
// simulate() is yours to read. Rebuild, run with
//
//     cmake --build build && build/bin/pendulum            check your work with   build/bin/simlab check pendulum
//
// THE PHYSICS
// The bob is a point mass m on a massless rod of length L, hinged at a fixed pivot and swinging in a vertical
// plane, so one coordinate describes it: theta, the rod's angle from the downward vertical. Gravity's torque
// about the pivot gives theta'' = -(g / L) sin theta. Released from rest at theta0 its energy stays at
// -m g L cos theta0 (zero at the pivot's height), and it swings back and forth with a period that grows with
// theta0: T = 4 K(sin(theta0 / 2)) sqrt(L / g), well past the small-swing 2 pi sqrt(L / g) at 150 degrees.
//
// NAMES
// G is Ground, with the pivot at its origin; B is the bob. p_GB is the position of B's origin from G's origin,
// expressed in G: (L sin theta, -L cos theta, 0). The contract you implement, with the Scene, Sample and Model
// types, is pendulum/Pendulum.h.
#include "pendulum/Pendulum.h"

#include "simlab/integrators.h"
#include "simlab/todo.h"

namespace pendulum {

using namespace SimTK;

void buildModel(const Scene& scene, Model& model) {
    // 1. The model: add to model.matter one body for the bob and the mobilizer that hinges it to Ground, store
    //    that mobilized body in model.bob, and add gravity to model.forces.
    //    - Mass properties of a point mass: MassProperties(scene.mass_kg, Vec3(0), UnitInertia(0)).
    //    - Give the bob only the motion the scene needs: it turns about the pivot, in the x-y plane. A
    //      MobilizedBody::Pin turns its body about the z axis of its two mobilizer frames:
    //      MobilizedBody::Pin(model.matter.Ground(), X_GF, body, X_BM). X_GF places the pivot in Ground (at its
    //      origin); X_BM places the pivot in the bob's frame, L above the bob (Transform(Vec3(0, L, 0))), so that
    //      at q = 0 the bob hangs straight down.
    //    - Force::UniformGravity(model.forces, model.matter, Vec3(0, -scene.gravity_mps2, 0)).
    SIMLAB_TODO("build the model: the bob's body, its Pin to Ground at the pivot, and gravity");
}

State initialState(const Scene& scene, const Model& model) {
    // 2. The initial conditions: realize the topology (model.system.realizeTopology() returns the default
    //    state), then set the Pin's coordinate (setOneQ) to the release angle - in radians, while the scene gives
    //    it in degrees - and its speed (setOneU) to zero.
    SIMLAB_TODO("set the initial state: the bob at rest at scene.releaseAngle_deg");
}

std::unique_ptr<Integrator> makeIntegrator(const Model& model, const simlab::RunSettings& run) {
    // 3. The integrator, as in the apple lab: the one run.integrator names, from
    //    simlab::integratorNamed(run.integrator, model.system, run.dt), at run.accuracy (setAccuracy), stepping at
    //    exactly run.dt (setFixedStepSize) when run.fixedStep says so.
    SIMLAB_TODO("make the integrator named in run, at run.accuracy");
}

Sample sample(const Model& model, const State& state) {
    // 4. The sampled quantities: the time, theta and theta' (the Pin's coordinate and speed: getOneQ and getOneU
    //    of model.bob), and the mechanical energy (model.system.calcEnergy). Energies need the state realized to
    //    Stage::Dynamics first: model.system.realize(state, Stage::Dynamics).
    SIMLAB_TODO("sample the time, theta, theta' and the mechanical energy from the state");
}

void simulate(const Model& model, Integrator& integrator, const State& initial, const simlab::RunSettings& run,
              simlab::Recorder<Sample>& recorder) {
    // Given: a TimeStepper moves the state forward with your integrator, and stepTo(t) comes back at time t.
    TimeStepper stepper(model.system, integrator);
    stepper.initialize(initial);
    recorder.record(sample(model, stepper.getState()));
    for (int k = 1; k <= run.sampleCount(); ++k) {
        stepper.stepTo(run.sampleTime(k));
        recorder.record(sample(model, stepper.getState()));
    }
}

}  // namespace pendulum
