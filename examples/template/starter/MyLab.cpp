// A block on a spring, simulated with Simbody.
//
// HOW TO USE THIS FILE
// Every place where you write code holds a line
//
//     SIMLAB_TODO("what to write here");
//
// As shipped the file compiles and runs, and the program stops at the first marker it reaches with that message
// (the grader shows it too). Replace each marker with your code; there are three. The integrator and the stepping
// loop in simulate() are given: read them.
//
// THE PHYSICS
// A block of mass m slides on a frictionless horizontal rail, held by a spring of stiffness k to its rest position.
// One coordinate describes it: x, its position along the rail from the rest position. The spring pulls it back
// with -k x, so m x'' = -k x. Released from rest at x0 it oscillates as x(t) = x0 cos(omega t), omega = sqrt(k / m),
// and its energy stays at k x0^2 / 2.
//
// NAMES
// G is Ground, with the spring's rest position at its origin and the rail along its x axis; B is the block. The
// contract you implement, with the Scene, Sample and Model types, is mylab/MyLab.h.
//
// CHANGE: the starter of your lab: the reference with a SIMLAB_TODO("...") where the student writes code, and a
// comment above each saying which Simbody calls it needs. Keep it compiling; two to five markers is plenty.
#include "mylab/MyLab.h"

#include "simlab/integrators.h"
#include "simlab/todo.h"

namespace mylab {

using namespace SimTK;

void buildModel(const Scene& scene, Model& model) {
    // 1. The model: add to model.matter one body for the block and the mobilizer that lets it move along the rail,
    //    store that mobilized body in model.block, and add the spring to model.forces.
    //    - Mass properties of a point mass: MassProperties(scene.mass_kg, Vec3(0), UnitInertia(0)).
    //    - Give the block only the motion the scene needs: it slides along Ground's x axis. A MobilizedBody::Slider
    //      translates its body along the x axis of its two mobilizer frames:
    //      MobilizedBody::Slider(model.matter.Ground(), Transform(), body, Transform()).
    //    - A spring on the Slider's coordinate, relaxed at q = 0:
    //      Force::MobilityLinearSpring(model.forces, model.block, MobilizerQIndex(0), stiffness, 0.0).
    SIMLAB_TODO("build the model: the block's body, its Slider along Ground's x, and the spring");
}

State initialState(const Scene& scene, const Model& model) {
    // 2. The initial conditions: realize the topology (model.system.realizeTopology() returns the default state),
    //    then set the Slider's coordinate (setOneQ) to the release position and its speed (setOneU) to zero.
    SIMLAB_TODO("set the initial state: the block at rest at scene.releasePosition_m");
}

std::unique_ptr<Integrator> makeIntegrator(const Model& model, const simlab::RunSettings& run) {
    // Given: the integrator run.integrator names, at run.accuracy, stepping at exactly run.dt when asked.
    std::unique_ptr<Integrator> integrator = simlab::integratorNamed(run.integrator, model.system, run.dt);
    integrator->setAccuracy(run.accuracy);
    if (run.fixedStep) integrator->setFixedStepSize(run.dt);
    return integrator;
}

Sample sample(const Model& model, const State& state) {
    // 3. The sampled quantities: the time, x and x' (the Slider's coordinate and speed: getOneQ and getOneU of
    //    model.block), and the mechanical energy (model.system.calcEnergy). Energies need the state realized to
    //    Stage::Dynamics first: model.system.realize(state, Stage::Dynamics).
    SIMLAB_TODO("sample the time, x, x' and the mechanical energy from the state");
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

}  // namespace mylab
