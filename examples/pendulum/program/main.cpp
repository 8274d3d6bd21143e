// The `pendulum` lab program (the course's side): runs the swing written in Pendulum.cpp, prints its table as it
// goes, writes the results file, and says how close theta and the period come to the exact elliptic swing.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "pendulum/contract/Pendulum.h"
#include "pendulum/program/exact.h"
#include "pendulum/program/period.h"
#include "pendulum/program/run_plot.h"
#include "simlab/cli_checks.h"
#include "simlab/digits.h"
#include "simlab/driver.h"
#include "simlab/messages.h"
#include "simlab/plot.h"
#include "simlab/program.h"
#include "simlab/reproducible_math.h"
#include "simlab/results_table.h"

namespace {

using pendulum::Sample;
using pendulum::Scene;

struct Options {
    Scene scene;
    simlab::ProgramOptions program;
};

const std::vector<std::string> kColumns = {"time", "theta", "thetaDot", "mechanicalEnergy", "thetaDifferenceFromExact"};

std::vector<double> resultsRow(const Scene& scene, const Sample& s) {
    return {s.time, s.theta_rad, s.thetaDot_radps, s.mechanicalEnergy_J,
            s.theta_rad - pendulum::exact::at(scene, s.time).theta_rad};
}

/// Digits of theta at the last sample, its error against theta0 (theta itself may be near zero there).
double finalDigits(const Scene& scene, const std::vector<Sample>& samples) {
    if (samples.empty()) throw std::runtime_error("the simulation recorded no samples");
    const Sample& last = samples.back();
    return simlab::accuracyDigits(last.theta_rad, pendulum::exact::at(scene, last.time).theta_rad,
                                  pendulum::exact::releaseAngle_rad(scene));
}

// The bob drawn as a sphere and the rod as a thin cylinder from it to the pivot.
void decorate(const Scene& scene, pendulum::Model& model) {
    using namespace SimTK;
    const double L = scene.length_m, r = scene.bobRadius_m;
    simlab::decorateUnlessDrawn(
        model.bob, {DecorativeSphere(r).setColor(Vec3(0.1, 0.3, 0.8)),
                    DecorativeCylinder(r / 8, L / 2).setTransform(Vec3(0, L / 2, 0)).setColor(Vec3(0.4)),
                    DecorativeText("bob").setScale(L / 8).setColor(Vec3(0, 0, 0.5)).setTransform(Vec3(r * 1.5, 0, 0))});
}

int runOnce(const Options& o) {
    const simlab::RunSettings& run = o.program.run;
    const Scene& scene = o.scene;
    char banner[300];
    std::snprintf(banner, sizeof banner,
                  "A pendulum's swing: %g kg on %g m released at %g degrees, g = %g m/s^2; %s",
                  scene.mass_kg, scene.length_m, scene.releaseAngle_deg, scene.gravity_mps2,
                  simlab::describeProgramRun(run).c_str());
    simlab::Tabulation<Sample, pendulum::Model> tabulation;
    tabulation.columns = kColumns;
    tabulation.row = [&](const Sample& s) { return resultsRow(scene, s); };
    tabulation.banner = banner;
    tabulation.bodyRadius = scene.bobRadius_m;
    const double reach = scene.length_m + scene.bobRadius_m;
    tabulation.scenery.low = {-reach, -reach, -reach / 2};
    tabulation.scenery.high = {reach, reach, reach / 2};
    tabulation.scenery.floorHeight = -reach;
    tabulation.scenery.trails = true;
    tabulation.decorate = [&](pendulum::Model& m) { decorate(scene, m); };
    tabulation.program = "pendulum";
    tabulation.conserved = "mechanicalEnergy";
    // The size of the terms: kinetic energy, and m g L for the potential energy (which passes zero at the pivot's
    // height, where a release at 90 degrees starts and turns back).
    tabulation.conservedScale = [&](const Sample& s) {
        const double m = scene.mass_kg, L = scene.length_m;
        return 0.5 * m * L * L * s.thetaDot_radps * s.thetaDot_radps + m * scene.gravity_mps2 * L;
    };
    pendulum::Model model;
    const auto result = simlab::runTabulated(scene, model, o.program, tabulation);

    const Sample& last = result.samples.back();
    std::printf("theta(%g s) = %.15g rad; exact %.15g rad: %.1f accurate digits against theta0 (%s, %d steps)\n",
                last.time, last.theta_rad, pendulum::exact::at(scene, last.time).theta_rad,
                finalDigits(scene, result.samples), result.integrator.method.c_str(), result.integrator.stepsTaken);
    const pendulum::MeasuredPeriod period = pendulum::measuredPeriod(result.samples);
    const double exactPeriod_s = pendulum::exact::period_s(scene);
    double farthest_rad = 0;  // the largest |theta| over the run
    for (const Sample& s : result.samples) farthest_rad = std::max(farthest_rad, std::abs(s.theta_rad));
    if (farthest_rad > SimTK::Pi) {
        // Released from rest below the top, the exact swing never passes it: a run that does gained energy.
        std::printf("period: exact %.10g s; none measured: the run went over the top (|theta| reached %.4g rad, past "
                    "pi), which a swing released from rest never does: the run gained energy (see --accuracy, "
                    "--integrator)\n",
                    exactPeriod_s, farthest_rad);
    } else if (pendulum::exact::modulus(scene) == 0) {
        std::printf("period: none: released at 0 degrees the bob hangs at rest and stays there (a small swing about "
                    "it would take %.10g s)\n",
                    exactPeriod_s);
    } else if (std::isnan(period.period_s) && std::floor(last.time / (exactPeriod_s / 2)) >= 2) {
        // Turning points came, but no sample fell between two of them: the samples are farther apart than they.
        const double dt_s = result.samples.size() > 1 ? result.samples[1].time - result.samples[0].time : last.time;
        std::printf("period: exact %.10g s; the samples, %g s apart, are too far apart to show it: %d turning point%s "
                    "seen by t = %g s, where %.0f came (every half period, %.4g s); a --dt under %.4g s shows each\n",
                    exactPeriod_s, dt_s, period.turningPoints, period.turningPoints == 1 ? "" : "s", last.time,
                    std::floor(last.time / (exactPeriod_s / 2)), exactPeriod_s / 2, exactPeriod_s / 2);
    } else if (std::isnan(period.period_s)) {
        std::printf("period: exact %.10g s; the run is too short to show it: %d turning point%s by t = %g s, where "
                    "two are needed (they come every half period, %.4g s)\n",
                    exactPeriod_s, period.turningPoints, period.turningPoints == 1 ? "" : "s", last.time,
                    exactPeriod_s / 2);
    } else {
        std::printf("period from %d turning points: %.10g s; exact %.10g s: %.1f accurate digits\n",
                    period.turningPoints, period.period_s, exactPeriod_s,
                    simlab::accuracyDigits(period.period_s, exactPeriod_s));
    }
    if (!o.program.plot.empty()) {
        simlab::drawPlot(pendulum::runPlot(scene, simlab::describeRun(run), result.samples), o.program.plot);
        std::printf("Plot drawn in %s\n", o.program.plot.c_str());
    }
    return 0;
}

// --from: an earlier run's results file drawn over the exact swing of this scene, which must be the one it ran.
int drawFrom(const Options& o) {
    std::vector<Sample> samples;
    for (const std::vector<double>& r : simlab::readResults(o.program.from, kColumns)) {
        samples.push_back({r[0], r[1], r[2], r[3]});
    }
    const double theta0_rad = pendulum::exact::releaseAngle_rad(o.scene);
    if (std::abs(samples.front().theta_rad - theta0_rad) > 1e-9) {
        throw std::runtime_error("'" + o.program.from + "' starts at theta = " +
                                 simlab::shortNumber(samples.front().theta_rad) + " rad, this scene at " +
                                 simlab::shortNumber(theta0_rad) +
                                 " rad: give the options of the run that wrote it (--release-angle)");
    }
    simlab::drawPlot(pendulum::runPlot(o.scene, "from " + o.program.from, samples), o.program.plot);
    std::printf("Plot drawn in %s\n", o.program.plot.c_str());
    return 0;
}

int runTrade(const Options& o) {
    char figure[32];
    std::snprintf(figure, sizeof figure, "theta(%g s)", o.program.run.finalTime);
    simlab::printTrade(std::cout, o.program.run, figure, [&](const simlab::RunSettings& run) {
        pendulum::Model model;
        const auto result = simlab::run<Sample>(o.scene, model, run);
        return simlab::TradePoint{finalDigits(o.scene, result.samples), result.integrator.stepsTaken,
                                  result.integrator.realizations};
    }, o.program.repeats, "pendulum");
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    simlab::useReproducibleMath(argv);
    Options o;
    o.program.run = pendulum::defaultRunSettings();
    o.program.output = "PendulumResults.txt";

    CLI::App app{"A pendulum's swing: release a bob on a rod from rest and compare its swing with the exact "
                 "elliptic one, sin(theta/2) = k sn(K - w0 t, k).",
                 "pendulum"};
    simlab::addProgramOptions(app, o.program);
    app.add_option("--release-angle", o.scene.releaseAngle_deg, "degrees from the downward vertical, at rest at t = 0")
        ->check(simlab::between(-179.9, 179.9))
        ->capture_default_str();
    app.add_option("--length", o.scene.length_m, "m, from the pivot to the bob")
        ->check(simlab::between(1e-3, 1e3))
        ->capture_default_str();
    app.add_option("--mass", o.scene.mass_kg, "kg, the bob")->check(simlab::positive())->capture_default_str();
    app.add_option("--gravity", o.scene.gravity_mps2, "m/s^2, pulling along -y")
        ->check(simlab::between(1e-3, 1e4))
        ->capture_default_str();
    if (const int status = simlab::parseCommandLine(app, argc, argv); status >= 0) return status;

    if (const int status = simlab::checkRunSettings("pendulum", o.program.run); status >= 0) return status;
    return simlab::runGuarded("pendulum", [&] {
        if (!o.program.from.empty()) return drawFrom(o);
        return o.program.trade ? runTrade(o) : runOnce(o);
    });
}
