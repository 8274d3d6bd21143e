// The torque-free book, solved exactly, without Simbody.
//
// About its center, with principal moments I1, I2, I3 along body axes 1, 2, 3, Euler's equations with no torque
//     I1 w1' = (I2 - I3) w2 w3,    I2 w2' = (I3 - I1) w3 w1,    I3 w3' = (I1 - I2) w1 w2
// keep two things constant: twice the kinetic energy, 2K = sum I_i w_i^2, and the squared angular momentum,
// H^2 = sum I_i^2 w_i^2. Their solution (Landau & Lifshitz, Mechanics, section 37) is in Jacobi's elliptic
// functions. Number the axes so that the one whose moment is nearest D = H^2 / 2K from the far side of the middle
// moment comes last: if D lies above the middle moment, 1, 2, 3 run from the smallest moment to the largest;
// below it, from the largest to the smallest (and one axis is flipped to keep the frame right-handed). Then
//     w1 = A1 cn(u, k),   w2 = s2 A2 sn(u, k),   w3 = s3 A3 dn(u, k),   u = u0 + lambda t,
//     A1^2 = (2K I3 - H^2) / (I1 (I3 - I1)),   A2^2 = (2K I3 - H^2) / (I2 (I3 - I2)),
//     A3^2 = (H^2 - 2K I1) / (I3 (I3 - I1)),   lambda^2 = (I3 - I2)(H^2 - 2K I1) / (I1 I2 I3),
//     k^2 = (I2 - I1)(2K I3 - H^2) / ((I3 - I2)(H^2 - 2K I1)),
// where s3 is the sign of w3 (dn never changes sign, so neither does w3), s2 = s3 sign(I3 - I2) as Euler's
// equations require, and u0 places the initial state: sn(u0) = w2(0) / (s2 A2), cn(u0) = w1(0) / A1.
//
// With two moments equal (an axisymmetric body, I1 = I2 = Ip about the symmetry axis s of moment Is) the elliptic
// functions degenerate: w_s stays constant and the rest of w turns about s at the constant rate
// Omega = (Is - Ip) w_s / Ip, taken positive from axis s+1 toward axis s+2 (indices cyclic). With all three
// equal, w stays as it is.
//
// Spin about the intermediate axis b of a body with moments Ia < Ib < Ic is unstable: linearized, a small
// perturbation grows like exp(lambda t) with lambda = w0 sqrt((Ib - Ia)(Ic - Ib) / (Ia Ic)).
#pragma once

#include <algorithm>
#include <array>
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <stdexcept>
#include <string>

#include "book/contract/BookSpin.h"
#include "simlab/digits.h"
#include "simlab/ode_reference.h"

