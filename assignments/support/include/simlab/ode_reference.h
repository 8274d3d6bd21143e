// A reference that does not use Simbody: y' = f(y) integrated in long double by Boost.Odeint, to judge Simbody's
// runs against (the work-precision study, and the trade question's grading of the book).
#pragma once

#include <algorithm>
#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstddef>
#include <functional>

namespace simlab {

/// A reference computed without Simbody: y' = f(y) for N long doubles (19 significant digits), integrated by
/// Boost.Odeint's Runge-Kutta-Fehlberg 7(8) pair at `tolerance` (relative and absolute) and advanced to each
/// time asked for. Times must not decrease; an earlier time starts again from t = 0.
template <std::size_t N>
class OdeReference {
public:
    using Y = std::array<long double, N>;
    using Derivative = std::function<void(const Y& y, Y& dydt)>;

    OdeReference(Derivative f, const Y& start, long double tolerance)
        : f_(std::move(f)), start_(start), y_(start), tolerance_(tolerance) {}

    /// The state at time `t` (s).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"  // Odeint's steppers, copied before their first step
    const Y& at(double t) {
        namespace odeint = boost::numeric::odeint;
        if (t < t_) {
            y_ = start_;
            t_ = 0;
        }
        if (t > t_) {
            auto stepper = odeint::make_controlled(tolerance_, tolerance_,
                                                   odeint::runge_kutta_fehlberg78<Y, long double>());
            auto system = [this](const Y& y, Y& dydt, long double) { f_(y, dydt); };
            odeint::integrate_adaptive(stepper, system, y_, static_cast<long double>(t_), static_cast<long double>(t),
                                       static_cast<long double>(std::min(1e-3, t - t_)));
            t_ = t;
        }
        return y_;
    }
#pragma GCC diagnostic pop

private:
    Derivative f_;
    Y start_;
    Y y_;
    double t_ = 0;
    long double tolerance_;
};

/// Digits to which two references agree at `finalTime`, component by component against `scales`: a bound on
/// the looser one's accuracy, and so a floor on the tighter one's.
template <std::size_t N>
double agreement(OdeReference<N> tight, OdeReference<N> loose, double finalTime, const std::array<double, N>& scales) {
    const auto& a = tight.at(finalTime);
    const auto& b = loose.at(finalTime);
    double worst = 19;
    for (std::size_t i = 0; i < N; ++i) {
        const long double error = std::abs(a[i] - b[i]) / std::max<long double>(std::abs(a[i]), scales[i]);
        if (error > 0) worst = std::min(worst, static_cast<double>(-std::log10(error)));
    }
    return worst;
}

}  // namespace simlab
