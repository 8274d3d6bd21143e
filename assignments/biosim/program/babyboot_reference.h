// The baby boot's equations of motion, derived by hand (Lagrange) and integrated with Boost.Odeint: a reference
// that shares nothing with Simbody, for testing the boot's Simbody model.
//
// Generalized coordinates qA (the rod's swing about the horizontal axis, 0 hanging down) and qB (the plate's turn
// about the rod, 0 with its normal along the swing axis), speeds uA = qA', uB = qB'. With the plate turned by qB,
// its moment about the swing axis is IBx cos^2 qB + IBy sin^2 qB, so
//     T = 1/2 J(qB) uA^2 + 1/2 IBz uB^2,   J(qB) = IAx + mA LA^2 + mB LB^2 + IBx - (IBx - IBy) sin^2 qB
//     V = -g (mA LA + mB LB) cos qA
// and Lagrange's equations d/dt(dT/du) - dT/dq + dV/dq = 0 give
//     J(qB) uA' = -g (mA LA + mB LB) sin qA + 2 (IBx - IBy) sin qB cos qB uA uB
//     IBz uB'   = -(IBx - IBy) sin qB cos qB uA^2
#pragma once

#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <vector>

namespace babyboot::reference {

struct Parameters {  // SI units
    double mA = 0.010, LA = 0.075, IAx = 5e-6;
    double mB = 0.100, LB = 0.20, IBx = 2.5e-4, IBy = 5e-5, IBz = 2e-4;
    double g = 9.81;
};

/// {qA, qB, uA, uB}: radians and radians per second.
using State = std::vector<double>;

/// x' for x = {qA, qB, uA, uB}, in the precision of X's values (double; long double for the study's reference;
/// Boost.Multiprecision's floats, whose sin and cos are found beside them, to check it).
template <class X>
inline void derivative(const Parameters& p, const X& x, X& dxdt) {
    using Real = typename X::value_type;
    using std::cos;
    using std::sin;
    const Real qA = x[0], qB = x[1], uA = x[2], uB = x[3];
    const Real s = sin(qB), c = cos(qB);
    const Real J = p.IAx + p.mA * p.LA * p.LA + p.mB * p.LB * p.LB + p.IBx - (p.IBx - p.IBy) * s * s;
    dxdt[0] = uA;
    dxdt[1] = uB;
    dxdt[2] = (-p.g * (p.mA * p.LA + p.mB * p.LB) * sin(qA) + 2 * (p.IBx - p.IBy) * s * c * uA * uB) / J;
    dxdt[3] = -(p.IBx - p.IBy) * s * c * uA * uA / p.IBz;
}

/// Kinetic plus potential energy, zero potential at the pivot.
inline double energy(const Parameters& p, const State& x) {
    const double s = std::sin(x[1]);
    const double J = p.IAx + p.mA * p.LA * p.LA + p.mB * p.LB * p.LB + p.IBx - (p.IBx - p.IBy) * s * s;
    return 0.5 * J * x[2] * x[2] + 0.5 * p.IBz * x[3] * x[3] - p.g * (p.mA * p.LA + p.mB * p.LB) * std::cos(x[0]);
}

/// The state at each of `times` (increasing, the first the start), from `start`, by a Runge-Kutta-Fehlberg 7(8)
/// pair with error control to `tolerance` (absolute and relative).
inline std::vector<State> integrate(const Parameters& p, State start, const std::vector<double>& times,
                                    double tolerance = 1e-14) {
    namespace odeint = boost::numeric::odeint;
    std::vector<State> states;
    auto stepper = odeint::make_controlled(tolerance, tolerance, odeint::runge_kutta_fehlberg78<State>());
    auto system = [&p](const State& x, State& dxdt, double) { derivative(p, x, dxdt); };
    odeint::integrate_times(stepper, system, start, times.begin(), times.end(), 1e-4,
                            [&states](const State& x, double) { states.push_back(x); });
    return states;
}

}  // namespace babyboot::reference
