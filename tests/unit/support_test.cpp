// The rest of the support library: run settings, the recorder, the results table, SIMLAB_TODO, and the
// apple's exact solution.
#include <catch2/catch.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <stdexcept>
#include <utility>
#include <vector>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "apple/program/exact.h"
#include "simlab/messages.h"
#include "simlab/plot.h"
#include "simlab/program.h"
#include "simlab/recorder.h"
#include "simlab/results_table.h"
#include "simlab/run_settings.h"
#include "simlab/todo.h"

namespace support_test {

TEST_CASE("samples fall on multiples of dt and the last one on the final time", "[settings]") {
    simlab::RunSettings run;
    run.finalTime = 4.0;
    run.dt = 0.01;
    CHECK(run.sampleCount() == 400);  // not 401, although 4 / 0.01 is 400.00000000000006 in doubles
    CHECK(run.sampleTime(400) == 4.0);
    run.finalTime = 5.23;
    CHECK(run.sampleCount() == 523);
    run.finalTime = 1.0;
    run.dt = 0.3;
    CHECK(run.sampleCount() == 4);
    CHECK(run.sampleTime(3) == Approx(0.9));
    CHECK(run.sampleTime(4) == 1.0);
}

TEST_CASE("unusable settings are refused with a message naming the setting", "[settings]") {
    simlab::RunSettings run;
    run.dt = 0;
    CHECK_THROWS_WITH(simlab::validate(run), "dt must be a positive number of seconds");
    run = {};
    run.accuracy = 2;
    CHECK_THROWS_WITH(simlab::validate(run), Catch::Contains("accuracy must be between 0 and 1"));
    run = {};
    run.integrator = "Euler";
    CHECK_THROWS_WITH(simlab::validate(run), Catch::StartsWith("unknown integrator 'Euler'"));
    run = {};
    run.dt = 10;
    CHECK_THROWS_WITH(simlab::validate(run), "dt must not exceed the final time");
    CHECK_NOTHROW(simlab::validate(simlab::RunSettings{}));
}

TEST_CASE("the recorder keeps rows, tells its listener, and stops a loop that does not end", "[recorder]") {
    int heard = 0;
    simlab::Recorder<int> recorder([&](const int&) { ++heard; }, 3);
    recorder.record(1);
    recorder.record(2);
    recorder.record(3);
    CHECK(recorder.rows() == std::vector<int>{1, 2, 3});
    CHECK(heard == 3);
    CHECK_THROWS_WITH(recorder.record(4), Catch::Contains("does the stepping loop stop at the final time?"));
}

TEST_CASE("the results file holds every value at full double precision", "[results]") {
    const std::string path = "simlab-results-test.txt";
    std::ostringstream screen;
    {
        simlab::ResultsTable table({"time", "yLocation"}, path, &screen);
        table.add({0.1, -68.40000000000012});
    }
    std::ifstream in(path);
    std::string header, t, y;
    std::getline(in, header);
    in >> t >> y;
    CHECK(header == "time\tyLocation");
    CHECK(std::stod(y) == -68.40000000000012);  // round-trips exactly
    CHECK(screen.str().find("yLocation") != std::string::npos);
    std::remove(path.c_str());
}

TEST_CASE("a conserved column that starts at zero is judged against the scene's scale, never its own rounding",
          "[results]") {
    // A pendulum released at 90 degrees: E(0) = -m g L cos(90 deg) is zero but for rounding (-6e-16 J), its terms are
    // m g L = 9.81 J. A drift of 1e-5 J (1e-6 of them) is an ordinary run's; 1e7 J, past 1e6 times 9.81 J, is not.
    const std::string path = "simlab-growth-test.txt";
    {
        simlab::ResultsTable table({"time", "E"}, path, nullptr);
        table.watchGrowth("E", 1e6, 9.81);
        CHECK_NOTHROW(table.add({0, -6.00689e-16}));
        CHECK_NOTHROW(table.add({856, 9.97161e-06}));
        CHECK_THROWS_WITH(table.add({900, 1e7}),
                          Catch::StartsWith("the run broke at t = 900 s: E moved from -6.00689e-16 to 1e+07, more than "
                                            "1e+06 times its scale in this scene (9.81)"));
    }
    {
        // An apple at rest at y = 0 with no gravity: nothing in the scene has a size, and nothing is judged.
        simlab::ResultsTable table({"time", "E"}, path, nullptr);
        table.watchGrowth("E", 1e6, 0);
        CHECK_NOTHROW(table.add({0, 0}));
        CHECK_NOTHROW(table.add({1, 1e-300}));
    }
    {
        // A scale below the first value's: the first value is the scale (a spin's kinetic energy).
        simlab::ResultsTable table({"time", "K"}, path, nullptr);
        table.watchGrowth("K", 1e6, 0);
        CHECK_NOTHROW(table.add({0, 2.0}));
        CHECK_NOTHROW(table.add({1, 1.9e6}));
        CHECK_THROWS(table.add({2, 2.1e6}));
    }
    std::remove(path.c_str());
}

TEST_CASE("a run's settings are said, with the accuracy wherever a fixed step reads it", "[settings]") {
    simlab::RunSettings run;
    run.integrator = "Verlet";
    run.fixedStep = true;
    run.dt = 0.04;
    run.accuracy = 1e-3;
    // Verlet solves its implicit velocity update to the accuracy, at a fixed step too.
    CHECK(simlab::describeRun(run) == "Verlet, fixed step 0.04 s at accuracy 0.001");
    run.integrator = "ExplicitEuler";
    CHECK(simlab::describeRun(run) == "ExplicitEuler, fixed step 0.04 s");
    // Where the model has events, any method's fixed step localizes them to the accuracy.
    CHECK(simlab::describeRun(run, true) == "ExplicitEuler, fixed step 0.04 s at accuracy 0.001");
    run.fixedStep = false;
    run.integrator = "RungeKuttaMerson";
    run.dt = 0.01;
    run.accuracy = 1e-7;
    CHECK(simlab::describeProgramRun(run) == "RungeKuttaMerson, accuracy 1e-07, dt 0.01 s, 0 <= t <= 4 s");
    // Fixed steps of 3 s to 4 s: samples at 0, 3 and 4 s, the last step 1 s.
    run.fixedStep = true;
    run.dt = 3;
    CHECK(simlab::shortLastStep(run) == 1.0);
    CHECK(simlab::describeProgramRun(run) == "RungeKuttaMerson, fixed step 3 s (the last 1 s), 0 <= t <= 4 s");
    run.dt = 0.01;  // 400 whole steps, though 4 / 0.01 is not 400 in doubles
    CHECK(simlab::shortLastStep(run) == 0.0);
    CHECK(simlab::describeProgramRun(run) == "RungeKuttaMerson, fixed step 0.01 s, 0 <= t <= 4 s");
}

TEST_CASE("a results file that cannot be written is an error saying why", "[results]") {
    CHECK_THROWS_WITH(simlab::ResultsTable({"time"}, "/nonexistent-dir/results.txt", nullptr),
                      "cannot write results file '/nonexistent-dir/results.txt': No such file or directory");
}

TEST_CASE("SIMLAB_TODO stops with the file, the line and the task", "[todo]") {
    try {
        SIMLAB_TODO("build the model");
        FAIL("SIMLAB_TODO returned");
    } catch (const simlab::NotDoneYet& e) {
        CHECK(e.file() == "support_test.cpp");
        CHECK(e.task() == "build the model");
        CHECK(std::string(e.what()) == "not done yet (support_test.cpp:" + std::to_string(e.line()) + "): build the model");
    }
}

TEST_CASE("the apple's exact fall reaches -68.4 m at 4 s with its energy unchanged", "[exact]") {
    const apple::Scene scene;  // 0.142 kg from 10 m, g = 9.8 m/s^2
    CHECK(apple::exact::yLocation(scene, 0) == 10.0);
    CHECK(apple::exact::yLocation(scene, 4) == Approx(-68.4).epsilon(1e-15));
    CHECK(apple::exact::yVelocity(scene, 4) == Approx(-39.2).epsilon(1e-15));
    // Energy: m g y + m v^2 / 2 at t = 4 equals m g h.
    const double y = apple::exact::yLocation(scene, 4), v = apple::exact::yVelocity(scene, 4);
    CHECK(scene.mass * scene.gravity * y + 0.5 * scene.mass * v * v ==
          Approx(apple::exact::mechanicalEnergy(scene)).epsilon(1e-14));
    CHECK(apple::exact::mechanicalEnergy(scene) == Approx(13.916));
}

namespace {

/// What `body` run under simlab::runGuarded("demo", ...) in a child process prints on stderr, and its exit status
/// (128 + N for signal N).
std::pair<std::string, int> guardedInChild(const std::function<int()>& body) {
    int pipeFds[2];
    REQUIRE(::pipe(pipeFds) == 0);
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        ::dup2(pipeFds[1], 2);
        ::close(pipeFds[0]);
        ::close(pipeFds[1]);
        std::_Exit(simlab::runGuarded("demo", body));
    }
    ::close(pipeFds[1]);
    std::string text;
    char buffer[512];
    for (ssize_t n; (n = ::read(pipeFds[0], buffer, sizeof buffer)) > 0;) text.append(buffer, static_cast<std::size_t>(n));
    ::close(pipeFds[0]);
    int status = 0;
    ::waitpid(child, &status, 0);
    return {text, WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status)};
}

}  // namespace

