// The `apple` lab program (the course's side): runs the simulation written in NewtonsApple.cpp, prints its
// table as it goes, writes the results file and says how many digits of y at the final time are right.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "apple/contract/NewtonsApple.h"
#include "apple/program/exact.h"
#include "apple/program/run_plot.h"
#include "simlab/reproducible_math.h"
#include "simlab/cli_checks.h"
#include "simlab/digits.h"
#include "simlab/driver.h"
#include "simlab/messages.h"
#include "simlab/results_table.h"
#include "simlab/plot.h"
#include "simlab/program.h"

namespace {

struct Options {
    apple::Scene scene;
    simlab::ProgramOptions program;
};

std::vector<double> resultsRow(const apple::Scene& scene, const apple::Sample& s) {
    return {s.time, s.yLocation, s.yVelocity, s.mechanicalEnergy,
            s.yLocation - apple::exact::yLocation(scene, s.time)};
}

double finalDigits(const apple::Scene& scene, const std::vector<apple::Sample>& samples) {
    if (samples.empty()) throw std::runtime_error("the simulation recorded no samples");
    return apple::exact::finalDigits(scene, samples.back());
}

const std::vector<std::string> kColumns = {"time", "yLocation", "yVelocity", "mechanicalEnergy", "yDifferenceFromExact"};

int runOnce(const Options& o) {
    const simlab::RunSettings& run = o.program.run;
    char banner[256];
    std::snprintf(banner, sizeof banner,
                  "Newton's apple: %g kg dropped from %g m, g = %g m/s^2; %s", o.scene.mass, o.scene.dropHeight,
                  o.scene.gravity, simlab::describeProgramRun(run).c_str());
    simlab::Tabulation<apple::Sample, apple::Model> tabulation;
    tabulation.columns = kColumns;
    tabulation.row = [&](const apple::Sample& s) { return resultsRow(o.scene, s); };
    tabulation.banner = banner;
    tabulation.bodyRadius = o.scene.radius;
    // The apple at its size, with a label that stays readable from as far back as the whole fall needs; the floor
    // where the fall ends, so that the apple lands on it in the last frame.
    const double yEnd = apple::exact::yLocation(o.scene, run.finalTime);
    const double low = std::min(yEnd, 0.0), high = std::max(o.scene.dropHeight, 0.0), tall = high - low + 1;
    tabulation.scenery.low = {-tall / 4, low - o.scene.radius, -1};
    tabulation.scenery.high = {tall / 4, high + o.scene.radius, 1};
    tabulation.scenery.floorHeight = low - o.scene.radius;
    tabulation.scenery.trails = true;
    tabulation.decorate = [&](apple::Model& m) {
        using namespace SimTK;
        simlab::decorateUnlessDrawn(
            m.apple, {DecorativeSphere(o.scene.radius).setColor(Vec3(0.8, 0.05, 0.05)),
                      DecorativeCylinder(o.scene.radius / 10, o.scene.radius / 3)
                          .setTransform(Vec3(0, o.scene.radius * 1.2, 0))
                          .setColor(Vec3(0.35, 0.2, 0.05)),
                      DecorativeText("apple").setScale(tall / 14).setColor(Vec3(0.5, 0, 0)).setTransform(
                          Vec3(tall / 50, 0, 0))});
    };
    tabulation.program = "apple";
    tabulation.conserved = "mechanicalEnergy";
    tabulation.conservedScale = [&](const apple::Sample& s) {
        return 0.5 * o.scene.mass * s.yVelocity * s.yVelocity + o.scene.mass * o.scene.gravity * std::abs(s.yLocation);
    };
    // The same terms' size over the whole exact fall (an apple dropped at rest from y = 0 starts with none): its
    // kinetic energy at the end, m (g T)^2 / 2, and its potential energy where it is farthest from y = 0.
    const double g = o.scene.gravity, T = run.finalTime;
    const double farthest = std::max(std::abs(o.scene.dropHeight), std::abs(yEnd));
    tabulation.conservedSize = 0.5 * o.scene.mass * (g * T) * (g * T) + o.scene.mass * g * farthest;
    apple::Model model;
    const auto result = simlab::runTabulated(o.scene, model, o.program, tabulation);

    const double digits = finalDigits(o.scene, result.samples);
    const apple::Sample& last = result.samples.back();
    const double yScale = apple::exact::yScale(o.scene, last.time);
    char of[96] = "";
    if (yScale > 0) std::snprintf(of, sizeof of, " of the %.6g m the fall spans (y is near 0)", yScale);
    std::printf("y(%g s) = %.15g m; exact %.15g m: %.1f accurate digits%s (%s, %d steps)\n", last.time, last.yLocation,
                apple::exact::yLocation(o.scene, last.time), digits, of, result.integrator.method.c_str(),
                result.integrator.stepsTaken);
    if (!o.program.plot.empty()) {
        simlab::drawPlot(apple::runPlot(o.scene, simlab::describeRun(run), result.samples), o.program.plot);
        std::printf("Plot drawn in %s\n", o.program.plot.c_str());
    }
    return 0;
}

// --from: an earlier run's results file drawn over the exact fall of this scene, which must be the one it ran.
int drawFrom(const Options& o) {
    std::vector<apple::Sample> samples;
    for (const std::vector<double>& r : simlab::readResults(o.program.from, kColumns)) {
        samples.push_back({r[0], r[1], r[2], r[3]});
    }
    const apple::Sample& first = samples.front();
    if (std::abs(first.yLocation - o.scene.dropHeight) > 1e-9 * std::max(1.0, std::abs(o.scene.dropHeight))) {
        throw std::runtime_error("'" + o.program.from + "' starts at y = " + simlab::shortNumber(first.yLocation) +
                                 " m, this scene at " + simlab::shortNumber(o.scene.dropHeight) +
                                 " m: give the options of the run that wrote it (--drop-height, --gravity)");
    }
    simlab::drawPlot(apple::runPlot(o.scene, "from " + o.program.from, samples), o.program.plot);
    std::printf("Plot drawn in %s\n", o.program.plot.c_str());
    return 0;
}

int runTrade(const Options& o) {
    char figure[32];
    std::snprintf(figure, sizeof figure, "y(%g s)", o.program.run.finalTime);
    simlab::printTrade(std::cout, o.program.run, figure, [&](const simlab::RunSettings& run) {
        apple::Model model;
        const auto result = simlab::run<apple::Sample>(o.scene, model, run);
        return simlab::TradePoint{finalDigits(o.scene, result.samples), result.integrator.stepsTaken,
                                  result.integrator.realizations};
    }, o.program.repeats, "apple");
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    simlab::useReproducibleMath(argv);
    Options o;
    o.program.run = apple::defaultRunSettings();
    o.program.output = "NewtonsAppleResults.txt";

    CLI::App app{"Newton's apple: drop an apple from rest and compare its fall with y = h - g t^2/2.", "apple"};
    simlab::addProgramOptions(app, o.program);
    app.add_option("--drop-height", o.scene.dropHeight, "m, starting height of the apple's center")
        ->check(simlab::between(-1e6, 1e6))
        ->capture_default_str();
    app.add_option("--mass", o.scene.mass, "kg, mass of the apple")->check(simlab::positive())->capture_default_str();
    app.add_option("--gravity", o.scene.gravity, "m/s^2, pulling along -y")
        ->check(simlab::between(0.0, 1e4))
        ->capture_default_str();
    if (const int status = simlab::parseCommandLine(app, argc, argv); status >= 0) return status;

    if (const int status = simlab::checkRunSettings("apple", o.program.run); status >= 0) return status;
    return simlab::runGuarded("apple", [&] {
        if (!o.program.from.empty()) return drawFrom(o);
        return o.program.trade ? runTrade(o) : runOnce(o);
    });
}
