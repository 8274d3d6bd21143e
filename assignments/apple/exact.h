// Newton's apple, solved by hand.
//
// Newton's second law along Ground's y for an apple of mass m in uniform gravity g (no other forces):
//     -m g = m y''   =>   y'' = -g.
// Integrating twice from rest at height h:
//     y'(t) = -g t,    y(t) = h - g t^2 / 2.
// Kinetic plus potential energy (zero at y = 0) keeps its initial value: E = m g h.
// With the lab's numbers (h = 10 m, g = 9.8 m/s^2): y(4) = 10 - 4.9 * 16 = -68.4 m.
#pragma once

#include "apple/NewtonsApple.h"

namespace apple::exact {

inline double yLocation(const Scene& scene, double t) { return scene.dropHeight - 0.5 * scene.gravity * t * t; }

inline double yVelocity(const Scene& scene, double t) { return -scene.gravity * t; }

inline double mechanicalEnergy(const Scene& scene) { return scene.mass * scene.gravity * scene.dropHeight; }

}  // namespace apple::exact
