// A replay page from a small run: a 20 x 30 x 5 cm brick drifting along x while it spins about its intermediate
// axis, where a spin is unstable, so the brick flips over and back. Writes PAGE (replay.html by default).
//
//   replay_demo [PAGE]
#include <cmath>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "Simbody.h"
#include "simlab/replay.h"

using namespace SimTK;

int main(int argc, char** argv) {
    const std::string page = argc > 1 ? argv[1] : "replay.html";
    try {
        MultibodySystem system;
        SimbodyMatterSubsystem matter(system);
        GeneralForceSubsystem forces(system);  // none: the brick flies free

        const Vec3 halfLengths_B(0.10, 0.15, 0.025);  // m
        const double mass = 1.5;                       // kg
        Body::Rigid brick(MassProperties(mass, Vec3(0), mass * UnitInertia::brick(halfLengths_B)));
        brick.addDecoration(DecorativeBrick(halfLengths_B).setColor(Vec3(0.85, 0.55, 0.20)));
        brick.addDecoration(DecorativeFrame(0.2));
        brick.addDecoration(Transform(Rotation(Pi / 2, ZAxis), Vec3(0.10, 0.15, 0.025)),
                            DecorativeFrame(0.06).setColor(Vec3(0.2, 0.2, 0.2)));
        MobilizedBody::Free body(matter.Ground(), Transform(), brick, Transform());
        matter.Ground().addBodyDecoration(Transform(), DecorativeFrame(0.3));

        simlab::ReplayRecorder replay(system, 1.0 / 30);
        system.realizeTopology();
        State state = system.getDefaultState();
        body.setQToFitTranslation(state, Vec3(-1.0, 0.4, 0));
        body.setUToFitAngularVelocity(state, Vec3(7, 0.2, 0.2));  // rad/s, about the brick's intermediate axis x
        body.setUToFitLinearVelocity(state, Vec3(0.5, 0, 0));     // m/s

        RungeKuttaMersonIntegrator integrator(system);
        integrator.setAccuracy(1e-6);
        TimeStepper stepper(system, integrator);
        stepper.initialize(state);

        const std::vector<std::string> columns = {"time", "wx (rad/s)", "wy (rad/s)", "wz (rad/s)", "x (m)"};
        std::vector<std::vector<double>> rows;
        const double dt = 0.01, finalTime = 4;  // s
        for (int i = 0;; ++i) {
            const State& s = integrator.getState();
            system.realize(s, Stage::Velocity);
            const Vec3 w_B = ~body.getBodyRotation(s) * body.getBodyAngularVelocity(s);
            rows.push_back({s.getTime(), w_B[0], w_B[1], w_B[2], body.getBodyOriginLocation(s)[0]});
            if (i * dt >= finalTime - 1e-12) break;
            stepper.stepTo((i + 1) * dt);
        }
        replay.write(page, "A brick's tumble: spin about the intermediate axis <x> & a drift", columns, rows);
        std::cout << "replay_demo: " << replay.frames() << " frames written to " << page << '\n';
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "replay_demo: error: " << e.what() << '\n';
        return 1;
    }
}
