// The `projectile` lab program (the course's side): runs the simulation written in ProjectileMotion.cpp, prints
// and saves its trajectory, then runs it again until the ball lands and reports the ground hit its event handler
// found, against t* = 2 v0 sin(theta) / g and x* = v0 cos(theta) t*.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>

#include "projectile/contract/ProjectileMotion.h"
#include "projectile/program/exact.h"
#include "projectile/program/landing.h"
#include "projectile/program/run_plot.h"
#include "simlab/reproducible_math.h"
#include "simlab/cli_checks.h"
#include "simlab/digits.h"
#include "simlab/messages.h"
#include "simlab/plot.h"
#include "simlab/results_table.h"
#include "simlab/program.h"

namespace {

using projectile::Sample;
using projectile::Scene;

struct Options {
    Scene scene;
    simlab::ProgramOptions program;
};

std::vector<double> resultsRow(const Scene& scene, const Sample& s) {
    return {s.time, s.x, s.y, s.xVelocity, s.yVelocity, s.mechanicalEnergy, s.y - projectile::exact::y(scene, s.time)};
}

struct HitDigits {
    double time = 0, range = 0;
    double rangeScale = 0;  ///< m: what the range's digits are relative to where x* is near zero (0: x* itself)
};

// Digits of the hit's time and range (projectile::exact::hitDigits's, the study's figure): the range's relative to x*
// itself, unless the launch is so near vertical that x* is under a tenth of v0 t*: then relative to v0 t*, the
// distance the ball travels, which the report states beside them.
HitDigits hitDigits(const Scene& scene, const projectile::GroundHit& hit) {
    if (!hit.found) return {};
    return {projectile::exact::hitTimeDigits(scene, hit.time), projectile::exact::hitRangeDigits(scene, hit.x),
            projectile::exact::rangeScale(scene)};
}

// A size for a line, worked out in long double (to 1e4932): "1.97e+298", and past a double's range too, "1.15e+600".
std::string sizeText(long double value) {
    char text[48];
    std::snprintf(text, sizeof text, "%.3Lg", value);
    return text;
}

// Why the event machinery cannot follow this flight, or "". Simbody tells event times apart to about its
// SignificantReal, 1.8e-14 s, near t = 0: a flight of t* s is timed to about log10(t* / 1.8e-14) digits (measured:
// 5.1 at 1.2e-9 s, 2.1 at 1.2e-12 s, and below that a hit it may miss), so under 1e-9 s it is refused. A flight of
// more than 1e150 s trips an assertion in its interpolation, which aborts the program (measured: 5e151 s runs,
// 5e156 s aborts).
std::string flightProblem(const Scene& scene) {
    const double tStar = projectile::exact::flightTime(scene);
    char why[240];
    if (!(tStar <= 1e150)) {
        // In long double, which holds the quotient even where a double overflows.
        const long double flight = 2.0L * scene.launchSpeed * std::sin(static_cast<long double>(
                                       projectile::exact::launchAngle(scene))) / scene.gravity;
        std::snprintf(why, sizeof why,
                      "the flight lasts %s s (2 v0 sin(theta)/g), longer than Simbody's event handling can follow "
                      "(1e+150 s): give a larger --gravity or a smaller --speed", sizeText(flight).c_str());
        return why;
    }
    if (!(tStar >= 1e-9)) {
        std::snprintf(why, sizeof why,
                      "the flight lasts %.3g s (2 v0 sin(theta)/g): Simbody times events to about 1.8e-14 s, so a "
                      "flight under 1e-09 s gets fewer than 5 digits: give a larger --speed or a smaller --gravity",
                      tStar);
        return why;
    }
    return "";
}

// Why the state's own size is past what a run can hold, or "": Simbody's integrators square the state's values
// (its interpolation among them), and a double's square overflows past 1.3e154. So no coordinate, speed or
// acceleration the runs reach - to the table's final time and to the landing run's end, past 2 t* - may pass
// 1e153 (measured: a flight of 1.9e151 m runs to 15 digits; a speed of 1e80 m/s, flying 1e159 m, and 1e140 m/s
// under 1e-5 m/s^2 end in an assertion of Simbody's interpolation).
std::string extentProblem(const Scene& scene, const simlab::RunSettings& run) {
    // In long double (to 1e4932), so that the check itself cannot overflow where the values it checks would.
    using Real = long double;
    const Real theta = projectile::exact::launchAngle(scene), v0 = scene.launchSpeed, g = scene.gravity;
    const Real vx = v0 * std::cos(theta), vy0 = v0 * std::sin(theta);
    const Real tEnd = std::max<Real>(run.finalTime, 2.1L * 2 * vy0 / g + 1);
    const Real extent = std::max({std::abs(vx * tEnd), vy0 * vy0 / (2 * g), std::abs(vy0 * tEnd - g * tEnd * tEnd / 2),
                                  v0, g * tEnd, std::abs(vy0 - g * tEnd)});
    if (extent <= 1e153L) return "";
    char why[300];
    std::snprintf(why, sizeof why,
                  "the ball would reach %s (m or m/s) by t = %s s, past 1e+153, whose square Simbody's "
                  "integrators form and a double cannot hold: give a smaller --speed or --final-time, or a larger "
                  "--gravity", sizeText(extent).c_str(), sizeText(tEnd).c_str());
    return why;
}

// The ground hit: the one the run above recorded where its event handler ended it there, so that the table and the
// hit are one run (with its steps, as the study measures a setting); else, where the table ends before the ball
// lands, a run on to the ground (simulateLanding).
projectile::GroundHit reportLanding(const Options& o, const projectile::GroundHit& tableHit, double tableEnd,
                                    const simlab::IntegratorStats& tableStats) {
    const double tStar = projectile::exact::flightTime(o.scene), xStar = projectile::exact::range(o.scene);
    projectile::Landing landing;
    std::string which = "the run above";
    if (tableHit.found) {
        landing = {tableHit, tableEnd, tableStats};
    } else {
        // The table ends before the ball lands, or its run went past the landing without its event: a flight shorter
        // than its first sample interval leaves the launch, at y = 0, for below the ground in one step, where the
        // event never sees the ball above it. A run on to the ground samples the flight finely enough to see it.
        const bool passed = tableEnd > tStar + o.scene.groundHitWindow;
        which = passed ? "a run on to the ground: the run above passed the landing without its event"
                       : "a run on to the ground, past the table's end";
        simlab::SolverChatter chatter(o.program.run.integrator == "CPodes");
        try {
            simlab::Progress progress("projectile", tStar, "the run to the ground hit");
            landing = projectile::simulateLanding(o.scene, o.program.run,
                                                  [&](const Sample& s) { progress.at(s.time); });
        } catch (const std::invalid_argument& e) {
            std::printf("No ground hit: the table %s, and a run on to the ground cannot see the landing: %s\n",
                        passed ? "went past the landing without its event" : "ends before the ball lands", e.what());
            return {};
        }
        if (const std::string said = chatter.finish(); !said.empty()) simlab::tellUser("projectile: " + said);
        if (!landing.hit.found) {
            std::printf("No ground hit: a run on to the ground went to t = %g s and nothing recorded the ball coming "
                        "back to y = 0 (exact: t* = %.10g s). Does buildModel add an event handler that records it?\n",
                        landing.endTime, tStar);
            return {};
        }
    }
    const HitDigits digits = hitDigits(o.scene, landing.hit);
    std::printf("Ground hit (event window %g s): t = %.12g s, x = %.12g m (%s, %d steps: %s)\n",
                o.scene.groundHitWindow, landing.hit.time, landing.hit.x, landing.integrator.method.c_str(),
                landing.integrator.stepsTaken, which.c_str());
    std::printf("  exact t* = 2 v0 sin(theta)/g = %.12g s: %.1f accurate digits\n", tStar, digits.time);
    // Conditioning: x* = v0^2 sin(2 theta) / g magnifies a relative change of theta by |2 theta cot(2 theta)|, so near
    // 90 degrees the angle's own rounding (half a unit in its last place) leaves x* fewer digits than a double holds,
    // whatever the integrator. x* is printed to the digits it keeps.
    const double theta = projectile::exact::launchAngle(o.scene);
    const double magnified = std::abs(2 * theta * std::cos(2 * theta) / std::sin(2 * theta));
    const double held = std::min(15.9, 15.9 - std::log10(std::max(1.0, magnified)));
    const int shown = std::clamp(static_cast<int>(std::floor(held)), 1, 12);
    if (digits.rangeScale > 0) {
        std::printf("  exact x* = v0 cos(theta) t*  = %.*g m: %.1f accurate digits of v0 t* = %.6g m (x* is near 0)\n",
                    shown, xStar, digits.range, digits.rangeScale);
    } else {
        std::printf("  exact x* = v0 cos(theta) t*  = %.*g m: %.1f accurate digits\n", shown, xStar, digits.range);
    }
    if (held < 12) {
        std::printf("  Conditioning: at %.10g degrees, x* = v0^2 sin(2 theta)/g magnifies the launch angle's rounding "
                    "%.2g times, so x* itself holds only %.1f significant digits, whatever the integrator\n",
                    o.scene.launchAngleDegrees, magnified, held);
    }
    return landing.hit;
}

const std::vector<std::string> kColumns = {"time",      "x", "y", "xVelocity", "yVelocity", "mechanicalEnergy",
                                           "yDifferenceFromExact"};

// --from: an earlier run's results file drawn over the exact parabola of this scene, which must be the one it ran
// (the file does not hold the ground hit, which is not marked).
int drawFrom(const Options& o) {
    std::vector<Sample> samples;
    for (const std::vector<double>& r : simlab::readResults(o.program.from, kColumns)) {
        samples.push_back({r[0], r[1], r[2], r[3], r[4], r[5]});
    }
    const Sample& first = samples.front();
    const double speed = std::hypot(first.xVelocity, first.yVelocity);
    const double angle = std::atan2(first.yVelocity, first.xVelocity) * 180 / M_PI;
    if (std::abs(speed - o.scene.launchSpeed) > 1e-9 * o.scene.launchSpeed ||
        std::abs(angle - o.scene.launchAngleDegrees) > 1e-7) {
        throw std::runtime_error("'" + o.program.from + "' starts at " + simlab::shortNumber(speed) + " m/s, " +
                                 simlab::shortNumber(angle) + " degrees, this scene at " +
                                 simlab::shortNumber(o.scene.launchSpeed) + " m/s, " +
                                 simlab::shortNumber(o.scene.launchAngleDegrees) +
                                 " degrees: give the options of the run that wrote it (--speed, --angle, --gravity)");
    }
    simlab::drawPlot(projectile::runPlot(o.scene, "from " + o.program.from, samples, projectile::GroundHit{}), o.program.plot);
    std::printf("Plot drawn in %s\n", o.program.plot.c_str());
    return 0;
}

int runOnce(const Options& o) {
    const simlab::RunSettings& run = o.program.run;
    char banner[320];
    std::snprintf(banner, sizeof banner,
                  "Projectile: a %g kg baseball at %g m/s, %.12g degrees, g = %g m/s^2; %s",
                  o.scene.mass, o.scene.launchSpeed, o.scene.launchAngleDegrees, o.scene.gravity,
                  simlab::describeProgramRun(run, /*events=*/true).c_str());
    simlab::Tabulation<Sample, projectile::Model> tabulation;
    tabulation.columns = kColumns;
    tabulation.row = [&](const Sample& s) { return resultsRow(o.scene, s); };
    tabulation.banner = banner;
    // A baseball's radius from its radius of gyration (a solid sphere's is sqrt(2/5) of it), a label readable from
    // as far back as the whole arc needs, and the trail of the flight.
    const double radius = o.scene.radiusOfGyration / std::sqrt(0.4);
    const double far = std::min(projectile::exact::range(o.scene), projectile::exact::x(o.scene, run.finalTime));
    const double span = std::max({far, projectile::exact::maxHeight(o.scene), 1.0});
    tabulation.bodyRadius = radius;
    tabulation.scenery.low = {0, 0, -1};
    tabulation.scenery.high = {far, projectile::exact::maxHeight(o.scene), 1};
    tabulation.scenery.trails = true;
    tabulation.decorate = [radius, span](projectile::Model& m) {
        using namespace SimTK;
        simlab::decorateUnlessDrawn(m.ball, {DecorativeSphere(radius).setColor(Vec3(0.95, 0.95, 0.9)),
                                             DecorativeText("ball").setScale(span / 14).setColor(Vec3(0.1)).setTransform(
                                                 Vec3(span / 80, span / 80, 0))});
    };
    tabulation.program = "projectile";
    tabulation.expectedEnd = projectile::exact::flightTime(o.scene);  // the ground-hit event ends the run there
    tabulation.conserved = "mechanicalEnergy";
    tabulation.conservedScale = [&](const projectile::Sample& s) {
        return 0.5 * o.scene.mass * (s.xVelocity * s.xVelocity + s.yVelocity * s.yVelocity) +
               o.scene.mass * o.scene.gravity * std::abs(s.y);
    };
    projectile::Model model;
    const auto result = simlab::runTabulated(o.scene, model, o.program, tabulation);

    const Sample& last = result.samples.back();
    if (last.time < run.finalTime * (1 - 1e-12)) {
        std::printf("The table ends at t = %.12g s, before the final time %g s: the simulation ended there (%s).\n",
                    last.time, run.finalTime,
                    model.groundHit.found ? "the ground-hit event ended it as the ball landed"
                                          : "and nothing recorded a ground hit");
    }
    // Positions are measured against the distance the ball has flown, v0 t, so that a coordinate whose exact
    // value is (near) zero, y at the ground or x of a vertical launch, still gets its digits.
    const double scale = o.scene.launchSpeed * last.time;
    const double yExact = projectile::exact::y(o.scene, last.time), xExact = projectile::exact::x(o.scene, last.time);
    std::printf("y(%g s) = %.15g m; exact %.15g m: %.1f accurate digits (of v0 t = %.6g m)\n", last.time, last.y,
                yExact, simlab::accuracyDigits(last.y, yExact, scale), scale);
    std::printf("x(%g s) = %.15g m; exact %.15g m: %.1f accurate digits (of v0 t = %.6g m)\n", last.time, last.x,
                xExact, simlab::accuracyDigits(last.x, xExact, scale), scale);
    const projectile::GroundHit hit = reportLanding(o, model.groundHit, last.time, result.integrator);
    if (!o.program.plot.empty()) {
        simlab::drawPlot(projectile::runPlot(o.scene, simlab::describeRun(run, /*events=*/true), result.samples, hit),
                         o.program.plot);
        std::printf("Plot drawn in %s\n", o.program.plot.c_str());
    }
    return 0;
}

// The ground hit's digits against the integrator's accuracy and the event's localization window.
int runTrade(const Options& o) {
    std::printf("Digits of the ground hit against cost, %s, dt %g s, median of %d runs\n",
                o.program.run.integrator.c_str(), o.program.run.dt, o.program.repeats);
    std::printf("%10s %10s %10s %10s %8s %12s %10s\n", "accuracy", "window s", "digits t*", "digits x*", "steps",
                "evaluations", "median ms");
    simlab::SolverChatter chatter(o.program.run.integrator == "CPodes");  // the rows say how each run went
    for (const double accuracy : {1e-3, 1e-5, 1e-7, 1e-9, 1e-11}) {
        for (const double window : {1e-1, 1e-3, 1e-6, 1e-9}) {
            Scene scene = o.scene;
            scene.groundHitWindow = window;
            simlab::RunSettings run = o.program.run;
            run.accuracy = accuracy;
            std::vector<double> ms;
            projectile::Landing landing;
            for (int r = 0; r < o.program.repeats; ++r) {
                const auto start = std::chrono::steady_clock::now();
                landing = projectile::simulateLanding(scene, run);
                ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
            }
            std::sort(ms.begin(), ms.end());
            const HitDigits digits = hitDigits(scene, landing.hit);
            std::printf("%10g %10g %10.2f %10.2f %8d %12d %10.1f\n", accuracy, window, digits.time, digits.range,
                        landing.integrator.stepsTaken, landing.integrator.realizations, ms[ms.size() / 2]);
        }
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    simlab::useReproducibleMath(argv);
    Options o;
    o.program.run = projectile::defaultRunSettings();
    o.program.output = "ProjectileMotionResults.txt";

    CLI::App app{"Projectile motion: a baseball launched from the ground, its trajectory, and the ground hit found by "
                 "Simbody's event handling.",
                 "projectile"};
    simlab::addProgramOptions(app, o.program);
    app.add_option("--angle", o.scene.launchAngleDegrees, "launch angle above the horizontal, degrees, in (0, 90]")
        ->check(CLI::Validator(
            [](std::string& text) {
                double angle = 0;
                if (!CLI::detail::lexical_cast(text, angle) || !(angle > 0 && angle <= 90)) {
                    return "must be in (0, 90] degrees, got " + text;
                }
                return std::string();
            },
            "DEGREES"))
        ->capture_default_str();
    app.add_option("--speed", o.scene.launchSpeed, "launch speed, m/s")->check(simlab::positive())->capture_default_str();
    app.add_option("--gravity", o.scene.gravity, "m/s^2, pulling along -y")->check(simlab::positive())->capture_default_str();
    app.add_option("--mass", o.scene.mass, "kg, mass of the ball")->check(simlab::positive())->capture_default_str();
    app.add_option("--event-window", o.scene.groundHitWindow,
                   "s: the time window Simbody must localize the ground hit to")
        ->check(simlab::positive())
        ->capture_default_str();
    app.get_option("--trade")->description("instead of one run, print the ground hit's digits against the "
                                           "accuracy and the event window");
    if (const int status = simlab::parseCommandLine(app, argc, argv); status >= 0) return status;

    if (const int status = simlab::checkRunSettings("projectile", o.program.run); status >= 0) return status;
    if (const std::string problem = flightProblem(o.scene); !problem.empty() && o.program.from.empty()) {
        std::cerr << "projectile: error: " << problem << '\n';
        return 2;
    }
    if (const std::string problem = extentProblem(o.scene, o.program.run); !problem.empty() && o.program.from.empty()) {
        std::cerr << "projectile: error: " << problem << '\n';
        return 2;
    }
    return simlab::runGuarded("projectile", [&] {
        if (!o.program.from.empty()) return drawFrom(o);
        return o.program.trade ? runTrade(o) : runOnce(o);
    });
}
