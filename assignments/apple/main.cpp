// The `apple` lab program (the course's side): runs the simulation written in NewtonsApple.cpp, prints its
// table as it goes, writes the results file and says how many digits of y at the final time are right.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>

#include "apple/NewtonsApple.h"
#include "apple/exact.h"
#include "simlab/cli_checks.h"
#include "simlab/digits.h"
#include "simlab/driver.h"
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
    const apple::Sample& last = samples.back();
    return simlab::accuracyDigits(last.yLocation, apple::exact::yLocation(scene, last.time));
}

int runOnce(const Options& o) {
    const simlab::RunSettings& run = o.program.run;
    char banner[256];
    std::snprintf(banner, sizeof banner,
                  "Newton's apple: %g kg dropped from %g m, g = %g m/s^2; %s, accuracy %g, dt %g s, 0 <= t <= %g s",
                  o.scene.mass, o.scene.dropHeight, o.scene.gravity, run.integrator.c_str(), run.accuracy, run.dt,
                  run.finalTime);
    simlab::Tabulation<apple::Sample> tabulation;
    tabulation.columns = {"time", "yLocation", "yVelocity", "mechanicalEnergy", "yDifferenceFromExact"};
    tabulation.row = [&](const apple::Sample& s) { return resultsRow(o.scene, s); };
    tabulation.banner = banner;
    tabulation.bodyRadius = o.scene.radius;
    tabulation.program = "apple";
    tabulation.conserved = "mechanicalEnergy";
    apple::Model model;
    const auto result = simlab::runTabulated(o.scene, model, o.program, tabulation);

    const double digits = finalDigits(o.scene, result.samples);
    const apple::Sample& last = result.samples.back();
    std::printf("y(%g s) = %.15g m; exact %.15g m: %.1f accurate digits (%s, %d steps)\n", last.time, last.yLocation,
                apple::exact::yLocation(o.scene, last.time), digits, result.integrator.method.c_str(),
                result.integrator.stepsTaken);
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
    Options o;
    o.program.run = apple::defaultRunSettings();
    o.program.output = "NewtonsAppleResults.txt";

    CLI::App app{"Newton's apple: drop an apple from rest and compare its fall with y = h - g t^2/2.", "apple"};
    simlab::addProgramOptions(app, o.program);
    app.add_option("--drop-height", o.scene.dropHeight, "m, starting height of the apple's center")
        ->check(CLI::Range(-1e6, 1e6))
        ->capture_default_str();
    app.add_option("--mass", o.scene.mass, "kg, mass of the apple")->check(simlab::positive())->capture_default_str();
    app.add_option("--gravity", o.scene.gravity, "m/s^2, pulling along -y")
        ->check(CLI::Range(0.0, 1e4))
        ->capture_default_str();
    if (const int status = simlab::parseCommandLine(app, argc, argv); status >= 0) return status;

    if (const int status = simlab::checkRunSettings("apple", o.program.run); status >= 0) return status;
    return simlab::runGuarded("apple", [&] {
        return o.program.trade ? runTrade(o) : runOnce(o);
    });
}
