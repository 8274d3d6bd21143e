// A pendulum's swing, simulated with Simbody (reference solution).
//
// The bob is a point mass m on a massless rod of length L that turns about a fixed pivot in a vertical plane, so
// one coordinate describes it: the rod's angle theta from the downward vertical. Gravity's torque about the pivot
// gives theta'' = -(g / L) sin theta; from rest at theta0 the energy keeps its value -m g L cos theta0 and the
// swing repeats with the period T = 4 K(sin(theta0 / 2)) sqrt(L / g). The model is one body on one rotational
// mobility about Ground's z axis: a Pin.
//
// Names follow Simbody: G is Ground, B the bob, M the Pin's frame on the bob and F its frame on Ground; p_GB is
// the position of B's origin from G's origin, expressed in G; X_BM the transform giving M's pose in B.
#include "pendulum/Pendulum.h"

#include "simlab/integrators.h"

namespace pendulum {

using namespace SimTK;

void buildModel(const Scene& scene, Model& model) {
    // The bob: all its mass at the body's origin, no inertia about it (a point mass).
    const Body::Rigid bobBody(MassProperties(scene.mass_kg, Vec3(0), UnitInertia(0)));

    // A Pin turns its body about the z axis its two frames share. F is G itself (the pivot at G's origin); M sits
    // L above the bob's origin, so at q = 0 the bob hangs L below the pivot and q is theta, counterclockwise.
    const Transform X_GF;                              // the pivot, fixed in Ground
    const Transform X_BM(Vec3(0, scene.length_m, 0));  // the pivot, seen from the bob
    model.bob = MobilizedBody::Pin(model.matter.Ground(), X_GF, bobBody, X_BM);

    // Uniform gravity along -y of Ground; its potential energy is zero at y = 0, the pivot's height.
    Force::UniformGravity(model.forces, model.matter, Vec3(0, -scene.gravity_mps2, 0));
}

State initialState(const Scene& scene, const Model& model) {
    State state = model.system.realizeTopology();
    // The Pin's one coordinate q is theta in radians, its one speed u = theta'.
    const double theta0_rad = scene.releaseAngle_deg * Pi / 180;
    model.bob.setOneQ(state, 0, theta0_rad);
    model.bob.setOneU(state, 0, 0.0);  // released from rest
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
    const double theta_rad = model.bob.getOneQ(state, 0);
    const double thetaDot_radps = model.bob.getOneU(state, 0);
    return {state.getTime(), theta_rad, thetaDot_radps, model.system.calcEnergy(state)};
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

}  // namespace pendulum