TEST_CASE("an abort inside a run is one line and status 1, naming the check a kept solver message held",
          "[program]") {
    const auto [bare, bareStatus] = guardedInChild([] {
        std::abort();
        return 0;
    });
    CHECK(bareStatus == 1);
    CHECK(bare == "demo: error: the run stopped in an internal check of Simbody or the C++ library (the line above "
                  "names it); the scene or setting is past what it can follow\n");

    const auto [kept, keptStatus] = guardedInChild([] {
        simlab::SolverChatter chatter(true);  // what the library prints goes to a file, not the screen
        std::fprintf(stderr, "x.cpp:12: void f(): Assertion `t > 0' failed.\n");
        std::fflush(stderr);
        std::abort();
        return 0;
    });
    CHECK(keptStatus == 1);
    CHECK(kept == "demo: error: the run stopped in an internal check of Simbody or the C++ library: x.cpp:12: void "
                  "f(): Assertion `t > 0' failed.; the scene or setting is past what it can follow\n");
}

TEST_CASE("an exception thrown where none may pass is one line and status 1", "[program]") {
    const auto [said, status] = guardedInChild([]() -> int {
        // Thrown from a function the compiler cannot see into, through one that promises not to throw.
        static void (*volatile step)() = [] {
            throw std::runtime_error("the step size fell to zero\n  (a line a solver adds)");
        };
        auto never = []() noexcept { step(); };
        never();
        return 0;
    });
    CHECK(status == 1);
    CHECK(said == "demo: error: the run stopped on an exception where none may pass: the step size fell to zero\n");
}

