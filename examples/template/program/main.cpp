// The lab program (the course's side): runs the simulation written in MyLab.cpp, prints its table as it goes,
// writes the results file, and says how many digits of x agree with the exact oscillation.
//
// CHANGE: the results' columns, the banner, the drawing, the plot and the scene's command-line options to your
// scene's. Keep the shape: runOnce for one run, drawFrom for --from, runTrade for --trade, main guarding them all.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "mylab/contract/MyLab.h"
#include "mylab/program/exact.h"
#include "simlab/cli_checks.h"
#include "simlab/digits.h"
#include "simlab/driver.h"
#include "simlab/messages.h"
#include "simlab/plot.h"
#include "simlab/program.h"
#include "simlab/reproducible_math.h"
#include "simlab/results_table.h"

namespace {

using mylab::Sample;
using mylab::Scene;

struct Options {
    Scene scene;
    simlab::ProgramOptions program;
};

const std::vector<std::string> kColumns = {"time", "x", "xDot", "mechanicalEnergy", "xDifferenceFromExact"};

std::vector<double> resultsRow(const Scene& scene, const Sample& s) {
    return {s.time, s.x_m, s.xDot_mps, s.mechanicalEnergy_J, s.x_m - mylab::exact::position_m(scene, s.time)};
}

// x and x' as simulated, every few samples, over the exact oscillation drawn as a line.
simlab::Plot runPlot(const Scene& scene, const std::string& how, const std::vector<Sample>& samples) {
    simlab::Plot plot;
    plot.title = "A block on a spring: m = " + simlab::shortNumber(scene.mass_kg) + " kg, k = " +
                 simlab::shortNumber(scene.stiffness_Npm) + " N/m - " + how;
    simlab::PlotCurve x("simulated x", true), xDot("simulated x'", true);
    simlab::PlotCurve xExact("exact: x0 cos(omega t)"), xDotExact("exact: -x0 omega sin(omega t)");
    for (std::size_t i : simlab::thinned(samples.size(), 80)) {
        x.x.push_back(samples[i].time), x.y.push_back(samples[i].x_m);
        xDot.x.push_back(samples[i].time), xDot.y.push_back(samples[i].xDot_mps);
    }
    const double end_s = samples.empty() ? 0.0 : samples.back().time;
    for (int k = 0; k <= 400; ++k) {
        const double t_s = end_s * k / 400;
        xExact.x.push_back(t_s), xExact.y.push_back(mylab::exact::position_m(scene, t_s));
        xDotExact.x.push_back(t_s), xDotExact.y.push_back(mylab::exact::velocity_mps(scene, t_s));
    }
    plot.panels.emplace_back("", "position x (m)", std::vector<simlab::PlotCurve>{xExact, x});
    plot.panels.emplace_back("time t (s)", "velocity x' (m/s)", std::vector<simlab::PlotCurve>{xDotExact, xDot});
    return plot;
}

int runOnce(const Options& o) {
    const simlab::RunSettings& run = o.program.run;
    const Scene& scene = o.scene;
    char banner[300];
    std::snprintf(banner, sizeof banner,
                  "A block on a spring: %g kg, k = %g N/m, released at x = %g m; %s", scene.mass_kg,
                  scene.stiffness_Npm, scene.releasePosition_m, simlab::describeProgramRun(run).c_str());
    simlab::Tabulation<Sample, mylab::Model> tabulation;
    tabulation.columns = kColumns;
    tabulation.row = [&](const Sample& s) { return resultsRow(scene, s); };
    tabulation.banner = banner;
    tabulation.bodyRadius = scene.blockSize_m / 2;
    const double reach = std::abs(scene.releasePosition_m) + scene.blockSize_m;
    tabulation.scenery.low = {-reach, -reach / 2, -reach / 2};
    tabulation.scenery.high = {reach, reach / 2, reach / 2};
    tabulation.scenery.floorHeight = -scene.blockSize_m / 2;
    tabulation.decorate = [&](mylab::Model& m) {
        using namespace SimTK;
        simlab::decorateUnlessDrawn(m.block, {DecorativeBrick(Vec3(scene.blockSize_m / 2)).setColor(Vec3(0.8, 0.4, 0.1))});
    };
    tabulation.program = "mylab";
    tabulation.conserved = "mechanicalEnergy";
    tabulation.conservedScale = [&](const Sample& s) { return mylab::exact::energyOf_J(scene, s.x_m, s.xDot_mps); };
    mylab::Model model;
    const auto result = simlab::runTabulated(scene, model, o.program, tabulation);

    const Sample& last = result.samples.back();
    std::printf("x(%g s) = %.15g m; exact %.15g m. Worst sample: %.1f accurate digits against x0 (%s, %d steps)\n",
                last.time, last.x_m, mylab::exact::position_m(scene, last.time),
                mylab::exact::worstDigits(scene, result.samples), result.integrator.method.c_str(),
                result.integrator.stepsTaken);
    if (!o.program.plot.empty()) {
        simlab::drawPlot(runPlot(scene, simlab::describeRun(run), result.samples), o.program.plot);
        std::printf("Plot drawn in %s\n", o.program.plot.c_str());
    }
    return 0;
}

// --from: an earlier run's results file drawn over the exact oscillation of this scene.
int drawFrom(const Options& o) {
    std::vector<Sample> samples;
    for (const std::vector<double>& r : simlab::readResults(o.program.from, kColumns)) {
        samples.push_back({r[0], r[1], r[2], r[3]});
    }
    simlab::drawPlot(runPlot(o.scene, "from " + o.program.from, samples), o.program.plot);
    std::printf("Plot drawn in %s\n", o.program.plot.c_str());
    return 0;
}

int runTrade(const Options& o) {
    simlab::printTrade(std::cout, o.program.run, "x at the worst sample", [&](const simlab::RunSettings& run) {
        mylab::Model model;
        const auto result = simlab::run<Sample>(o.scene, model, run);
        return simlab::TradePoint{mylab::exact::worstDigits(o.scene, result.samples), result.integrator.stepsTaken,
                                  result.integrator.realizations};
    }, o.program.repeats, "mylab");
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    simlab::useReproducibleMath(argv);
    Options o;
    o.program.run = mylab::defaultRunSettings();
    o.program.output = "MyLabResults.txt";

    CLI::App app{"A block on a spring: release a block on a frictionless rail from rest and compare its motion "
                 "with the exact x0 cos(omega t).",
                 "mylab"};
    simlab::addProgramOptions(app, o.program);
    app.add_option("--mass", o.scene.mass_kg, "kg, the block")->check(simlab::positive())->capture_default_str();
    app.add_option("--stiffness", o.scene.stiffness_Npm, "N/m, the spring")
        ->check(simlab::positive())
        ->capture_default_str();
    app.add_option("--release-position", o.scene.releasePosition_m, "m from the rest position, at rest at t = 0")
        ->check(simlab::between(-1e3, 1e3))
        ->capture_default_str();
    if (const int status = simlab::parseCommandLine(app, argc, argv); status >= 0) return status;

    if (const int status = simlab::checkRunSettings("mylab", o.program.run); status >= 0) return status;
    return simlab::runGuarded("mylab", [&] {
        if (!o.program.from.empty()) return drawFrom(o);
        return o.program.trade ? runTrade(o) : runOnce(o);
    });
}
