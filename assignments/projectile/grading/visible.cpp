// Projectile motion: the tests a student's self-check runs. Points and thresholds are in ../rubric.toml.
#include "projectile_testing.h"

namespace projectile::testing {

TEST_CASE("the ball starts at the origin with the launch velocity", "[projectile][initial]") {
    const Scene scene;  // 44.7 m/s at 35 degrees: 36.6 m/s along x, 25.6 m/s along y
    const Run run = simulate(scene);
    requireSamples(run);
    const Sample& first = run.samples.front();
    INFO("first sample: t = " << first.time << " s, (x, y) = (" << first.x << ", " << first.y << ") m, velocity ("
                              << first.xVelocity << ", " << first.yVelocity << ") m/s; expected t = 0 at (0, 0) with ("
                              << exact::xVelocity0(scene) << ", " << exact::yVelocity0(scene) << ") m/s");
    CHECK(first.time == 0.0);
    CHECK(first.x == Approx(0.0).margin(1e-12));
    CHECK(first.y == Approx(0.0).margin(1e-12));
    CHECK(first.xVelocity == Approx(exact::xVelocity0(scene)).epsilon(1e-12));
    CHECK(first.yVelocity == Approx(exact::yVelocity0(scene)).epsilon(1e-12));
}

TEST_CASE("samples run from t = 0 to the final time every dt", "[projectile][sampling]") {
    const simlab::RunSettings settings = settingsFor(/*finalTime=*/2.0, /*dt=*/0.25);
    checkSampleTimes(simulate(Scene{}, settings), settings);
}

TEST_CASE("the integrator is the one asked for at the accuracy asked for", "[projectile][integrator]") {
    checkIntegratorRequests<Sample>(Scene{}, settingsFor(1.0, 0.05));
}

TEST_CASE("y at 5.2 s has the target accuracy digits", "[projectile][accuracy]") {
    // y(5.2) = 44.7 sin(35 deg) 5.2 - 4.9 * 5.2^2 = 0.8316 m: the ball is nearly down again.
    const Scene scene;
    const Run run = simulate(scene);
    const Sample& s = sampleAt(run, 5.2);
    WorstDigits digits;
    digits.add(simlab::accuracyDigits(s.y, exact::y(scene, 5.2)), grading::at("y", s.time), s.y, exact::y(scene, 5.2),
               "m");
    CHECK(atLeast(digits, grading::param("floor"), grading::param("target"), "digits"));
}

TEST_CASE("x at 5.2 s has the target accuracy digits", "[projectile][accuracy]") {
    const Scene scene;
    const Run run = simulate(scene);
    const Sample& s = sampleAt(run, 5.2);
    WorstDigits digits;
    digits.add(simlab::accuracyDigits(s.x, exact::x(scene, 5.2)), grading::at("x", s.time), s.x, exact::x(scene, 5.2),
               "m");
    CHECK(atLeast(digits, grading::param("floor"), grading::param("target"), "digits"));
}

TEST_CASE("the trajectory follows the parabola y(x) at every sample", "[projectile][trajectory]") {
    const Scene scene;
    const Run run = simulate(scene);
    lastSample(run, defaultRunSettings().finalTime);
    CHECK(atLeast(parabolaDigits(scene, run), grading::param("floor"), grading::param("target"),
                  "digits at the worst sample"));
}

TEST_CASE("the ground hit time comes from an event to the target digits", "[projectile][ground]") {
    // Sampled only every 0.25 s: an event handler localizes the hit whatever the sampling; a scan of the samples
    // cannot.
    const HitDigits digits = groundHitDigits(Scene{}, 0.25);
    CHECK(atLeast(digits.time, grading::param("floor"), grading::param("target"), "digits of t*"));
}

TEST_CASE("the ground hit range comes from an event to the target digits", "[projectile][ground]") {
    const HitDigits digits = groundHitDigits(Scene{}, 0.25);
    CHECK(atLeast(digits.range, grading::param("floor"), grading::param("target"), "digits of x*"));
}

TEST_CASE("only a descent through y = 0 is a ground hit: from a trench the ball flies on", "[projectile][ground]") {
    // The ball starts 2 m below the ground's level (the course moves it there after initialState), rises through
    // y = 0 at 0.08 s and comes down through it at 5.15 s. A handler that also triggers on rising transitions ends
    // the flight at the first crossing.
    const Scene scene;
    const double depth = 2;
    const Landing landing = observeLanding(scene, defaultRunSettings(), depth);
    const double tHit = exact::flightTimeFrom(scene, depth);
    const double tRise = 2 * exact::yVelocity0(scene) / scene.gravity - tHit;  // the two roots add up to 2 vy0 / g
    {  // said only where nothing was recorded, not beside a later check on what was
        INFO("no ground hit was recorded (the simulation ran to t = " << landing.endTime << " s)");
        CHECK(landing.hit.found);
    }
    if (!landing.hit.found) return;
    const bool rising = std::abs(landing.hit.time - tRise) < 0.5 * (tHit - tRise);
    if (rising) {
        grading::feedback("the flight ended at t = " + grading::show(landing.hit.time) + " s, as the ball rose out of "
                          "the trench through y = 0: the ground is hit only coming down, so the handler's trigger "
                          "takes falling sign transitions and not rising ones");
    }
    WorstDigits digits;
    const std::string crossing =
        rising ? "(the rising crossing, as the ball climbs out of the trench: the trigger fires on the way up)" : "";
    digits.add(simlab::accuracyDigits(landing.hit.time, tHit), "t*", landing.hit.time, tHit, "s", crossing);
    CHECK(atLeast(digits, grading::param("floor"), grading::param("target"), "digits of the landing time"));
}

TEST_CASE("the simulation ends at the ground hit and records its state last", "[projectile][ground]") {
    // Samples every 0.01 s asked for up to 6 s, past the hit at t* = 5.2324 s: the event handler ends the
    // simulation there, simulate records that state and stops, and no row after it repeats it.
    const Scene scene;
    const simlab::RunSettings settings = settingsFor(/*finalTime=*/6.0, /*dt=*/0.01);
    const Run run = simulate(scene, settings);
    requireSamples(run);
    const Sample& last = run.samples.back();
    GroundHit end;  // where the run stopped, marked on the feedback's plot if it stopped early
    end.found = last.time < settings.finalTime - 1e-9;
    end.time = last.time;
    end.x = last.x;
    grading::attachPlot("your-run.svg", runPlot(scene, "your run: " + simlab::describeRun(settings), run.samples, end));
    std::size_t repeats = 0;
    for (std::size_t k = 1; k < run.samples.size(); ++k) repeats += !(run.samples[k].time > run.samples[k - 1].time);
    const double tStar = exact::flightTime(scene);
    {  // the loop's advice with its own check only: a run that ends at the wrong time may have a correct loop
        INFO(repeats << " samples repeat an earlier time (the last at t = " << last.time
                     << " s): once the handler has ended the simulation, stop the loop (integrator.isSimulationOver())");
        CHECK(repeats == 0);
    }
    INFO("the last sample is at t = " << last.time << " s; the ball lands at t* = " << tStar << " s");
    CHECK(last.time == Approx(tStar).margin(1e-4));
}

TEST_CASE("the mechanical energy stays at its launch value", "[projectile][energy]") {
    // Only gravity acts: kinetic + potential energy stays at m v0^2 / 2, to about the integrator's accuracy.
    const Scene scene;
    const simlab::RunSettings settings = defaultRunSettings();
    const Run run = simulate(scene, settings);
    lastSample(run, settings.finalTime);
    const double expected = exact::mechanicalEnergy(scene);
    WorstDrift drift;
    for (const Sample& s : run.samples) {
        drift.add(std::abs(s.mechanicalEnergy / expected - 1), grading::at("E", s.time), s.mechanicalEnergy, expected,
                  "J");
    }
    CHECK(atMost(drift, grading::param("tolerance") * settings.accuracy, "relative energy drift"));
}

TEST_CASE("the model has only the two degrees of freedom a flight in a plane needs", "[projectile][model]") {
    checkDegreesOfFreedom(simlab::observe::model(Scene{}), 2,
                          "a flight in the x-y plane",
                          "two Sliders in series (along x, then along y) give the ball exactly x and y");
}

TEST_CASE("the trade: 10 digits of the question's flight for the fewest evaluations", "[projectile][trade]") {
    // cheapestSettings(), measured on the student's own model as `simlab study trade projectile --question`
    // measures a setting - the integrator stops only where it chooses to (and at the ground hit), and every step
    // counts - from each of the question's starts, against the front of the question's throw (not the lab's).
    gradeTrade<Sample, Scene>(tradeQuestion(), studentScene(tradeQuestion()), tradeDigits);
}

}  // namespace projectile::testing
