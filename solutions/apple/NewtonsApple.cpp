// Newton's apple, simulated with Simbody (reference solution).
//
// The apple is a rigid uniform sphere that only translates vertically in uniform gravity, so one coordinate
// describes it: its height y. Newton's second law, -m g = m y'', gives y'' = -g, and from rest at height h
//     y(t) = h - g t^2 / 2,        y'(t) = -g t,        kinetic + potential energy = m g h.
// The model therefore has one body on one translational mobility along Ground's y axis: a Slider.
//
// Names follow Simbody: G is Ground, A the apple; p_GA is the position of A's origin from G's origin,
// expressed in G; v_GA its velocity in G; X_GF the transform giving frame F's pose in G.
#include "apple/NewtonsApple.h"

#include "simlab/integrators.h"

namespace apple {

using namespace SimTK;

void buildModel(const Scene& scene, Model& model) {
    // The apple: a uniform sphere whose center of mass is at the body's origin.
    const Body::Rigid appleBody(MassProperties(scene.mass, Vec3(0), UnitInertia::sphere(scene.radius)));

    // A Slider lets its body translate along the x axis of its mobilizer frames. Turning both frames +90 degrees
    // about z lines that axis up with Ground's y, and keeps the apple's own axes parallel to Ground's.
    const Rotation R_GF(Pi / 2, ZAxis);  // F, the inboard frame, fixed in Ground at its origin
    const Rotation R_AM(Pi / 2, ZAxis);  // M, the outboard frame, fixed in the apple at its center
    model.apple = MobilizedBody::Slider(model.matter.Ground(), Transform(R_GF, Vec3(0)),
                                        appleBody, Transform(R_AM, Vec3(0)));

    // Uniform gravity pulls every body along -y of Ground; its potential energy is zero at y = 0.
    // Like the body above, the force is a handle: the force subsystem keeps what it refers to.
    Force::UniformGravity(model.forces, model.matter, Vec3(0, -scene.gravity, 0));
}

State initialState(const Scene& scene, const Model& model) {
    State state = model.system.realizeTopology();
    // The Slider's one coordinate q is the distance along its axis (Ground's y), its one speed u = q'.
    model.apple.setOneQ(state, 0, scene.dropHeight);
    model.apple.setOneU(state, 0, 0.0);  // dropped from rest
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
    const Vec3 p_GA = model.apple.getBodyOriginLocation(state);
    const Vec3 v_GA = model.apple.getBodyOriginVelocity(state);
    return {state.getTime(), p_GA[YAxis], v_GA[YAxis], model.system.calcEnergy(state)};
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

simlab::RunSettings cheapestSettings() {
    // The trade question's fall (`simlab study trade apple --question`): h = 100 m, g = 9.8 m/s^2, T = 2 s.
    // Explicit Euler's error in y at time t is g t dt / 2 (its vy is exact); the digits count it against the
    // height the fall spans, the larger of h and g T^2 / 2 (here h), and it is largest at T. 3 digits need
    // g T dt / 2 <= 1e-3 h, so dt <= 2e-3 h / (g T) = 1.02e-2 s. A little under that, for a margin: 1e-2 s,
    // 200 steps (the study's steps of 6e-3 s and 2e-2 s keep 3.2 and 2.7 digits: the answer lies between).
    simlab::RunSettings choice;
    choice.integrator = "ExplicitEuler";
    choice.fixedStep = true;
    choice.dt = 1e-2;
    return choice;
}

}  // namespace apple
