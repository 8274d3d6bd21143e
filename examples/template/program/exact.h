// A block on a spring, solved by hand.
//
// The spring pulls the block back towards its rest position with the force -k x, and nothing else acts along the
// rail (it is frictionless and horizontal, so gravity and the rail's push do no work):
//     m x'' = -k x.
// Released from rest at x0, the block oscillates about the rest position with omega = sqrt(k / m):
//     x(t) = x0 cos(omega t),      x'(t) = -x0 omega sin(omega t),      period T = 2 pi / omega,
// and its energy, kinetic plus the spring's, keeps its value at release: m x'^2 / 2 + k x^2 / 2 = k x0^2 / 2.
// With the lab's numbers (m = 2 kg, k = 50 N/m, x0 = 0.1 m): omega = 5 rad/s, T = 1.2566 s, E = 0.25 J.
//
// CHANGE: the exact solution of your scene, worked out by hand: whatever the tests measure the student's samples
// against. Keep it in the lab's namespace, as functions of the Scene.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "mylab/contract/MyLab.h"
#include "simlab/digits.h"

namespace mylab::exact {

/// omega = sqrt(k / m), rad/s.
inline double angularFrequency_radps(const Scene& scene) { return std::sqrt(scene.stiffness_Npm / scene.mass_kg); }

/// x(t) = x0 cos(omega t), m.
inline double position_m(const Scene& scene, double t) {
    return scene.releasePosition_m * std::cos(angularFrequency_radps(scene) * t);
}

/// x'(t) = -x0 omega sin(omega t), m/s.
inline double velocity_mps(const Scene& scene, double t) {
    const double omega = angularFrequency_radps(scene);
    return -scene.releasePosition_m * omega * std::sin(omega * t);
}

/// E = k x0^2 / 2, J: the energy of the release from rest, all of it in the spring.
inline double mechanicalEnergy_J(const Scene& scene) {
    return 0.5 * scene.stiffness_Npm * scene.releasePosition_m * scene.releasePosition_m;
}

/// E(x, x') for this scene: m x'^2 / 2 + k x^2 / 2, J.
inline double energyOf_J(const Scene& scene, double x_m, double xDot_mps) {
    return 0.5 * scene.mass_kg * xDot_mps * xDot_mps + 0.5 * scene.stiffness_Npm * x_m * x_m;
}

/// Digits of x at the worst of `samples` against x0 cos(omega t). x passes zero twice a period, where a relative
/// error means nothing: errors count against x0, the size of the oscillation.
inline double worstDigits(const Scene& scene, const std::vector<Sample>& samples) {
    const double scale_m = std::abs(scene.releasePosition_m);
    double worst = simlab::kMaxDigits;
    for (const Sample& s : samples) {
        worst = std::min(worst, simlab::accuracyDigits(s.x_m, position_m(scene, s.time), scale_m));
    }
    return worst;
}

}  // namespace mylab::exact