TEST_CASE("an integrator's failed step is said with its cause, not Simbody's names", "[messages]") {
    const std::string advance =
        "SimTK Exception thrown at AbstractIntegrator.cpp:151:\n  Integrator step failed at time 0.7442289521733112 "
        "apparently because: AbstractIntegrator::takeOneStep(): Unable to advance time past 0.744229.";
    const std::string said = simlab::oneLineMessage(advance);
    CHECK(said.rfind("the integrator could not advance past t = 0.744229 s: ", 0) == 0);
    CHECK(said.find("coarser accuracy") != std::string::npos);
    CHECK(said.find("AbstractIntegrator") == std::string::npos);
    const std::string cpodes =
        "Integrator step failed at time 0 apparently because: CPodes::step() returned an error\n[CPODES ERROR] ...";
    CHECK(simlab::oneLineMessage(cpodes).rfind("CPodes gave up at t = 0 s: ", 0) == 0);
    // Another reason keeps its words, with the time said once.
    CHECK(simlab::oneLineMessage("Integrator step failed at time 2.5 apparently because: something new") ==
          "the integrator's step failed at t = 2.5 s: something new");
    // Any other message is untouched.
    CHECK(simlab::oneLineMessage("the simulation recorded no samples") == "the simulation recorded no samples");
}

