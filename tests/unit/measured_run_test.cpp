// A measured run (the work-precision study's and the trade question's): what it checks, where it stops, and the
// judge's check of the counts a student's process reports.
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "Simbody.h"
#include "simlab/measured_run.h"

namespace measured_run_test {

using namespace SimTK;

namespace {

// A ball on a Slider along Ground's y, falling from 10 m: y = 10 - 4.9 t^2.
struct Fall {
    MultibodySystem system;
    SimbodyMatterSubsystem matter{system};
    GeneralForceSubsystem forces{system};
    MobilizedBody::Slider ball;
    State initial;
    Fall()
        : ball(matter.Ground(), Transform(Rotation(Pi / 2, ZAxis), Vec3(0)),
               Body::Rigid(MassProperties(1, Vec3(0), UnitInertia::sphere(0.05))),
               Transform(Rotation(Pi / 2, ZAxis), Vec3(0))) {
        Force::UniformGravity(forces, matter, Vec3(0, -9.8, 0));
        initial = system.realizeTopology();
        ball.setOneQ(initial, 0, 10);
    }
};

simlab::RunSettings choice(const std::string& integrator, double accuracy, bool fixed = false, double dt = 0.01) {
    simlab::RunSettings c;
    c.integrator = integrator;
    c.accuracy = accuracy;
    c.fixedStep = fixed;
    c.dt = dt;
    return c;
}

struct Sample {
    double time = 0;
};

}  // namespace

TEST_CASE("a measured run checks t = 0, its own steps and the last state, and ends at the final time") {
    Fall fall;
    auto integrator = simlab::integratorFor(choice("RungeKuttaMerson", 1e-8), fall.system, 2.0);
    int checks = 0, lasts = 0;
    double worst = 0;
    const simlab::MeasuredRun run = simlab::measureRun(
        fall.system, *integrator, fall.initial, 2.0, simlab::MeasureLimits{}, [&](const State& s, bool last) {
            ++checks;
            lasts += last;
            const double y = fall.ball.getOneQ(s, 0), t = s.getTime();
            worst = std::max(worst, std::abs(y - (10 - 4.9 * t * t)));
        });
    CHECK(run.status == "ok");
    CHECK(run.reached == Approx(2.0));
    CHECK(lasts == 1);
    CHECK(checks >= 2);
    CHECK(checks <= run.integrator.stepsTaken + 1);
    CHECK(worst < 1e-9);  // a second-order motion: RungeKuttaMerson follows it to round-off
    CHECK(run.integrator.realizations >= run.integrator.stepsAttempted);
}

TEST_CASE("a measured run's step seconds are its integrator's alone: the time its checks take is left out") {
    Fall fall;
    auto integrator = simlab::integratorFor(choice("RungeKuttaMerson", 1e-8), fall.system, 2.0);
    using Clock = std::chrono::steady_clock;
    Clock::duration checking{};
    const Clock::time_point began = Clock::now();
    const simlab::MeasuredRun run = simlab::measureRun(
        fall.system, *integrator, fall.initial, 2.0, simlab::MeasureLimits{}, [&](const State&, bool) {
            const Clock::time_point start = Clock::now();
            std::this_thread::sleep_for(std::chrono::milliseconds(2));  // a check dearer than the steps
            checking += Clock::now() - start;
        });
    const double whole = std::chrono::duration<double>(Clock::now() - began).count();
    const double checks = std::chrono::duration<double>(checking).count();
    CHECK(run.status == "ok");
    CHECK(run.stepSeconds > 0);
    CHECK(run.stepSeconds + checks <= whole);
}

TEST_CASE("a measured run stops past its cap of evaluations, says where, and checks the state it stopped at") {
    Fall fall;
    auto integrator = simlab::integratorFor(choice("RungeKutta3", 0, true, 1e-4), fall.system, 1.0);
    simlab::MeasureLimits limits;
    limits.maxEvaluations = 100;
    double lastTime = -1;
    const simlab::MeasuredRun run = simlab::measureRun(fall.system, *integrator, fall.initial, 1.0, limits,
                                                       [&](const State& s, bool last) {
                                                           if (last) lastTime = s.getTime();
                                                       });
    CHECK(run.status == "too costly");
    CHECK_THAT(run.message, Catch::StartsWith("past the cap of 100 evaluations at t = "));
    CHECK(run.reached < 0.01);
    CHECK(lastTime == run.reached);
    CHECK(run.integrator.realizations > 100);
    CHECK(run.integrator.realizations < 110);
}

TEST_CASE("a fixed step ends where a lab program's samples end it, at whole multiples of the step") {
    // Adding up steps of 0.1 s strays from k * 0.1 in the last bits; a lab program's samples, at k * dt, end each
    // step there, and so does a measured run: the same run, to the last bit.
    Fall fall;
    auto integrator = simlab::integratorFor(choice("ExplicitEuler", 1e-7, true, 0.1), fall.system, 1.0);
    simlab::MeasureLimits limits;
    limits.checks = 100000;  // every step
    std::vector<double> times;
    const simlab::MeasuredRun run = simlab::measureRun(
        fall.system, *integrator, fall.initial, 1.0, limits,
        [&](const State& s, bool) { times.push_back(s.getTime()); }, 0.1);
    CHECK(run.status == "ok");
    REQUIRE(times.size() == 11);
    for (int k = 0; k < 10; ++k) CHECK(times[static_cast<std::size_t>(k)] == k * 0.1);
    CHECK(times.back() == 1.0);
    CHECK(run.integrator.stepsTaken == 10);
    CHECK(simlab::nextStepEnd(0.1, 1.0, 0.30000000000000004) == 0.4);
    CHECK(simlab::nextStepEnd(0.1, 1.0, 0.95) == 1.0);
    CHECK(simlab::nextStepEnd(0, 1.0, 0.5) == 1.0);  // error control: its own steps to the final time
}

TEST_CASE("Verlet's fixed step is solved to the accuracy it is given, which decides its digits") {
    // A ball on a Slider slowed by a damper: u' = -(c/m) u, so the trapezoid rule for u is implicit, and Simbody
    // iterates it to min(1e-4, accuracy / 10). Exact: q(t) = q0 + (m/c) u0 (1 - exp(-c t / m)), here with m = 1 kg,
    // c = 5 N s/m, u0 = 1 m/s, q0 = 0: 0.19865 m at 1 s. Steps of 0.1 s (c h / m = 0.5) leave Verlet's explicit
    // position update an error of about 6 % of that either way; how well the velocity's is solved moves it further.
    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    GeneralForceSubsystem forces(system);
    MobilizedBody::Slider ball(matter.Ground(), Transform(),
                               Body::Rigid(MassProperties(1, Vec3(0), UnitInertia::sphere(0.05))), Transform());
    Force::MobilityLinearDamper(forces, ball, 0, 5.0);
    State initial = system.realizeTopology();
    ball.setOneU(initial, 0, 1.0);
    const double exact = 0.2 * (1 - std::exp(-5.0));
    auto error = [&](double accuracy) {
        auto integrator = simlab::integratorFor(choice("Verlet", accuracy, true, 0.1), system, 1.0);
        double q = NAN;
        const simlab::MeasuredRun run = simlab::measureRun(
            system, *integrator, initial, 1.0, simlab::MeasureLimits{},
            [&](const State& s, bool last) {
                if (last) q = ball.getOneQ(s, 0);
            },
            0.1);
        CHECK(run.integrator.accuracyInUse == accuracy);
        return std::abs(q - exact);
    };
    const double loose = error(1e-1), tight = error(1e-12);
    INFO("errors: " << loose << " m solved to 1e-1, " << tight << " m solved to 1e-12");
    CHECK(tight < 0.1 * exact);
    CHECK(loose < 0.1 * exact);
    CHECK(std::abs(loose - tight) > 1e-6);  // far past rounding: the accuracy changes the fixed-step run
}

TEST_CASE("a choice that is not a setting is refused, naming what is wrong") {
    Fall fall;
    CHECK_THROWS_WITH(simlab::integratorFor(choice("Verlett", 0.1), fall.system, 1.0),
                      Catch::Contains("unknown integrator 'Verlett'"));
    CHECK_THROWS_WITH(simlab::integratorFor(choice("RungeKuttaMerson", 0), fall.system, 1.0),
                      Catch::Contains("accuracy must be between 0 and 1"));
    CHECK_THROWS_WITH(simlab::integratorFor(choice("RungeKutta2", 0.1, true, -1), fall.system, 1.0),
                      Catch::Contains("a fixed step must be a positive number of seconds"));
    CHECK_THROWS_WITH(simlab::integratorFor(choice("SemiExplicitEuler", 0.1, false, 2.0), fall.system, 1.0),
                      Catch::Contains("no longer than the run"));
}

TEST_CASE("counts a student's process reports for its choice must add up") {
    simlab::ChoiceRun<Sample> run;
    for (int k = 0; k <= 50; ++k) run.samples.push_back({k * 0.1});
    run.run.integrator.stepsTaken = 60;
    run.run.integrator.stepsAttempted = 64;
    run.run.integrator.realizations = 300;
    CHECK(simlab::inconsistencyOf(run).empty());
    // Fifty later sample times, each at a step of the integrator's, from a run that claims three steps.
    run.run.integrator.stepsTaken = 3;
    run.run.integrator.stepsAttempted = 3;
    run.run.integrator.realizations = 12;
    CHECK_THAT(simlab::inconsistencyOf(run), Catch::Contains("samples 50 later times"));
    // Fewer evaluations than attempted steps.
    run.samples.resize(2);
    run.run.integrator.realizations = 2;
    CHECK_THAT(simlab::inconsistencyOf(run), Catch::Contains("cannot all be true"));
}

}  // namespace measured_run_test
