// Projectile motion, solved by hand.
//
// With gravity g along -y and no air, the ball launched from the origin at speed v0 and angle theta has
//     x(t) = v0 cos(theta) t,          y(t) = v0 sin(theta) t - g t^2 / 2,
// so its path is the parabola y(x) = tan(theta) x - g x^2 / (2 v0^2 cos^2(theta)). It is back at y = 0 at
//     t* = 2 v0 sin(theta) / g,        x* = v0 cos(theta) t*,
// 5.232422 s and 191.5909 m for the lab's 44.7 m/s at 35 degrees. Kinetic plus potential energy (zero at y = 0)
// keeps its launch value m v0^2 / 2.
#pragma once

#include <algorithm>
#include <cmath>

#include "projectile/contract/ProjectileMotion.h"
#include "simlab/digits.h"

namespace projectile::exact {

inline double launchAngle(const Scene& s) { return s.launchAngleDegrees * M_PI / 180.0; }  ///< radians
inline double xVelocity0(const Scene& s) { return s.launchSpeed * std::cos(launchAngle(s)); }
inline double yVelocity0(const Scene& s) { return s.launchSpeed * std::sin(launchAngle(s)); }

inline double x(const Scene& s, double t) { return xVelocity0(s) * t; }
inline double y(const Scene& s, double t) { return yVelocity0(s) * t - 0.5 * s.gravity * t * t; }
inline double xVelocity(const Scene& s, double) { return xVelocity0(s); }
inline double yVelocity(const Scene& s, double t) { return yVelocity0(s) - s.gravity * t; }

/// Height on the parabola at range x (not defined for a vertical launch).
inline double yOfX(const Scene& s, double x) {
    const double vx = xVelocity0(s);
    return std::tan(launchAngle(s)) * x - s.gravity * x * x / (2 * vx * vx);
}

inline double flightTime(const Scene& s) { return 2 * yVelocity0(s) / s.gravity; }  ///< t*

/// The flight of a ball launched `depth` metres below the ground's level (from a trench), which rises through
/// y = 0 and comes down through it later: the later root of -depth + vy0 t - g t^2/2 = 0 (NaN if it never
/// reaches the ground's level).
inline double flightTimeFrom(const Scene& s, double depth) {
    const double vy = yVelocity0(s);
    return (vy + std::sqrt(vy * vy - 2 * s.gravity * depth)) / s.gravity;
}
inline double range(const Scene& s) { return xVelocity0(s) * flightTime(s); }         ///< x*
inline double maxHeight(const Scene& s) { return yVelocity0(s) * yVelocity0(s) / (2 * s.gravity); }
inline double mechanicalEnergy(const Scene& s) { return 0.5 * s.mass * s.launchSpeed * s.launchSpeed; }

/// s: where the work-precision study's runs and the trade question's end, past the ground hit at 5.23 s (which ends
/// them first).
inline constexpr double kTradeFinalTime = 6;

/// Digits of a sample of the flight against the parabola, the worst of x, y, vx and vy. x starts at zero and y is
/// zero at both ends: positions count against the range and the top of the arc, speeds against the launch speed.
inline double flightDigits(const Scene& s, const Sample& sample) {
    const double v0 = s.launchSpeed;
    return std::min({simlab::accuracyDigits(sample.x, x(s, sample.time), range(s)),
                     simlab::accuracyDigits(sample.y, y(s, sample.time), maxHeight(s)),
                     simlab::accuracyDigits(sample.xVelocity, xVelocity(s, sample.time), v0),
                     simlab::accuracyDigits(sample.yVelocity, yVelocity(s, sample.time), v0)});
}

/// m: what the range's digits are relative to. x* itself, unless the launch is so near vertical that x* is under a
/// tenth of v0 t* (at 90 degrees it is zero): then v0 t*, the distance the ball travels. 0 stands for x* itself.
inline double rangeScale(const Scene& s) {
    const double travelled = s.launchSpeed * flightTime(s);
    return std::abs(range(s)) < 0.1 * travelled ? travelled : 0.0;
}

/// Digits of a ground hit's time `t` (s) against t*, and of its range `x` (m) against x* (on rangeScale).
inline double hitTimeDigits(const Scene& s, double t) { return simlab::accuracyDigits(t, flightTime(s)); }
inline double hitRangeDigits(const Scene& s, double x) { return simlab::accuracyDigits(x, range(s), rangeScale(s)); }

/// Digits of a ground hit found at time `t` (s) and range `x` (m), the worse of the two: the figure the lab program
/// reports and the study measures.
inline double hitDigits(const Scene& s, double t, double x) {
    return std::min(hitTimeDigits(s, t), hitRangeDigits(s, x));
}

}  // namespace projectile::exact