TEST_CASE("CPodes at fixed steps is refused before it runs", "[settings]") {
    simlab::RunSettings run;
    run.integrator = "CPodes";
    run.fixedStep = true;
    CHECK_THROWS_WITH(simlab::validate(run), Catch::Contains("CPodes takes no fixed steps"));
    run.fixedStep = false;
    CHECK_NOTHROW(simlab::validate(run));
}

TEST_CASE("a panel whose values differ in the sixth digit is drawn less a reference, its ticks apart", "[plot]") {
    if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
        WARN("gnuplot is not installed: the plot is not drawn");
        return;
    }
    // A conserved energy: -2.12393142 J to within 3e-9 J. In '% g' every tick would read -2.12393.
    simlab::PlotCurve energy("E");
    for (int k = 0; k <= 100; ++k) {
        energy.x.push_back(0.01 * k);
        energy.y.push_back(-2.12393142 + 3e-9 * std::sin(0.3 * k));
    }
    simlab::Plot plot;
    plot.title = "energy";
    plot.panels.emplace_back("time t (s)", "J", std::vector<simlab::PlotCurve>{energy});
    char folder[] = "/tmp/simlab-plot-test-XXXXXX";
    REQUIRE(::mkdtemp(folder) != nullptr);
    const std::string path = std::string(folder) + "/energy.svg";
    simlab::drawPlot(plot, path);
    std::ifstream in(path);
    const std::string svg((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::remove(path.c_str());
    ::rmdir(folder);
    // Written to the digits the spread needs: its middle, -2.12393141999..., to 12 (what is left over is a
    // thousandth of the 6e-9 spread or less).
    CHECK(svg.find("J, less -2.12393141999") != std::string::npos);
    CHECK(svg.find(">-2.12393<") == std::string::npos);  // no tick label that says nothing
    CHECK(svg.find("e-09<") != std::string::npos);         // the ticks tell the values apart
}

TEST_CASE("a plot says in words what it draws: each curve's ends and extremes, how near its samples keep to their line",
          "[plot]") {
    // A fall, y = 10 - 4.9 t^2 from t = 0 to 2 s: the exact line, and samples 0.1 m off it at t = 1.5 s.
    simlab::PlotCurve exact("exact"), simulated("simulated", true);
    for (int k = 0; k <= 200; ++k) {
        const double t = 0.01 * k;
        exact.x.push_back(t), exact.y.push_back(10 - 4.9 * t * t);
    }
    for (int k = 0; k <= 4; ++k) {
        const double t = 0.5 * k;
        simulated.x.push_back(t), simulated.y.push_back(10 - 4.9 * t * t + (k == 3 ? 0.1 : 0.0));
    }
    simulated.x.push_back(NAN), simulated.y.push_back(1);  // not drawn, not counted
    simlab::Plot plot;
    plot.title = "a fall";
    plot.panels.emplace_back("time t (s)", "height y (m)", std::vector<simlab::PlotCurve>{exact, simulated});
    plot.panels.back().marks.push_back({2, 0.4, "the end"});
    const std::string said = simlab::describePlot(plot);
    CHECK(said == "a fall. Drawn: height y (m) against time t (s), from 0 to 2: exact, a line, from 10 at 0 to -9.6 "
                  "at 2; simulated, 5 samples, from 10 at 0 to -9.6 at 2, up to 0.1 off the line exact (at 1.5); "
                  "marked: the end at (2, 0.4).");
    // 0.1 m in 19.6 m is more than the drawing shows; 1e-6 m is not.
    plot.panels.back().curves[1].y[3] -= 0.1 - 1e-6;
    CHECK_THAT(simlab::describePlot(plot), Catch::Contains("5 samples, from 10 at 0 to -9.6 at 2, on the line exact as drawn"));
    // Its points, at most kPlotDataRows a curve, the first and the last among them.
    const std::string points = simlab::plotDataJson(plot);
    CHECK_THAT(points, Catch::Contains("\"points\":201,\"samples\":false,\"title\":\"exact\""));
    CHECK_THAT(points, Catch::Contains("\"label\":\"the end\",\"x\":2.0,\"y\":0.4"));
    CHECK_THAT(points, Catch::Contains(",2.0],\"y\":[10.0,"));
}

}  // namespace support_test
