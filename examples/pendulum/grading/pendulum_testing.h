// What the pendulum's visible and hidden tests share: observing a student's swing and measuring it against the
// exact one (program/exact.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "pendulum/contract/Pendulum.h"
#include "pendulum/grading/observations.h"
#include "pendulum/program/exact.h"
#include "pendulum/program/period.h"
#include "pendulum/program/run_plot.h"
#include "simlab/digits.h"
#include "simlab/harness/testing.h"

namespace pendulum::testing {

namespace grading = simlab::grading;
using namespace simlab::testing;
using Run = simlab::RunResult<Sample>;

inline Run simulate(const Scene& scene, const simlab::RunSettings& settings = defaultRunSettings()) {
    return simlab::testing::simulate<Sample>(scene, settings);
}

inline simlab::RunSettings settingsFor(double finalTime, double dt, double accuracy = 1e-7) {
    return simlab::testing::settingsFor(defaultRunSettings(), finalTime, dt, accuracy);
}

inline Scene sceneWith(double releaseAngle_deg, double length_m = 1.0, double gravity_mps2 = 9.81,
                       double mass_kg = 1.0) {
    Scene s;
    s.releaseAngle_deg = releaseAngle_deg;
    s.length_m = length_m;
    s.gravity_mps2 = gravity_mps2;
    s.mass_kg = mass_kg;
    return s;
}

/// Digits of theta at the worst sample against the exact swing. theta passes zero twice a swing: its errors count
/// against the release angle, the size of the swing, never against theta itself.
inline double thetaDigits(const Scene& scene, const Run& run) {
    const double scale_rad = std::abs(exact::releaseAngle_rad(scene));
    double worst = simlab::kMaxDigits;
    for (const Sample& s : run.samples) {
        worst = std::min(worst, simlab::accuracyDigits(s.theta_rad, exact::at(scene, s.time).theta_rad, scale_rad));
    }
    return worst;
}

/// Digits of the period the samples show against T = 4 K(k) / w0; none with fewer than two turning points.
inline double periodDigits(const Scene& scene, const MeasuredPeriod& measured) {
    return std::isnan(measured.period_s) ? 0.0 : simlab::accuracyDigits(measured.period_s, exact::period_s(scene));
}

/// What was measured of the period, in words.
inline std::string describePeriod(const Scene& scene, const MeasuredPeriod& measured) {
    std::ostringstream text;
    text.precision(10);
    text << "released at " << scene.releaseAngle_deg << " degrees, L = " << scene.length_m << " m, g = "
         << scene.gravity_mps2 << " m/s^2: " << measured.turningPoints << " turning points, period "
         << measured.period_s << " s, exact " << exact::period_s(scene) << " s";
    return text.str();
}

/// Largest departure, relative to m g L (the size of the potential energy's swing), of the swing's energy from its
/// value at release: the energy the physics gives theta and theta' (m L^2 theta'^2 / 2 - m g L cos theta), and the
/// mechanical energy sampled.
inline double energyDrift(const Scene& scene, const Run& run) {
    const double expected_J = exact::mechanicalEnergy_J(scene);
    const double scale_J = scene.mass_kg * scene.gravity_mps2 * scene.length_m;
    double drift = 0;
    for (const Sample& s : run.samples) {
        const double ofAngle_J = exact::energyOf_J(scene, s.theta_rad, s.thetaDot_radps);
        const double worst = std::max(std::abs(ofAngle_J - expected_J), std::abs(s.mechanicalEnergy_J - expected_J));
        drift = std::isnan(worst) ? INFINITY : std::max(drift, worst / scale_J);
    }
    return drift;
}

}  // namespace pendulum::testing
