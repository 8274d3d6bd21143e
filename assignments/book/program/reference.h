// The book's reference for a run's last sample: Euler's equations integrated without Simbody, certified by a second
// precision (simlab/precision_ladder.h). The elliptic solution in exact.h is fast and right to 13 digits almost
// everywhere, but near the separatrix (a spin within a hair of the intermediate axis) neither it nor an integration in
// long double can tell on which side the book will tumble: a spin of (7, 1e-12, 1e-12) rad/s lies 6.6e-27 (relative)
// from it, far below long double's 1e-19. The ladder then goes on to 113-bit and 50-digit floats.
#pragma once

#include <array>
#include <cmath>

#include "book/contract/BookSpin.h"
#include "book/program/exact.h"
#include "simlab/precision_ladder.h"

namespace book::exact {

/// w_B(t) with an upper estimate of its error (rad/s, the worst component), and how it was made.
using CertifiedSpin = simlab::precision::Certified<3>;

/// The digits asked of the reference: 13 against |w_B(0)|, more than a double-precision run can keep.
constexpr double kReferenceDigits = 13;

/// w_B(t), certified to kReferenceDigits against |w_B(0)| if the ladder can (`confirmed`), with its error either way.
/// With `longDoubleOnly`, the first rung alone: the error of eulerReference, which the study and the grader follow.
inline CertifiedSpin certifiedAngularVelocity(const Scene& scene, double t, bool longDoubleOnly = false) {
    const SimTK::Vec3 I = principalMoments(scene);
    auto euler = [I](const auto& w, auto& dwdt) { eulerEquations(I, w, dwdt); };
    double rate = 0;
    for (int i = 0; i < 3; ++i) rate = std::max(rate, std::abs(scene.w_B0[i]));
    const double firstStep = rate > 0 ? 1e-3 / rate : 1e-3;
    const std::array<double, 3> w0 = {scene.w_B0[0], scene.w_B0[1], scene.w_B0[2]};
    if (longDoubleOnly) return simlab::precision::certifyLongDouble<3>(euler, w0, t, firstStep);
    return simlab::precision::certify<3>(euler, w0, t, magnitude(scene.w_B0) * std::pow(10.0, -kReferenceDigits),
                                         firstStep);
}

}  // namespace book::exact
