// A reference certified by a second precision, not only by a second tolerance.
//
// A reference integrated at two tolerances in the same precision shares that precision's rounding: where the motion
// magnifies rounding (a spin within 1e-26 of a separatrix, a chaotic trajectory) both runs can be wrong by the same
// amount and still agree. So each rung of the ladder below integrates y' = f(y) three times: at `tolerance` and at a
// looser one in its own precision (the truncation error), and at `tolerance` in the next, wider precision (the
// rounding error). The rung's value is its own run at `tolerance`; its error is the larger of the two differences.
// When a rung cannot certify the digits asked of it, the next one, 49 bits wider, is tried:
//
//     long double (64-bit significand)  ->  cpp_bin_float_quad (113 bits)  ->  cpp_bin_float_50 (168 bits)
//
// Boost.Multiprecision's binary floats are computed in software, bit for bit the same on every machine, and so are
// Odeint's steps with them. Each wider run costs about 30 times the one below.
#pragma once

#include <algorithm>
#include <array>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>
#include <type_traits>

#include "simlab/ode_reference.h"

namespace simlab::precision {

using Quad = boost::multiprecision::cpp_bin_float_quad;
using Fifty = boost::multiprecision::number<boost::multiprecision::cpp_bin_float<50>, boost::multiprecision::et_off>;

}  // namespace simlab::precision

// Odeint reads a state's value type through a nested value_type, which Boost.Multiprecision's numbers also have;
// these say that such a number is its own value.
namespace boost::numeric::odeint::detail {
template <>
struct extract_value_type<simlab::precision::Quad, void> {
    using type = simlab::precision::Quad;
};
template <>
struct extract_value_type<simlab::precision::Fifty, void> {
    using type = simlab::precision::Fifty;
};
}  // namespace boost::numeric::odeint::detail

namespace simlab::precision {

/// y(t) for y' = f(y), y(0) = y0, by Runge-Kutta-Fehlberg 7(8) at `tolerance` (relative and absolute) in Real.
/// `f(y, dydt)` is called with arrays of Real. The controller is Odeint's own: in a software precision its powers
/// round the same everywhere; long double goes through referenceStepper's arithmetic controller instead.
template <class Real, std::size_t N, class F>
std::array<Real, N> integrate(const F& f, const std::array<double, N>& y0, double t, double tolerance,
                              double firstStep, std::size_t* steps = nullptr) {
    namespace odeint = boost::numeric::odeint;
    using Y = std::array<Real, N>;
    Y y;
    for (std::size_t i = 0; i < N; ++i) y[i] = Real(y0[i]);
    if (steps) *steps = 0;
    if (!(t > 0)) return y;
    auto system = [&f](const Y& state, Y& dydt, const Real&) { f(state, dydt); };
    const Real step = Real(std::min(firstStep, t));
    std::size_t taken = 0;
    if constexpr (std::is_same_v<Real, long double>) {
        taken = odeint::integrate_adaptive(referenceStepper<Y>(static_cast<long double>(tolerance)), system, y, 0.0L,
                                           static_cast<long double>(t), step);
    } else {
        auto stepper = odeint::make_controlled(Real(tolerance), Real(tolerance), odeint::runge_kutta_fehlberg78<Y, Real>());
        taken = odeint::integrate_adaptive(stepper, system, y, Real(0), Real(t), step);
    }
    if (steps) *steps = taken;
    return y;
}

/// One certified reference: the value, an upper estimate of its error, and what made it.
template <std::size_t N>
struct Certified {
    std::array<double, N> y{};
    double error = 0;        ///< the largest |difference| between the runs, component by component, in y's units
    bool widerChecked = false;  ///< a wider precision checked the rounding (false: too long a run to check)
    bool confirmed = false;  ///< error <= the error asked for
    std::string how;         ///< e.g. "long double at 1e-18, checked at 1e-16 and in 113-bit floats" (tolerances)
};

/// A long-double run longer than this many steps is not checked in quad precision (some 40 us a step: 1 s).
constexpr std::size_t kWiderCheckSteps = 20000;

namespace detail {

template <class Low, class High, std::size_t N, class F>
Certified<N> rung(const F& f, const std::array<double, N>& y0, double t, double tolerance, double firstStep,
                  const char* low, const char* high) {
    using boost::multiprecision::abs;
    using std::abs;
    std::size_t steps = 0;
    const auto value = integrate<Low>(f, y0, t, tolerance, firstStep, &steps);
    const auto loose = integrate<Low>(f, y0, t, 100 * tolerance, firstStep);
    Certified<N> c;
    c.widerChecked = steps <= kWiderCheckSteps;
    std::array<High, N> wider{};
    if (c.widerChecked) wider = integrate<High>(f, y0, t, tolerance, firstStep);
    for (std::size_t i = 0; i < N; ++i) {
        c.y[i] = static_cast<double>(value[i]);
        c.error = std::max(c.error, static_cast<double>(abs(value[i] - loose[i])));
        if (c.widerChecked) c.error = std::max(c.error, static_cast<double>(abs(High(value[i]) - wider[i])));
    }
    char text[200];
    if (c.widerChecked) {
        std::snprintf(text, sizeof text, "%s at %.0e, checked at %.0e and in %s", low, tolerance, 100 * tolerance,
                      high);
    } else {
        std::snprintf(text, sizeof text, "%s at %.0e, checked at %.0e but not in %s (%zu steps, too many)", low,
                      tolerance, 100 * tolerance, high, steps);
    }
    c.how = text;
    return c;
}

}  // namespace detail

/// y(t), certified to `wanted` (an absolute error in y's units) if the ladder can: long double at tolerance 1e-18,
/// checked at 1e-16 and in quad precision; where that leaves more error than wanted, quad at 1e-24 checked at 1e-22
/// and in 50 digits. The result says how far it got (`confirmed`) and its error; a caller claims no digit past it.
/// The ladder's first rung alone: long double at tolerance 1e-18, checked at 1e-16 and in quad precision (the
/// error of the long-double references that follow a run sample by sample, as OdeReference does).
template <std::size_t N, class F>
Certified<N> certifyLongDouble(const F& f, const std::array<double, N>& y0, double t, double firstStep) {
    return detail::rung<long double, Quad>(f, y0, t, 1e-18, firstStep, "long double", "113-bit floats");
}

template <std::size_t N, class F>
Certified<N> certify(const F& f, const std::array<double, N>& y0, double t, double wanted, double firstStep) {
    Certified<N> c = certifyLongDouble<N>(f, y0, t, firstStep);
    if (!(c.error <= wanted) && c.widerChecked) {
        c = detail::rung<Quad, Fifty>(f, y0, t, 1e-24, firstStep, "113-bit floats", "50-digit floats");
    }
    c.confirmed = c.error <= wanted;
    return c;
}

}  // namespace simlab::precision
