// The `book` lab program (the course's side): runs the simulation written in BookSpin.cpp for one spin, prints
// and saves w, H (in the book and in Ground), |H| and K, compares w at the final time with the exact solution
// (Jacobi elliptic functions, see exact.h), and for a spin about the intermediate axis measures how fast the
// wobble grows, against the linear theory's rate.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "book/BookSpin.h"
#include "book/exact.h"
#include "book/run_plot.h"
#include "simlab/reproducible_math.h"
#include "simlab/cli_checks.h"
#include "simlab/digits.h"
#include "simlab/messages.h"
#include "simlab/plot.h"
#include "simlab/results_table.h"
#include "simlab/program.h"

namespace {

// Why Simbody cannot spin this book, or "". Its motion does not depend on the mass or the size (w(t) is the same
// for any book of the same proportions), but Simbody's dynamics do not keep their digits far from ordinary
// magnitudes. Measured on the lab's book: 1e-100 kg runs and 1e-101 kg cannot take a first step; 1e100 kg keeps
// 9.4 digits and 1e105 kg 1.2; moments of 3.5e-103 kg m^2 run and 6.7e-106 cannot start.
std::string bookProblem(const book::Scene& scene) {
    const SimTK::Vec3 I = book::exact::principalMoments(scene);
    const double smallest = std::min({I[0], I[1], I[2]}), largest = std::max({I[0], I[1], I[2]});
    char why[280];
    if (!(scene.mass >= 1e-100 && scene.mass <= 1e100)) {
        std::snprintf(why, sizeof why,
                      "a mass of %g kg is outside 1e-100 to 1e100 kg, where Simbody's dynamics keep their digits; the "
                      "motion does not depend on the mass: give one inside", scene.mass);
        return why;
    }
    if (!(smallest >= 1e-103 && largest <= 1e100)) {
        std::snprintf(why, sizeof why,
                      "moments of inertia of %g to %g kg m^2 are outside 1e-103 to 1e100 kg m^2, where Simbody's "
                      "dynamics keep their digits; the motion depends only on the book's proportions: give "
                      "--dimensions nearer a metre", smallest, largest);
        return why;
    }
    return "";
}

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
    for (const Sample& s : samples) worst = std::max(worst, book::exact::magnitude(SimTK::Vec3(f(s) - f(samples.front()))));
    return worst / book::exact::magnitude(SimTK::Vec3(f(samples.front())));
}

// The wobble's growth about the intermediate axis: the slope of ln |w_perpendicular| while it grows from twice
// its initial size to 30 % of the spin, fitted by least squares. A rate is given only when the wobble grows
// through that range at the start of the run, sample after sample, and ln |w_perp| lies on the fitted line:
// otherwise the growth is not the exponential the linear theory describes, and the line says why.
void reportGrowth(const Scene& scene, const std::vector<Sample>& samples) {
    const std::array<int, 3> axes = book::exact::axesByMoment(scene);
    const double rate = std::abs(scene.w_B0[axes[1]]);
    const double linear = book::exact::linearGrowthRate(scene, rate);
    char theory[160];
    std::snprintf(theory, sizeof theory, "linear theory's rate is %.3f rad/s", linear);
    auto wobble = [&](const Sample& s) { return std::hypot(s.w_B[axes[0]], s.w_B[axes[2]]); };
    const double start = wobble(samples.front());
    if (!(start > 1e-12 * rate)) {
        std::printf("No growth rate: w0 lies along the intermediate axis, an equilibrium nothing disturbs; %s\n",
                    theory);
        return;
    }
    if (!(linear > 0)) {
        std::printf("No growth rate: the intermediate moment equals another, so the spin is not unstable\n");
        return;
    }
    // The fitting window: the samples from the first with |w_perp| >= 2 |w_perp(0)| while it keeps growing and
    // stays under 30 % of the spin.
    std::vector<double> t, y;
    bool started = false, grew = false;
    double previous = start;
    for (const Sample& s : samples) {
        const double p = wobble(s);
        if (!started && p >= 2 * start && p <= 0.3 * rate) started = true;
        if (started) {
            if (p > 0.3 * rate) { grew = true; break; }
            if (p <= previous) break;  // it stopped growing before reaching 30 %
            t.push_back(s.time);
            y.push_back(std::log(p));
        }
        previous = p;
    }
    if (!started || !grew || t.size() < 5) {
        std::printf("No growth rate: the wobble did not grow steadily from %.3g to %.3g rad/s over 5 or more samples "
                    "(a smaller --dt, a smaller initial wobble or a longer run may show it); %s\n",
                    2 * start, 0.3 * rate, theory);
        return;
    }
    const double n = static_cast<double>(t.size());
    double st = 0, sy = 0, stt = 0, sty = 0;
    for (std::size_t i = 0; i < t.size(); ++i) {
        st += t[i];
        sy += y[i];
        stt += t[i] * t[i];
        sty += t[i] * y[i];
    }
    const double measured = (n * sty - st * sy) / (n * stt - st * st);
    const double intercept = (sy - measured * st) / n;
    // How far ln|w_perp| strays from the line, against the rise it fits: an exponential stays within a few %.
    double worst = 0;
    for (std::size_t i = 0; i < t.size(); ++i) worst = std::max(worst, std::abs(y[i] - intercept - measured * t[i]));
    const double rise = y.back() - y.front();
    if (!(measured > 0) || !std::isfinite(measured) || !(worst < 0.05 * rise)) {
        std::printf("No growth rate: ln|w_perp| does not rise along a line for %.2f <= t <= %.2f s (it strays %.2g "
                    "from the fit over a rise of %.2g), so the growth is not exponential; %s\n",
                    t.front(), t.back(), worst, rise, theory);
        return;
    }
    std::printf("Wobble about the intermediate axis grows at %.3f rad/s (least-squares slope of ln|w_perp| for "
                "%.2f <= t <= %.2f s);\n  linear theory: lambda = w0 sqrt((Ib - Ia)(Ic - Ib) / (Ia Ic)) = %.3f rad/s "
                "(measured / linear = %.3f)\n",
                measured, t.front(), t.back(), linear, measured / linear);
}

