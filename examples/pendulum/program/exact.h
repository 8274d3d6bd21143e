// A pendulum's swing, solved by hand.
//
// The bob (mass m, on a massless rod of length L) turns about the pivot; its angular momentum about the pivot,
// m L^2 theta', changes by gravity's torque, -m g L sin theta:
//     theta'' = -(g / L) sin theta.
// Its energy, kinetic plus potential (zero at the pivot's height), keeps its value at release from rest:
//     E = m L^2 theta'^2 / 2 - m g L cos theta = -m g L cos theta0.
// From rest at theta0 the solution is an elliptic function. With k = sin(theta0 / 2), K = K(k) the complete
// elliptic integral of the first kind, and w0 = sqrt(g / L):
//     sin(theta(t) / 2) = k sn(K - w0 t, k),      theta'(t) = -2 k w0 cn(K - w0 t, k),
// and the period (there and back) is T = 4 K / w0. It grows without bound as theta0 nears 180 degrees, like
// (4 / w0) ln(4 / cos(theta0 / 2)); for small swings it tends to 2 pi sqrt(L / g). A release to the other side
// (theta0 < 0) is the mirror image, theta(t; -theta0) = -theta(t; theta0): the modulus is |k|, and the sign of
// theta0 multiplies theta and theta'.
// With the lab's numbers (L = 1 m, g = 9.81 m/s^2, theta0 = 150 degrees): T = 3.5351 s.
#pragma once

#include <algorithm>
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <cmath>

#include "pendulum/contract/Pendulum.h"

namespace pendulum::exact {

inline double releaseAngle_rad(const Scene& scene) { return scene.releaseAngle_deg * SimTK::Pi / 180; }

/// w0 = sqrt(g / L), rad/s: the small-swing angular frequency.
inline double naturalFrequency_radps(const Scene& scene) { return std::sqrt(scene.gravity_mps2 / scene.length_m); }

/// |k| = |sin(theta0 / 2)|, the elliptic modulus of the swing (the same for a release to either side).
inline double modulus(const Scene& scene) { return std::abs(std::sin(releaseAngle_rad(scene) / 2)); }

/// T = 4 K(k) / w0, s.
inline double period_s(const Scene& scene) {
    return 4 * boost::math::ellint_1(modulus(scene)) / naturalFrequency_radps(scene);
}

/// theta and theta' at time t of the swing released from rest at theta0 at t = 0.
struct Angle {
    double theta_rad = 0, thetaDot_radps = 0;
};

inline Angle at(const Scene& scene, double t) {
    const double k = modulus(scene), w0 = naturalFrequency_radps(scene);
    if (k == 0) return {};  // hanging straight down: it stays there
    const double side = releaseAngle_rad(scene) < 0 ? -1.0 : 1.0;  // the mirror image of the release to +|theta0|
    double cn = 0, dn = 0;
    const double sn = boost::math::jacobi_elliptic(k, boost::math::ellint_1(k) - w0 * t, &cn, &dn);
    return {side * 2 * std::asin(std::clamp(k * sn, -1.0, 1.0)), -side * 2 * k * w0 * cn};
}

/// E = -m g L cos theta0, J: the energy of the release from rest, all of it potential.
inline double mechanicalEnergy_J(const Scene& scene) {
    return -scene.mass_kg * scene.gravity_mps2 * scene.length_m * std::cos(releaseAngle_rad(scene));
}

/// E(theta, theta') for this scene: m L^2 theta'^2 / 2 - m g L cos theta, J.
inline double energyOf_J(const Scene& scene, double theta_rad, double thetaDot_radps) {
    const double m = scene.mass_kg, L = scene.length_m;
    return 0.5 * m * L * L * thetaDot_radps * thetaDot_radps - m * scene.gravity_mps2 * L * std::cos(theta_rad);
}

}  // namespace pendulum::exact
