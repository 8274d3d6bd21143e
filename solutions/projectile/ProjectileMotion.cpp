// Projectile motion, simulated with Simbody (reference solution).
//
// A baseball flies from Ground's origin at speed v0 and angle theta, with gravity and nothing else. It does not
// need to turn, and stays in the vertical x-y plane, so two coordinates describe it: x and y. Newton's second law
// gives x'' = 0 and y'' = -g, and from the launch
//     x(t) = v0 cos(theta) t,        y(t) = v0 sin(theta) t - g t^2 / 2,
// back at the ground (y = 0) at t* = 2 v0 sin(theta) / g and x* = v0 cos(theta) t*.
// The model: two Sliders in series, one along Ground's x carrying a massless frame, one along y carrying the
// ball; and an event handler that watches y and stops the simulation when the ball comes back down to 0.
//
// Names follow Simbody: G is Ground, B the ball; p_GB is the position of B's origin from G's origin, expressed
// in G; v_GB its velocity in G.
#include "projectile/ProjectileMotion.h"

#include "simlab/integrators.h"

namespace projectile {

using namespace SimTK;

namespace {

// Watches the ball's height and, when it falls through zero, records the time and range of the hit in
// `hit` and ends the simulation. Simbody localizes the sign change to within the trigger's time window.
class GroundHitHandler : public TriggeredEventHandler {
public:
    GroundHitHandler(const MobilizedBody& ball, GroundHit& hit, double window)
        : TriggeredEventHandler(Stage::Position), ball_(ball), hit_(hit) {
        getTriggerInfo().setTriggerOnRisingSignTransition(false);  // only on the way down
        getTriggerInfo().setRequiredLocalizationTimeWindow(window);
    }

    Real getValue(const State& state) const override { return ball_.getBodyOriginLocation(state)[YAxis]; }

    void handleEvent(State& state, Real /*accuracy*/, bool& shouldTerminate) const override {
        hit_.found = true;
        hit_.time = state.getTime();
        hit_.x = ball_.getBodyOriginLocation(state)[XAxis];
        shouldTerminate = true;
    }

private:
    const MobilizedBody& ball_;
    GroundHit& hit_;
};

}  // namespace

void buildModel(const Scene& scene, Model& model) {
    // A uniform ball: its inertia is the same about every axis through its center, m k^2.
    const double k = scene.radiusOfGyration;
    const Body::Rigid ballBody(MassProperties(scene.mass, Vec3(0), UnitInertia(k * k)));

    // Horizontal motion: a Slider along Ground's x, carrying a massless frame H.
    MobilizedBody::Slider horizontal(model.matter.Ground(), Transform(), Body::Massless(), Transform());
    // Vertical motion: a Slider along H's y (both mobilizer frames turned 90 degrees about z), carrying the ball.
    const Transform X_HF(Rotation(Pi / 2, ZAxis), Vec3(0));
    const Transform X_BM(Rotation(Pi / 2, ZAxis), Vec3(0));
    model.ball = MobilizedBody::Slider(horizontal, X_HF, ballBody, X_BM);

    // Uniform gravity along -y of Ground; its potential energy is zero at y = 0.
    Force::UniformGravity(model.forces, model.matter, Vec3(0, -scene.gravity, 0));

    // The system adopts (and later deletes) the handler.
    model.system.addEventHandler(new GroundHitHandler(model.ball, model.groundHit, scene.groundHitWindow));
}

State initialState(const Scene& scene, const Model& model) {
    State state = model.system.realizeTopology();
    // The ball starts at the origin (all coordinates zero); set the two Sliders' speeds to the launch velocity.
    const double theta = scene.launchAngleDegrees * Pi / 180;  // radians, for sin and cos
    const MobilizedBody& horizontal = model.ball.getParentMobilizedBody();
    horizontal.setOneU(state, 0, scene.launchSpeed * std::cos(theta));
    model.ball.setOneU(state, 0, scene.launchSpeed * std::sin(theta));
    return state;
}

std::unique_ptr<Integrator> makeIntegrator(const Model& model, const simlab::RunSettings& run) {
    std::unique_ptr<Integrator> integrator = simlab::integratorNamed(run.integrator, model.system, run.dt);
    integrator->setAccuracy(run.accuracy);
    if (run.fixedStep) integrator->setFixedStepSize(run.dt);
    return integrator;
}

Sample sample(const Model& model, const State& state) {
    model.system.realize(state, Stage::Dynamics);
    const Vec3 p_GB = model.ball.getBodyOriginLocation(state);
    const Vec3 v_GB = model.ball.getBodyOriginVelocity(state);
    return {state.getTime(), p_GB[XAxis], p_GB[YAxis], v_GB[XAxis], v_GB[YAxis], model.system.calcEnergy(state)};
}

void simulate(const Model& model, Integrator& integrator, const State& initial, const simlab::RunSettings& run,
              simlab::Recorder<Sample>& recorder) {
    TimeStepper stepper(model.system, integrator);
    stepper.initialize(initial);
    recorder.record(sample(model, stepper.getState()));
    for (int k = 1; k <= run.sampleCount(); ++k) {
        stepper.stepTo(run.sampleTime(k));
        recorder.record(sample(model, stepper.getState()));
        if (integrator.isSimulationOver()) break;  // the ground hit ended it
    }
}

simlab::RunSettings cheapestSettings() {
    // `simlab study trade projectile`: the flight's acceleration is constant too, so a second-order method at the
    // loosest accuracy keeps every digit, and Verlet gets there in the fewest evaluations (29).
    simlab::RunSettings choice;
    choice.integrator = "Verlet";
    choice.accuracy = 0.1;
    return choice;
}

}  // namespace projectile
