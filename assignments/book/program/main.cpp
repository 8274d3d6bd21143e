// The `book` lab program (the course's side): runs the simulation written in BookSpin.cpp for one spin, prints
// and saves w, H (in the book and in Ground), |H| and K, compares w at the final time with the exact solution
// (Jacobi elliptic functions, see exact.h), and for a spin about the intermediate axis measures how fast the
// wobble grows, against the linear theory's rate.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "book/contract/BookSpin.h"
#include "book/program/exact.h"
#include "book/program/reference.h"
#include "book/program/run_plot.h"
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
    // Simbody forms the kinetic energy and the gyroscopic terms, I w^2: worked out in long double, they must fit a
    // double with room to spare.
    long double energy = 0, spin2 = 0;
    for (int i = 0; i < 3; ++i) {
        const long double w = scene.w_B0[i];
        energy += 0.5L * I[i] * w * w;
        spin2 += w * w;
    }
    if (!(energy <= 1e300L)) {
        std::snprintf(why, sizeof why,
                      "a spin of %.3Lg rad/s gives the book a kinetic energy of %.3Lg J, past 1e300 J, where the terms "
                      "Simbody's dynamics form overflow a double: give a smaller --omega (its size only sets the "
                      "motion's pace)", std::sqrt(spin2), energy);
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
    if (!(start > 0)) {
        std::printf("No growth rate: w0 lies along the intermediate axis, an equilibrium nothing disturbs; %s\n",
                    theory);
        return;
    }
    // A wobble below the rounding of the spin itself (a double's 1.1e-16 of it) is not what disturbs the run: the
    // simulation's own rounding is, at least as much.
    if (start < 1.1e-16 * rate) {
        std::printf("The wobble of %.2g rad/s is below the rounding of a %.3g rad/s spin in double precision (%.2g): "
                    "the run's own rounding disturbs the spin as much as w0 does, so a growth rate would measure "
                    "that rounding; %s\n",
                    start, rate, 1.1e-16 * rate, theory);
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
        // Where linear theory puts the wobble's arrival at 30 % of the spin: ln(0.3 w0 / |w_perp(0)|) / lambda.
        const double arrival = std::log(0.3 * rate / start) / linear;
        std::printf("No growth rate: the wobble did not grow steadily from %.3g to %.3g rad/s over 5 or more samples "
                    "(linear theory has it reach %.3g rad/s at t = %.3g s; a smaller --dt, a smaller initial wobble "
                    "or a longer run may show it); %s\n",
                    2 * start, 0.3 * rate, 0.3 * rate, arrival, theory);
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

// Conditioning: the motion turns on the differences of the moments, I_y - I_x and the like. Where two moments differ
// by a small share of their size, rounding each to a double keeps few digits of their difference (none, for a
// needle of 1e-9 by 2e-9 by 1 m), and every run, the reference's too, follows a slightly different book from the one
// described. The difference m (L_j^2 - L_i^2) / 12 computed from the dimensions, (L_j - L_i)(L_j + L_i), keeps its
// digits; the line compares the rounded moments' difference with it.
void reportConditioning(const Scene& scene) {
    const SimTK::Vec3 I = book::exact::principalMoments(scene);
    const SimTK::Vec3& L = scene.dimensions;
    const char* names = "xyz";
    double worst = simlab::kMaxDigits, share = 0;
    int a = 0, b = 1;
    for (int i = 0; i < 3; ++i) {
        for (int j = i + 1; j < 3; ++j) {
            // I_j - I_i = m/12 (L_i^2 - L_j^2): I about an axis sums the squares of the other two dimensions.
            const double described = scene.mass / 12 * (L[i] - L[j]) * (L[i] + L[j]);
            const double rounded = I[j] - I[i];
            if (described == 0 && rounded == 0) continue;  // equal by design: nothing is lost
            const double held = simlab::accuracyDigits(rounded, described);
            if (held < worst) {
                worst = held;
                share = std::abs(described) / std::max(std::abs(I[i]), std::abs(I[j]));
                a = i;
                b = j;
            }
        }
    }
    if (worst >= 12) return;
    std::printf("Conditioning: I_%c and I_%c differ by %.2g of their size, and rounding the moments to doubles keeps "
                "%.1f digits of that difference: every run, the reference's too, spins a book slightly different from "
                "the one described\n",
                names[a], names[b], share, worst);
}

// Digits of a simulated w_B against the certified reference: the worst component against |w_B(0)|, the one
// definition the study and the grader use too (book::exact::spinDigits), and no more than the reference is certified
// to (`capped` says when that limits them).
struct WDigits {
    double digits = 0;
    double held = simlab::kMaxDigits;  ///< the reference's certified digits on the same scale
    bool capped = false;
};

WDigits digitsAgainst(const Scene& scene, const book::exact::CertifiedSpin& reference, const SimTK::Vec3& w_B) {
    WDigits d;
    const double scale = book::exact::magnitude(scene.w_B0);
    d.held = reference.error > 0 ? simlab::accuracyDigits(reference.error, 0.0, scale) : simlab::kMaxDigits;
    if (!w_B.isFinite()) return d;
    d.digits = book::exact::spinDigits(scene, w_B, {reference.y[0], reference.y[1], reference.y[2]});
    if (d.digits > d.held) {
        d.digits = d.held;
        d.capped = true;
    }
    return d;
}

// A component of the reference printed to the digits its certified error leaves: "-6.99999997379" where the error
// is 1e-13, "-0.0058" where it is 1e-4, and "0 +- 2e-13" where the error is larger than the value.
std::string certifiedNumber(double value, double error) {
    char text[64];
    if (!(error > 0)) {
        std::snprintf(text, sizeof text, "%.12g", value);
        return text;
    }
    if (!(std::abs(value) > error)) {
        std::snprintf(text, sizeof text, "0 +- %.0e", error);
        return text;
    }
    const int significant = static_cast<int>(std::floor(std::log10(std::abs(value)))) -
                            static_cast<int>(std::ceil(std::log10(error))) + 1;
    std::snprintf(text, sizeof text, "%.*g", std::clamp(significant, 1, 12), value);
    return text;
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
                  "Book: %g kg, %g x %g x %g m (I = %.6g, %.6g, %.6g kg m^2), w0 = (%g, %g, %g) rad/s; %s",
                  o.scene.mass, o.scene.dimensions[0], o.scene.dimensions[1], o.scene.dimensions[2], I[0], I[1], I[2],
                  o.scene.w_B0[0], o.scene.w_B0[1], o.scene.w_B0[2], simlab::describeProgramRun(run).c_str());
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
    const book::exact::CertifiedSpin reference = book::exact::certifiedAngularVelocity(o.scene, last.time);
    const WDigits digits = digitsAgainst(o.scene, reference, last.w_B);
    // The elliptic solution is named as the source where it agrees with the certified reference to its error.
    const SimTK::Vec3 elliptic = book::exact::angularVelocity(o.scene, last.time);
    const SimTK::Vec3 certified(reference.y[0], reference.y[1], reference.y[2]);
    const double ellipticDigits = book::exact::spinDigits(o.scene, elliptic, {reference.y[0], reference.y[1], reference.y[2]});
    std::string source = "Euler's equations in " + reference.how;
    if (ellipticDigits >= std::min(digits.held, 12.0)) {
        source = "elliptic functions, certified by " + source;
    } else {
        char held[96];
        std::snprintf(held, sizeof held, "; the elliptic functions hold %.1f digits here", ellipticDigits);
        source += held;
    }
    std::printf("w(%g s) = (%.12g, %.12g, %.12g) rad/s\n", last.time, last.w_B[0], last.w_B[1], last.w_B[2]);
    const std::string exact = certifiedNumber(certified[0], reference.error) + ", " +
                              certifiedNumber(certified[1], reference.error) + ", " +
                              certifiedNumber(certified[2], reference.error);
    if (digits.held < 1) {
        // Not one digit of the reference is certain: the spin's fate hangs on less than the widest precision holds.
        std::printf("  exact   unknown: the reference's runs disagree by %.2g rad/s (%s), so 0.0 accurate digits "
                    "are claimed (%s, %d steps)\n",
                    reference.error, reference.how.c_str(), result.integrator.method.c_str(),
                    result.integrator.stepsTaken);
    } else {
        std::printf("  exact   (%s) rad/s (%s): %.1f accurate digits%s (%s, %d steps)\n", exact.c_str(),
                    source.c_str(), digits.digits,
                    digits.capped ? ", all the certified reference can confirm" : "", result.integrator.method.c_str(),
                    result.integrator.stepsTaken);
    }
    reportConditioning(o.scene);
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
    const book::exact::CertifiedSpin reference = book::exact::certifiedAngularVelocity(o.scene, o.program.run.finalTime);
    simlab::printTrade(std::cout, o.program.run, figure, [&](const simlab::RunSettings& run) {
        book::Model model;
        const auto result = simlab::run<Sample>(o.scene, model, run);
        if (result.samples.empty()) throw std::runtime_error("the simulation recorded no samples");
        const Sample& last = result.samples.back();
        const double digits = last.time == run.finalTime
                                  ? digitsAgainst(o.scene, reference, last.w_B).digits
                                  : digitsAgainst(o.scene, book::exact::certifiedAngularVelocity(o.scene, last.time),
                                                  last.w_B).digits;
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
        ->check(simlab::finite())
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
    if (!o.omega.empty()) asked.w_B0 = SimTK::Vec3(o.omega[0], o.omega[1], o.omega[2]);
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
