// Newton's apple, solved by hand.
//
// Newton's second law along Ground's y for an apple of mass m in uniform gravity g (no other forces):
//     -m g = m y''   =>   y'' = -g.
// Integrating twice from rest at height h:
//     y'(t) = -g t,    y(t) = h - g t^2 / 2.
// Kinetic plus potential energy (zero at y = 0) keeps its initial value: E = m g h.
// With the lab's numbers (h = 10 m, g = 9.8 m/s^2): y(4) = 10 - 4.9 * 16 = -68.4 m.
#pragma once

#include <algorithm>
#include <cmath>

#include "apple/contract/NewtonsApple.h"
#include "simlab/digits.h"

namespace apple::exact {

inline double yLocation(const Scene& scene, double t) { return scene.dropHeight - 0.5 * scene.gravity * t * t; }

inline double yVelocity(const Scene& scene, double t) { return -scene.gravity * t; }

inline double mechanicalEnergy(const Scene& scene) { return scene.mass * scene.gravity * scene.dropHeight; }

/// m: what the digits of y at time `t` are relative to. y itself, unless it is under a tenth of the height the fall
/// spans by then (the apple passes y = 0): then that height, so that a y near zero is never judged by its own size.
/// 0 stands for y itself.
inline double yScale(const Scene& scene, double t) {
    const double span = std::max(std::abs(scene.dropHeight), std::abs(yLocation(scene, t)));
    return std::abs(yLocation(scene, t)) < 0.1 * span ? span : 0.0;
}

/// Digits of y at the end of a run, the figure the lab program reports and the study's final digits: against the
/// exact y, on yScale's scale.
inline double finalDigits(const Scene& scene, const Sample& s) {
    return simlab::accuracyDigits(s.yLocation, yLocation(scene, s.time), yScale(scene, s.time));
}

/// Digits of a sample against the exact fall, the worse of y and vy. y passes zero as the apple falls past
/// Ground's origin: positions count against the largest height the fall spans by `finalTime`, speeds against g T.
inline double sampleDigits(const Scene& scene, const Sample& s, double finalTime) {
    const double g = scene.gravity, T = finalTime;
    const double yScale = std::max(std::abs(scene.dropHeight), 0.5 * g * T * T);
    return std::min(simlab::accuracyDigits(s.yLocation, yLocation(scene, s.time), yScale),
                    simlab::accuracyDigits(s.yVelocity, yVelocity(scene, s.time), g * T));
}

}  // namespace apple::exact
