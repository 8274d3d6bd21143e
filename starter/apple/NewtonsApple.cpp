// Newton's apple, simulated with Simbody.
//
// HOW TO USE THIS FILE
// Every place where you write code holds a line
//
//     SIMLAB_TODO("what to write here");
//
// As shipped the file compiles and runs, and the program stops at the first marker it reaches with that
// message (the grader shows it too). Replace each marker with your code. There are five: four the program
// needs, then the trade question's answer. The stepping loop in simulate() is yours to read. Rebuild, run with
//
//     cmake --build build && build/bin/apple            check your work with   build/bin/simlab check apple
//
// THE PHYSICS
// The apple is a rigid uniform sphere that only translates vertically in uniform gravity, so one coordinate
// describes it: its height y. Newton's second law, -m g = m y'', gives y'' = -g, and from rest at height h
//     y(t) = h - g t^2 / 2,        y'(t) = -g t,        kinetic + potential energy = m g h.
//
// NAMES
// G is Ground, A the apple. p_GA is the position of A's origin from G's origin, expressed in G; v_GA its
// velocity in G. The contract you implement, with the Scene, Sample and Model types, is apple/NewtonsApple.h.
#include "apple/NewtonsApple.h"

#include "simlab/integrators.h"
#include "simlab/todo.h"

namespace apple {

using namespace SimTK;

void buildModel(const Scene& scene, Model& model) {
    // 1. The model: add to model.matter one body for the apple and the mobilizer that lets it move relative to
    //    Ground, and store that mobilized body in model.apple; then add gravity to model.forces.
    //    - Mass properties: MassProperties(scene.mass, Vec3(0), UnitInertia::sphere(scene.radius)).
    //    - Give the apple only the motion the scene needs: it falls straight down. A MobilizedBody::Slider
    //      translates along the x axis of its two mobilizer frames; rotate both frames by Pi/2 about ZAxis
    //      (Transform(Rotation(Pi / 2, ZAxis), Vec3(0))) so that axis is Ground's y. The Slider's parent is
    //      Ground, model.matter.Ground(): MobilizedBody::Slider(model.matter.Ground(), X_GF, body, X_AM).
    //    - Force::UniformGravity(model.forces, model.matter, Vec3(0, -scene.gravity, 0)).
    SIMLAB_TODO("build the model: the apple's body, its Slider along Ground's y, and gravity");
}

State initialState(const Scene& scene, const Model& model) {
    // 2. The initial conditions: realize the topology (model.system.realizeTopology() returns the default
    //    state), then set the Slider's coordinate (setOneQ) to the drop height and its speed (setOneU) to zero.
    SIMLAB_TODO("set the initial state: the apple at rest at scene.dropHeight");
}

std::unique_ptr<Integrator> makeIntegrator(const Model& model, const simlab::RunSettings& run) {
    // 3. The integrator: simlab::integratorNamed(run.integrator, model.system, run.dt) makes the one asked for.
    //    Set its accuracy to run.accuracy, and when run.fixedStep is true, fix its step at run.dt
    //    (setFixedStepSize).
    SIMLAB_TODO("make the integrator named in run, at run.accuracy");
}

Sample sample(const Model& model, const State& state) {
    // 4. The sampled quantities: time, the y components of p_GA and v_GA (getBodyOriginLocation and
    //    getBodyOriginVelocity of model.apple), and the mechanical energy (model.system.calcEnergy). Energies
    //    need the state realized to Stage::Dynamics first: model.system.realize(state, Stage::Dynamics).
    SIMLAB_TODO("sample the time, y, y velocity and mechanical energy from the state");
}

void simulate(const Model& model, Integrator& integrator, const State& initial, const simlab::RunSettings& run,
              simlab::Recorder<Sample>& recorder) {
    // A TimeStepper advances the state with the integrator; stepTo(t) returns once the state has reached t.
    TimeStepper stepper(model.system, integrator);
    stepper.initialize(initial);
    recorder.record(sample(model, stepper.getState()));
    for (int k = 1; k <= run.sampleCount(); ++k) {
        stepper.stepTo(run.sampleTime(k));
        recorder.record(sample(model, stepper.getState()));
    }
}

simlab::RunSettings cheapestSettings() {
    // 5. The trade (handout, section 7): explicit Euler's largest fixed step that keeps 3 digits of the trade
    //    question's fall. Work it out from Euler's error, then measure it:
    //    `build/bin/simlab study trade apple --question` (in the student bundle, add `--file NewtonsApple.cpp`).
    //    Return ExplicitEuler, fixedStep = true, dt.
    SIMLAB_TODO("explicit Euler's largest fixed step that keeps 3 digits of the question's fall");
}

}  // namespace apple
