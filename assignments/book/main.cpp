// The `book` lab program (the course's side): runs the simulation written in BookSpin.cpp for one spin, prints
// and saves w, H (in the book and in Ground), |H| and K, compares w at the final time with the exact solution
// (Jacobi elliptic functions, see exact.h), and for a spin about the intermediate axis measures how fast the
// wobble grows, against the linear theory's rate.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "book/BookSpin.h"
#include "book/exact.h"
#include "simlab/cli_checks.h"
#include "simlab/digits.h"
#include "simlab/program.h"

namespace {

using book::Sample;
using book::Scene;

struct Options {
    Scene scene;
    simlab::ProgramOptions program;
    std::string spin = "min";
    std::vector<double> omega;      // rad/s, instead of --spin
    std::vector<double> dimensions;  // m
};

std::vector<double> resultsRow(const Sample& s) {
    return {s.time,   s.w_B[0], s.w_B[1], s.w_B[2], s.H_B[0],         s.H_B[1],
            s.H_B[2], s.Hmag,   s.kineticEnergy,   s.H_G[0], s.H_G[1], s.H_G[2]};
}

// Largest change over the run of f(sample), relative to its first value (f gives a number or a vector).
template <class F>
double relativeChange(const std::vector<Sample>& samples, F f) {
    double worst = 0;
    for (const Sample& s : samples) worst = std::max(worst, SimTK::Vec3(f(s) - f(samples.front())).norm());
    return worst / SimTK::Vec3(f(samples.front())).norm();
}

// The wobble's growth about the intermediate axis: the slope of ln |w_perpendicular| while it grows from twice
// its initial size to 30 % of the spin, fitted by least squares.
void reportGrowth(const Scene& scene, const std::vector<Sample>& samples) {
    const std::array<int, 3> axes = book::exact::axesByMoment(scene);
    const double rate = std::abs(scene.w_B0[axes[1]]);
    auto wobble = [&](const Sample& s) { return std::hypot(s.w_B[axes[0]], s.w_B[axes[2]]); };
    const double start = wobble(samples.front());
    double n = 0, st = 0, sy = 0, stt = 0, sty = 0, t0 = -1, t1 = -1;
    for (const Sample& s : samples) {
        const double p = wobble(s);
        if (p < 2 * start) continue;
        if (p > 0.3 * rate) break;
        if (t0 < 0) t0 = s.time;
        t1 = s.time;
        const double y = std::log(p);
        n += 1;
        st += s.time;
        sy += y;
        stt += s.time * s.time;
        sty += s.time * y;
    }
    const double linear = book::exact::linearGrowthRate(scene, rate);
    if (n < 3) {
        std::printf("The wobble did not grow through the fitting range; linear theory's rate is %.3f rad/s\n", linear);
        return;
    }
    const double measured = (n * sty - st * sy) / (n * stt - st * st);
    std::printf("Wobble about the intermediate axis grows at %.3f rad/s (least-squares slope of ln|w_perp| for "
                "%.2f <= t <= %.2f s);\n  linear theory: lambda = w0 sqrt((Ib - Ia)(Ic - Ib) / (Ia Ic)) = %.3f rad/s "
                "(measured / linear = %.3f)\n",
                measured, t0, t1, linear, measured / linear);
}

int runOnce(const Options& o) {
    const simlab::RunSettings& run = o.program.run;
    const SimTK::Vec3 I = book::exact::principalMoments(o.scene);
    char banner[400];
    std::snprintf(banner, sizeof banner,
                  "Book: %g kg, %g x %g x %g m (I = %.6g, %.6g, %.6g kg m^2), w0 = (%g, %g, %g) rad/s; %s, accuracy %g, "
                  "dt %g s, 0 <= t <= %g s",
                  o.scene.mass, o.scene.dimensions[0], o.scene.dimensions[1], o.scene.dimensions[2], I[0], I[1], I[2],
                  o.scene.w_B0[0], o.scene.w_B0[1], o.scene.w_B0[2], run.integrator.c_str(), run.accuracy, run.dt,
                  run.finalTime);
    simlab::Tabulation<Sample> tabulation;
    tabulation.columns = {"time", "wx", "wy", "wz", "Hx", "Hy", "Hz", "Hmag", "K", "HGx", "HGy", "HGz"};
    tabulation.row = resultsRow;
    tabulation.banner = banner;
    tabulation.bodyRadius = o.scene.dimensions.norm() / 4;
    book::Model model;
    const auto result = simlab::runTabulated(o.scene, model, o.program, tabulation);

    const Sample& last = result.samples.back();
    const SimTK::Vec3 exact = book::exact::angularVelocity(o.scene, last.time);
    std::printf("w(%g s) = (%.12g, %.12g, %.12g) rad/s\n  exact   (%.12g, %.12g, %.12g) rad/s (elliptic functions): "
                "%.1f accurate digits (%s, %d steps)\n",
                last.time, last.w_B[0], last.w_B[1], last.w_B[2], exact[0], exact[1], exact[2],
                book::exact::angularVelocityDigits(o.scene, last.time, last.w_B), result.integrator.method.c_str(),
                result.integrator.stepsTaken);
    std::printf("Largest relative change over the run: K %.2g, |H| %.2g, H in Ground %.2g; w in the book %.2g, H in "
                "the book %.2g\n",
                relativeChange(result.samples, [](const Sample& s) { return SimTK::Vec3(s.kineticEnergy, 0, 0); }),
                relativeChange(result.samples, [](const Sample& s) { return SimTK::Vec3(s.Hmag, 0, 0); }),
                relativeChange(result.samples, [](const Sample& s) { return s.H_G; }),
                relativeChange(result.samples, [](const Sample& s) { return s.w_B; }),
                relativeChange(result.samples, [](const Sample& s) { return s.H_B; }));
    const std::array<int, 3> axes = book::exact::axesByMoment(o.scene);
    if (std::abs(o.scene.w_B0[axes[1]]) > 2 * std::max(std::abs(o.scene.w_B0[axes[0]]), std::abs(o.scene.w_B0[axes[2]]))) {
        reportGrowth(o.scene, result.samples);
    }
    return 0;
}

int runTrade(const Options& o) {
    char figure[32];
    std::snprintf(figure, sizeof figure, "w(%g s)", o.program.run.finalTime);
    simlab::printTrade(std::cout, o.program.run, figure, [&](const simlab::RunSettings& run) {
        book::Model model;
        const auto result = simlab::run<Sample>(o.scene, model, run);
        if (result.samples.empty()) throw std::runtime_error("the simulation recorded no samples");
        const Sample& last = result.samples.back();
        return simlab::TradePoint{book::exact::angularVelocityDigits(o.scene, last.time, last.w_B),
                                  result.integrator.stepsTaken, result.integrator.realizations};
    }, o.program.repeats);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    o.program.run = book::defaultRunSettings();
    o.program.output = "BookSpinResults.txt";

    CLI::App app{"The spinning book: a uniform book spun about one of its principal axes, torque-free. Which "
                 "quantities stay constant, and which spins are stable?",
                 "book"};
    simlab::addProgramOptions(app, o.program);
    CLI::Option* spin = app.add_option("--spin", o.spin, "spin about the min, intermediate or max principal axis: "
                                                         "7 rad/s about it, 0.2 about the others")
                            ->check(CLI::IsMember({"min", "intermediate", "max"}))
                            ->capture_default_str();
    app.add_option("--omega", o.omega, "rad/s: w_B at t = 0 as wx,wy,wz, instead of --spin")
        ->delimiter(',')
        ->expected(3)
        ->excludes(spin);
    app.add_option("--dimensions", o.dimensions, "m: the book's height (x), width (y) and thickness (z) as Lx,Ly,Lz")
        ->delimiter(',')
        ->expected(3)
        ->check(simlab::positive());
    app.add_option("--mass", o.scene.mass, "kg, mass of the book")->check(simlab::positive())->capture_default_str();
    app.get_option("--trade")->description("instead of one run, print w's digits at the final time against cost for "
                                           "every integrator");
    if (const int status = simlab::parseCommandLine(app, argc, argv); status >= 0) return status;

    return simlab::runGuarded("book", [&] {
        simlab::validate(o.program.run);
        if (!o.dimensions.empty()) o.scene.dimensions = SimTK::Vec3(o.dimensions[0], o.dimensions[1], o.dimensions[2]);
        o.scene.w_B0 = o.omega.empty() ? book::exact::spin(o.scene, o.spin)
                                       : SimTK::Vec3(o.omega[0], o.omega[1], o.omega[2]);
        return o.program.trade ? runTrade(o) : runOnce(o);
    });
}
