// Projectile motion, simulated with Simbody.
//
// HOW TO USE THIS FILE
// As in Newton's apple, every place where you write code holds a line
//
//     SIMLAB_TODO("what to write here");
//
// and the program stops at the first one it reaches. Replace each with your code; much of it is your apple,
// modified. Rebuild and run with
//
//     cmake --build build && build/bin/projectile       check your work with   build/bin/simlab check projectile
//
// THE PHYSICS
// A baseball flies from Ground's origin at speed v0 and angle theta, with gravity and nothing else. It does not
// need to turn and stays in the vertical x-y plane, so two coordinates describe it: x and y. Newton's second
// law gives x'' = 0 and y'' = -g, and from the launch
//     x(t) = v0 cos(theta) t,        y(t) = v0 sin(theta) t - g t^2 / 2,
// back at the ground (y = 0) at t* = 2 v0 sin(theta) / g and x* = v0 cos(theta) t*.
//
// NAMES
// G is Ground, B the ball. p_GB is the position of B's origin from G's origin, expressed in G; v_GB its
// velocity in G. The contract, with the Scene, Sample, GroundHit and Model types, is
// projectile/ProjectileMotion.h.
#include "projectile/ProjectileMotion.h"

#include "simlab/integrators.h"
#include "simlab/todo.h"

namespace projectile {

using namespace SimTK;

namespace {

// Watches the ball's height; when it falls through zero, records the hit and ends the simulation.
// Simbody calls getValue as it steps, and handleEvent once it has localized a sign change of that value to
// within the trigger's time window.
class GroundHitHandler : public TriggeredEventHandler {
public:
    GroundHitHandler(const MobilizedBody& ball, GroundHit& hit, double window)
        : TriggeredEventHandler(Stage::Position), ball_(ball), hit_(hit) {
        // 1. The trigger: only a falling sign change counts, so turn rising ones off
        //    (getTriggerInfo().setTriggerOnRisingSignTransition(false); falling ones are on by default), and
        //    localize it to within `window` seconds (getTriggerInfo().setRequiredLocalizationTimeWindow(window)).
        SIMLAB_TODO("set the trigger: falling sign changes only, localized to within the window");
    }

    Real getValue(const State& state) const override {
        // 2. The value whose sign change is the event: the ball's height, y of p_GB.
        SIMLAB_TODO("return the ball's height");
    }

    void handleEvent(State& state, Real /*accuracy*/, bool& shouldTerminate) const override {
        // 3. The event: record in hit_ that it was found, its time and the ball's x, then end the simulation
        //    (shouldTerminate = true).
        SIMLAB_TODO("record the ground hit and end the simulation");
    }

private:
    const MobilizedBody& ball_;
    GroundHit& hit_;
};

}  // namespace

void buildModel(const Scene& scene, Model& model) {
    // 4. The model. Give the ball only the motions the scene needs, x and y:
    //    - the ball: Body::Rigid with MassProperties(scene.mass, Vec3(0), UnitInertia(k * k)), where k is
    //      scene.radiusOfGyration;
    //    - a Slider from Ground along x carrying a Body::Massless() frame, then a Slider from that frame along y
    //      (both mobilizer frames turned Pi/2 about ZAxis, as in the apple) carrying the ball: store that one in
    //      model.ball;
    //    - gravity, as in the apple;
    //    - the event handler: model.system.addEventHandler(new GroundHitHandler(model.ball, model.groundHit,
    //      scene.groundHitWindow)). The system takes ownership of it.
    SIMLAB_TODO("build the model: the ball on two Sliders, gravity, and the ground-hit handler");
}

State initialState(const Scene& scene, const Model& model) {
    // 5. The initial state: realize the topology; the ball starts at the origin (coordinates 0), with speed
    //    scene.launchSpeed at scene.launchAngleDegrees above the horizontal. std::sin and std::cos take radians.
    //    Set the x Slider's speed (model.ball.getParentMobilizedBody()) and the y Slider's (model.ball).
    SIMLAB_TODO("set the initial state: at the origin with the launch velocity");
}

std::unique_ptr<Integrator> makeIntegrator(const Model& model, const simlab::RunSettings& run) {
    // 6. The integrator, as in the apple.
    SIMLAB_TODO("make the integrator named in run, at run.accuracy");
}

Sample sample(const Model& model, const State& state) {
    // 7. The sampled quantities: time, x and y of p_GB and of v_GB, and the mechanical energy.
    SIMLAB_TODO("sample the time, position, velocity and mechanical energy from the state");
}

void simulate(const Model& model, Integrator& integrator, const State& initial, const simlab::RunSettings& run,
              simlab::Recorder<Sample>& recorder) {
    // 8. The stepping loop, as in the apple, with one change: when the ground hit has ended the simulation
    //    (integrator.isSimulationOver()), record that last state and stop.
    SIMLAB_TODO("step to the final time, sampling every dt, and stop at the ground hit");
}

simlab::RunSettings cheapestSettings() {
    // 9. The trade (handout, section 6): the cheapest setting that keeps 10 digits of the trade question's flight.
    //    Measure it: `build/bin/simlab study trade projectile --question` (in the student bundle, add
    //    `--file ProjectileMotion.cpp`). Return a RunSettings with integrator and accuracy set (or fixedStep = true
    //    and the step in dt).
    SIMLAB_TODO("the cheapest setting that keeps 10 digits of the question's flight to the ground hit");
}

}  // namespace projectile
