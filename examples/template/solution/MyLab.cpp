// A block on a spring, simulated with Simbody (reference solution).
//
// The block slides on a frictionless horizontal rail, so one coordinate describes it: its position x along the
// rail, from the spring's rest position. The spring pulls it back with -k x, so m x'' = -k x; released from rest
// at x0 it oscillates as x0 cos(omega t), omega = sqrt(k / m), and its energy stays at k x0^2 / 2. The model is one
// body on one translational mobility along Ground's x axis (a Slider), with a linear spring on that mobility.
//
// CHANGE: the reference for your scene. It must earn every point, hidden tests included (simlab assignment verify
// checks that). Keep the five functions of the contract; simulate() rarely needs changing.
#include "mylab/MyLab.h"

#include "simlab/integrators.h"

namespace mylab {

using namespace SimTK;

void buildModel(const Scene& scene, Model& model) {
    // The block: all its mass at the body's origin (a point mass; it only translates, so inertia plays no part).
    const Body::Rigid blockBody(MassProperties(scene.mass_kg, Vec3(0), UnitInertia(0)));

    // A Slider translates its body along the x axis its two frames share; both frames are the bodies' own, so the
    // Slider's coordinate q is x, the block's position along Ground's x axis.
    model.block = MobilizedBody::Slider(model.matter.Ground(), Transform(), blockBody, Transform());

    // The spring acts on that coordinate: force -k (q - 0) along the rail, potential energy k q^2 / 2.
    Force::MobilityLinearSpring(model.forces, model.block, MobilizerQIndex(0), scene.stiffness_Npm, 0.0);
}

State initialState(const Scene& scene, const Model& model) {
    State state = model.system.realizeTopology();
    model.block.setOneQ(state, 0, scene.releasePosition_m);
    model.block.setOneU(state, 0, 0.0);  // released from rest
    return state;
}

std::unique_ptr<Integrator> makeIntegrator(const Model& model, const simlab::RunSettings& run) {
    std::unique_ptr<Integrator> integrator = simlab::integratorNamed(run.integrator, model.system, run.dt);
    integrator->setAccuracy(run.accuracy);
    if (run.fixedStep) integrator->setFixedStepSize(run.dt);
    return integrator;
}

Sample sample(const Model& model, const State& state) {
    // Energies need forces, which Simbody computes at the Dynamics stage.
    model.system.realize(state, Stage::Dynamics);
    return {state.getTime(), model.block.getOneQ(state, 0), model.block.getOneU(state, 0),
            model.system.calcEnergy(state)};
}

void simulate(const Model& model, Integrator& integrator, const State& initial, const simlab::RunSettings& run,
              simlab::Recorder<Sample>& recorder) {
    TimeStepper stepper(model.system, integrator);
    stepper.initialize(initial);
    recorder.record(sample(model, stepper.getState()));
    for (int k = 1; k <= run.sampleCount(); ++k) {
        stepper.stepTo(run.sampleTime(k));
        recorder.record(sample(model, stepper.getState()));
    }
}

}  // namespace mylab