// Digits of a simulated w_B at time t against Euler's equations integrated in long double, and no more than that
// reference's own accuracy supports (`capped` says when that limits them).
struct WDigits {
    double digits = 0;
    bool capped = false;
    SimTK::Vec3 reference;
};

WDigits digitsAgainst(const book::exact::Reference& reference, const SimTK::Vec3& w_B) {
    const double size = book::exact::magnitude(reference.w_B);
    WDigits d;
    d.reference = reference.w_B;
    if (!w_B.isFinite()) return d;
    d.digits = simlab::accuracyDigits(book::exact::magnitude(w_B - reference.w_B), 0.0, size);
    const double held = reference.error > 0 ? simlab::accuracyDigits(reference.error, 0.0, size) : simlab::kMaxDigits;
    if (d.digits > held) {
        d.digits = held;
        d.capped = true;
    }
    return d;
}

const std::vector<std::string> kColumns = {"time", "wx", "wy", "wz", "Hx", "Hy", "Hz", "Hmag", "K", "HGx", "HGy", "HGz"};

// The book as --animate draws it: a brick of its size whose six faces each have their own colour (x faces red,
// y faces green, z faces blue; the + face of each pair the brighter), and its body axes.
std::vector<SimTK::DecorativeGeometry> bookDrawing(const SimTK::Vec3& dimensions) {
    using namespace SimTK;
    const Vec3 half = dimensions / 2;
    const double skin = std::max(half.norm() / 200, 1e-4);  // a face's thickness, just over the brick's own
    std::vector<DecorativeGeometry> drawing{DecorativeBrick(half * 0.995).setColor(Vec3(0.92, 0.9, 0.82))};
    for (int axis = 0; axis < 3; ++axis) {
        for (const int side : {1, -1}) {
            Vec3 faceHalf = half, at(0);
            faceHalf[axis] = skin;
            at[axis] = side * half[axis];
            Vec3 color(0.15);
            color[axis] = side > 0 ? 0.95 : 0.55;
            drawing.push_back(DecorativeBrick(faceHalf).setTransform(at).setColor(color));
        }
    }
    drawing.push_back(DecorativeFrame(half.norm() * 1.3).setLineThickness(3));
    return drawing;
}

void drawRequestedPlot(const Options& o, const std::vector<Sample>& samples) {
    if (o.program.plot.empty()) return;
    const std::string spin = o.omega.empty() ? "about the " + o.spin + " axis" : "from the given w0";
    const std::string how = o.program.from.empty() ? simlab::describeRun(o.program.run) : "from " + o.program.from;
    simlab::drawPlot(book::runPlot(o.scene, spin, how, samples), o.program.plot);
    std::printf("Plot drawn in %s\n", o.program.plot.c_str());
}

