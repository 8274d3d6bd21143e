// The integrator factory, and what each integrator does to Newton's apple: y'' = -g from rest at 10 m.
#include <catch2/catch.hpp>
#include <string>

#include "Simbody.h"
#include "simlab/digits.h"
#include "simlab/integrators.h"

namespace integrators_test {

using namespace SimTK;

namespace {

// An apple on a Slider along Ground's y, built directly with Simbody (independent of any student file).
struct FallingApple {
    MultibodySystem system;
    SimbodyMatterSubsystem matter{system};
    GeneralForceSubsystem forces{system};
    MobilizedBody::Slider apple;
    FallingApple()
        : apple(matter.Ground(), Transform(Rotation(Pi / 2, ZAxis), Vec3(0)),
                Body::Rigid(MassProperties(0.142, Vec3(0), UnitInertia::sphere(0.036576))),
                Transform(Rotation(Pi / 2, ZAxis), Vec3(0))) {
        Force::UniformGravity(forces, matter, Vec3(0, -9.8, 0));
    }
};

struct Outcome {
    double digits;
    int steps;
};

// Step to t = 4 s, reporting every 0.01 s as the lab program does; digits of y(4) against -68.4 m.
Outcome fall(const std::string& name, double accuracy, bool fixed) {
    FallingApple model;
    State state = model.system.realizeTopology();
    model.apple.setQ(state, 10.0);
    const std::unique_ptr<Integrator> integrator = simlab::integratorNamed(name, model.system, 0.01);
    integrator->setAccuracy(accuracy);
    if (fixed) integrator->setFixedStepSize(0.01);
    TimeStepper stepper(model.system, *integrator);
    stepper.initialize(state);
    for (int k = 1; k <= 400; ++k) stepper.stepTo(k * 0.01);
    return {simlab::accuracyDigits(model.apple.getQ(stepper.getState()), -68.4), integrator->getNumStepsTaken()};
}

}  // namespace

TEST_CASE("every integrator Simbody 3.7 ships can be made by name", "[integrators]") {
    const std::vector<std::string> expected = {"RungeKuttaMerson",  "RungeKutta3",        "RungeKutta2",
                                               "RungeKuttaFeldberg", "ExplicitEuler",      "SemiExplicitEuler",
                                               "SemiExplicitEuler2", "Verlet",             "CPodes"};
    CHECK(simlab::integratorNames() == expected);
    FallingApple model;
    for (const std::string& name : expected) {
        const auto integrator = simlab::integratorNamed(name, model.system, 0.01);
        REQUIRE(integrator);
        const std::string method = integrator->getMethodName();
        INFO(name << " made " << method);
        CHECK(method.rfind(name == "CPodes" ? "CPodes" : name, 0) == 0);
        CHECK(integrator->methodHasErrorControl() == simlab::hasErrorControl(name));
    }
}

TEST_CASE("an unknown integrator name is an error that lists the valid ones", "[integrators]") {
    FallingApple model;
    CHECK_THROWS_WITH(simlab::integratorNamed("RungeKutta4", model.system, 0.01),
                      "unknown integrator 'RungeKutta4'; choose one of: RungeKuttaMerson, RungeKutta3, RungeKutta2, "
                      "RungeKuttaFeldberg, ExplicitEuler, SemiExplicitEuler, SemiExplicitEuler2, Verlet, CPodes");
    CHECK_THROWS_AS(simlab::requireIntegratorName(""), std::invalid_argument);
}

TEST_CASE("Runge-Kutta methods of order 3 and more integrate a constant acceleration exactly", "[integrators]") {
    // y(t) is a quadratic: any method exact for quadratics leaves only roundoff.
    for (const char* name : {"RungeKuttaMerson", "RungeKutta3", "RungeKuttaFeldberg", "Verlet"}) {
        INFO(name);
        CHECK(fall(name, 1e-7, false).digits > 13.0);
    }
}

TEST_CASE("fixed-step Euler is first order: its error is g t h / 2", "[integrators]") {
    // Explicit and semi-explicit Euler with h = 0.01 s miss y(4) by 9.8 * 4 * 0.01 / 2 = 0.196 m (in opposite
    // directions), a relative error of 2.87e-3: 2.54 digits.
    const Outcome euler = fall("ExplicitEuler", 1e-7, true);
    CHECK(euler.steps == 400);
    CHECK(euler.digits == Approx(-std::log10(0.196 / 68.4)).margin(0.01));
    CHECK(fall("SemiExplicitEuler", 1e-7, false).digits == Approx(-std::log10(0.196 / 68.4)).margin(0.01));
}

TEST_CASE("tighter accuracy buys digits with steps for an error-controlled first-order method", "[integrators]") {
    const Outcome loose = fall("ExplicitEuler", 1e-4, false);
    const Outcome tight = fall("ExplicitEuler", 1e-7, false);
    CHECK(tight.digits > loose.digits + 1.0);
    CHECK(tight.steps > 10 * loose.steps);
}

}  // namespace integrators_test