namespace book::exact {

/// The central principal moments of inertia of a uniform brick of the scene's mass and dimensions, about the
/// book's x, y and z: m (Ly^2 + Lz^2) / 12, m (Lx^2 + Lz^2) / 12, m (Lx^2 + Ly^2) / 12.
/// |v| without squaring its components (std::hypot): a spin of 1e-160 rad/s, or a kinetic energy of 1e-204 J, has
/// a magnitude, where v.norm() would underflow to zero (and a ratio of two to NaN).
inline double magnitude(const SimTK::Vec3& v) { return std::hypot(v[0], v[1], v[2]); }

inline SimTK::Vec3 principalMoments(const Scene& scene) {
    const SimTK::Vec3& L = scene.dimensions;
    return scene.mass / 12 * SimTK::Vec3(L[1] * L[1] + L[2] * L[2], L[0] * L[0] + L[2] * L[2], L[0] * L[0] + L[1] * L[1]);
}

/// The book's axes (0 = x, 1 = y, 2 = z) in order of increasing moment: minimum, intermediate, maximum.
inline std::array<int, 3> axesByMoment(const Scene& scene) {
    const SimTK::Vec3 I = principalMoments(scene);
    std::array<int, 3> axes = {0, 1, 2};
    std::sort(axes.begin(), axes.end(), [&](int a, int b) { return I[a] < I[b]; });
    return axes;
}

/// A spin of `rate` rad/s about the "min", "intermediate" or "max" axis, with `wobble` rad/s about the other two:
/// for the lab's book, (0.2, 7, 0.2), (7, 0.2, 0.2) and (0.2, 0.2, 7).
inline SimTK::Vec3 spin(const Scene& scene, const std::string& which, double rate = 7.0, double wobble = 0.2) {
    const std::array<int, 3> axes = axesByMoment(scene);
    const int axis = which == "min" ? axes[0] : which == "intermediate" ? axes[1] : which == "max" ? axes[2] : -1;
    if (axis < 0) throw std::invalid_argument("a spin is min, intermediate or max, not '" + which + "'");
    SimTK::Vec3 w(wobble);
    w[axis] = rate;
    return w;
}

inline double kineticEnergy(const Scene& scene) {
    const SimTK::Vec3 I = principalMoments(scene);
    double K = 0;
    for (int i = 0; i < 3; ++i) K += 0.5 * I[i] * scene.w_B0[i] * scene.w_B0[i];
    return K;
}

inline double angularMomentum(const Scene& scene) {
    const SimTK::Vec3 I = principalMoments(scene);
    return std::sqrt(SimTK::square(I[0] * scene.w_B0[0]) + SimTK::square(I[1] * scene.w_B0[1]) +
                     SimTK::square(I[2] * scene.w_B0[2]));
}

/// w_B(t): the book's angular velocity, expressed in its own axes, t seconds after the spin w_B0.
inline SimTK::Vec3 angularVelocity(const Scene& scene, double t) {
    const SimTK::Vec3 I = principalMoments(scene);
    const SimTK::Vec3& w0 = scene.w_B0;
    double twoK = 0, H2 = 0;
    for (int i = 0; i < 3; ++i) {
        twoK += I[i] * w0[i] * w0[i];
        H2 += I[i] * I[i] * w0[i] * w0[i];
    }
    // Moments closer than this (relative to the largest) count as equal. The elliptic formula fails only where a
    // difference of moments vanishes (its amplitudes become 0/0): against an integration of Euler's equations in
    // long double it keeps 13 digits or more for differences down to 1e-15. The closed form for equal moments is
    // off by about the difference times the turn Omega t, so 1e-13 keeps it to 12 digits for a hundred radians.
    const double kEqualMoments = 1e-13;
    const std::array<int, 3> order = axesByMoment(scene);
    const double Imax = I[order[2]];
    if (I[order[2]] - I[order[0]] <= kEqualMoments * Imax) return w0;  // a sphere's w never changes
    const bool lowPair = I[order[1]] - I[order[0]] <= kEqualMoments * Imax;
    const bool highPair = I[order[2]] - I[order[1]] <= kEqualMoments * Imax;
    if (lowPair || highPair) {
        const int s = lowPair ? order[2] : order[0];  // the symmetry axis: the moment that differs
        const int a = (s + 1) % 3, b = (s + 2) % 3;
        const double Ip = 0.5 * (I[a] + I[b]);
        const double Omega = (I[s] - Ip) / Ip * w0[s];
        const double c = std::cos(Omega * t), sn = std::sin(Omega * t);
        SimTK::Vec3 w;
        w[s] = w0[s];
        w[a] = w0[a] * c - w0[b] * sn;
        w[b] = w0[a] * sn + w0[b] * c;
        return w;
    }
    // A spin about one principal axis (or no spin) is an equilibrium: it stays as it is.
    int zero = 0;
    for (int i = 0; i < 3; ++i) zero += w0[i] == 0;
    if (zero >= 2) return w0;
    // Number the axes (see above); an odd reordering flips the last axis to keep the frame right-handed.
    std::array<int, 3> axis = axesByMoment(scene);
    if (H2 / twoK < I[axis[1]]) std::swap(axis[0], axis[2]);
    int inversions = 0;
    for (int i = 0; i < 3; ++i) {
        for (int j = i + 1; j < 3; ++j) inversions += axis[i] > axis[j];
    }
    const std::array<double, 3> flip = {1.0, 1.0, inversions % 2 ? -1.0 : 1.0};
    const double I1 = I[axis[0]], I2 = I[axis[1]], I3 = I[axis[2]];
    std::array<double, 3> w;
    for (int i = 0; i < 3; ++i) w[i] = flip[i] * w0[axis[i]];

    const double A1 = std::sqrt(std::max(0.0, (twoK * I3 - H2) / (I1 * (I3 - I1))));
    const double A2 = std::sqrt(std::max(0.0, (twoK * I3 - H2) / (I2 * (I3 - I2))));
    const double A3 = std::sqrt(std::max(0.0, (H2 - twoK * I1) / (I3 * (I3 - I1))));
    const double lambda = std::sqrt((I3 - I2) * (H2 - twoK * I1) / (I1 * I2 * I3));
    const double k = std::min(1.0, std::sqrt(std::max(0.0, (I2 - I1) * (twoK * I3 - H2) / ((I3 - I2) * (H2 - twoK * I1)))));
    const double s3 = w[2] >= 0 ? 1.0 : -1.0;
    const double s2 = (I3 > I2 ? 1.0 : -1.0) * s3;
    const double u0 = boost::math::ellint_1(k, std::atan2(w[1] / (s2 * A2), w[0] / A1));
    double cn = 0, dn = 0;
    const double sn = boost::math::jacobi_elliptic(k, u0 + lambda * t, &cn, &dn);

    const std::array<double, 3> wt = {A1 * cn, s2 * A2 * sn, s3 * A3 * dn};
    SimTK::Vec3 result;
    for (int i = 0; i < 3; ++i) result[axis[i]] = flip[i] * wt[i];
    return result;
}

/// Accuracy digits of a simulated w_B at time t, as a vector: -log10(|w - w_exact| / |w_exact|).
inline double angularVelocityDigits(const Scene& scene, double t, const SimTK::Vec3& w_B) {
    const SimTK::Vec3 exact = angularVelocity(scene, t);
    if (!w_B.isFinite()) return 0;
    return simlab::accuracyDigits(magnitude(w_B - exact), 0.0, magnitude(exact));
}

/// Euler's torque-free equations, I1 w1' = (I2 - I3) w2 w3 and cyclically, for w_B in the precision of W's values
/// (long double for the references that check double-precision runs).
template <class W>
inline void eulerEquations(const SimTK::Vec3& moments, const W& w, W& dwdt) {
    using Real = typename W::value_type;
    const Real I[3] = {moments[0], moments[1], moments[2]};
    dwdt[0] = (I[1] - I[2]) * w[1] * w[2] / I[0];
    dwdt[1] = (I[2] - I[0]) * w[2] * w[0] / I[1];
    dwdt[2] = (I[0] - I[1]) * w[0] * w[1] / I[2];
}

/// The linear growth rate of a small perturbation of a spin of `rate` rad/s about the intermediate axis.
inline double linearGrowthRate(const Scene& scene, double rate) {
    const SimTK::Vec3 I = principalMoments(scene);
    const std::array<int, 3> axes = axesByMoment(scene);
    const double Ia = I[axes[0]], Ib = I[axes[1]], Ic = I[axes[2]];
    return rate * std::sqrt((Ib - Ia) * (Ic - Ib) / (Ia * Ic));
}

/// Euler's equations for w_B in long double, followed step by step as later times are asked for (the work-precision
/// study's reference, and the trade question's).
inline simlab::OdeReference<3> eulerReference(const Scene& scene, long double tolerance = 1e-18L) {
    const SimTK::Vec3 I = principalMoments(scene);
    auto f = [I](const std::array<long double, 3>& w, std::array<long double, 3>& dwdt) { eulerEquations(I, w, dwdt); };
    return simlab::OdeReference<3>(f, {scene.w_B0[0], scene.w_B0[1], scene.w_B0[2]}, tolerance);
}

/// Digits of a simulated w_B against the reference's `w`, the worst component. Each passes through zero as the book
/// tumbles: all count against the spin's size, |w_B(0)|.
inline double spinDigits(const Scene& scene, const SimTK::Vec3& w_B, const std::array<long double, 3>& w) {
    const double scale = magnitude(scene.w_B0);
    double worst = simlab::kMaxDigits;
    for (int i = 0; i < 3; ++i) {
        worst = std::min(worst, simlab::accuracyDigits(w_B[i], static_cast<double>(w[static_cast<std::size_t>(i)]), scale));
    }
    return worst;
}

}  // namespace book::exact