// --from: an earlier run's results file drawn over this scene's exact spin, which must be the one it ran.
int drawFrom(const Options& o) {
    std::vector<Sample> samples;
    for (const std::vector<double>& r : simlab::readResults(o.program.from, kColumns)) {
        samples.push_back({r[0], SimTK::Vec3(r[1], r[2], r[3]), SimTK::Vec3(r[4], r[5], r[6]),
                           SimTK::Vec3(r[9], r[10], r[11]), r[7], r[8]});
    }
    const SimTK::Vec3& w0 = samples.front().w_B;
    if ((w0 - o.scene.w_B0).norm() > 1e-9 * std::max(1.0, o.scene.w_B0.norm())) {
        throw std::runtime_error("'" + o.program.from + "' starts at w = (" + simlab::shortNumber(w0[0]) + ", " +
                                 simlab::shortNumber(w0[1]) + ", " + simlab::shortNumber(w0[2]) +
                                 ") rad/s, not this scene's: give the options of the run that wrote it (--spin or "
                                 "--omega, --dimensions, --mass)");
    }
    drawRequestedPlot(o, samples);
    return 0;
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
    simlab::Tabulation<Sample, book::Model> tabulation;
    tabulation.columns = kColumns;
    tabulation.row = resultsRow;
    tabulation.banner = banner;
    tabulation.bodyRadius = o.scene.dimensions.norm() / 4;
    const double size = std::max(o.scene.dimensions.norm(), 1e-3);
    tabulation.scenery.low = SimTK::Vec3(-size / 2);
    tabulation.scenery.high = SimTK::Vec3(size / 2);
    tabulation.scenery.floor = false;  // the book turns about a point fixed in space; a floor would cut it
    tabulation.decorate = [&](book::Model& m) { simlab::decorateUnlessDrawn(m.book, bookDrawing(o.scene.dimensions)); };
    tabulation.program = "book";
    tabulation.conserved = "K";
    book::Model model;
    const auto result = simlab::runTabulated(o.scene, model, o.program, tabulation);

    const Sample& last = result.samples.back();
    const book::exact::Reference reference = book::exact::integratedAngularVelocity(o.scene, last.time);
    const WDigits digits = digitsAgainst(reference, last.w_B);
    // The elliptic solution is shown where it agrees with the integrated reference to the 12 digits printed.
    const SimTK::Vec3 elliptic = book::exact::angularVelocity(o.scene, last.time);
    const double ellipticDigits = simlab::accuracyDigits(book::exact::magnitude(elliptic - reference.w_B), 0.0,
                                                        book::exact::magnitude(reference.w_B));
    char source[160] = "elliptic functions";
    if (ellipticDigits < 12.5) {
        std::snprintf(source, sizeof source, "Euler's equations integrated in long double; the elliptic functions "
                      "hold %.1f digits here", ellipticDigits);
    }
    const SimTK::Vec3 exact = ellipticDigits < 12.5 ? reference.w_B : elliptic;
    std::printf("w(%g s) = (%.12g, %.12g, %.12g) rad/s\n  exact   (%.12g, %.12g, %.12g) rad/s (%s): "
                "%.1f accurate digits%s (%s, %d steps)\n",
                last.time, last.w_B[0], last.w_B[1], last.w_B[2], exact[0], exact[1], exact[2], source, digits.digits,
                digits.capped ? ", all the reference integration of Euler's equations can confirm" : "",
                result.integrator.method.c_str(), result.integrator.stepsTaken);
    if (o.scene.w_B0.norm() == 0) {
        // A book at rest has nothing to be relative to: the changes are absolute, and should be zero.
        double moved = 0;
        for (const Sample& s : result.samples) moved = std::max(moved, s.w_B.norm());
        std::printf("The book starts at rest: the largest |w| over the run is %.2g rad/s\n", moved);
        drawRequestedPlot(o, result.samples);
        return 0;
    }
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
    drawRequestedPlot(o, result.samples);
    return 0;
}

int runTrade(const Options& o) {
    char figure[32];
    std::snprintf(figure, sizeof figure, "w(%g s)", o.program.run.finalTime);
    // The reference for the final time, worked out before the runs are timed.
    const book::exact::Reference reference = book::exact::integratedAngularVelocity(o.scene, o.program.run.finalTime);
    simlab::printTrade(std::cout, o.program.run, figure, [&](const simlab::RunSettings& run) {
        book::Model model;
        const auto result = simlab::run<Sample>(o.scene, model, run);
        if (result.samples.empty()) throw std::runtime_error("the simulation recorded no samples");
        const Sample& last = result.samples.back();
        const double digits = last.time == run.finalTime
                                  ? digitsAgainst(reference, last.w_B).digits
                                  : digitsAgainst(book::exact::integratedAngularVelocity(o.scene, last.time), last.w_B).digits;
        return simlab::TradePoint{digits,
                                  result.integrator.stepsTaken, result.integrator.realizations};
    }, o.program.repeats, "book");
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    simlab::useReproducibleMath(argv);
    Options o;
    o.program.run = book::defaultRunSettings();
    o.program.output = "BookSpinResults-SPIN.txt";  // SPIN: the spin's name, so that each spin keeps its file

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
    if (app.get_option("--output")->count() == 0) {
        o.program.output = "BookSpinResults-" + (o.omega.empty() ? o.spin : std::string("omega")) + ".txt";
    }

    if (const int status = simlab::checkRunSettings("book", o.program.run); status >= 0) return status;
    book::Scene asked = o.scene;
    if (!o.dimensions.empty()) asked.dimensions = SimTK::Vec3(o.dimensions[0], o.dimensions[1], o.dimensions[2]);
    if (const std::string problem = bookProblem(asked); !problem.empty() && o.program.from.empty()) {
        std::cerr << "book: error: " << problem << '\n';
        return 2;
    }
    return simlab::runGuarded("book", [&] {
        if (!o.dimensions.empty()) o.scene.dimensions = SimTK::Vec3(o.dimensions[0], o.dimensions[1], o.dimensions[2]);

        o.scene.w_B0 = o.omega.empty() ? book::exact::spin(o.scene, o.spin)
                                       : SimTK::Vec3(o.omega[0], o.omega[1], o.omega[2]);
        if (!o.program.from.empty()) return drawFrom(o);
        return o.program.trade ? runTrade(o) : runOnce(o);
    });
}
