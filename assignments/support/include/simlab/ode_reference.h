// A reference that does not use Simbody: y' = f(y) integrated in long double by Boost.Odeint, to judge Simbody's
// runs against (the work-precision study, and the trade question's grading of the book).
//
// Its steps are the same on every x86-64 machine. Odeint's own step-size control raises the error estimate to a
// power with pow(), which glibc computes in long double with the x87 instructions F2XM1 and FYL2X; Intel's and
// AMD's processors round those differently in the last bit, so the reference took other steps on another machine
// and the accuracy the study states for it changed in the first decimal (15.6 digits against 15.7). The controller
// here takes the power with +, -, *, / alone, which round the same everywhere.
#pragma once

#include <algorithm>
#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstddef>
#include <functional>

namespace simlab {

/// x^(1/n) for x > 0 and n >= 1, by Newton's iteration from above (exact frexp and ldexp scale x into
/// [1/2, 2^(n-1)) first): the same bits on every machine, good to a few units in the last place.
inline long double arithmeticRoot(long double x, int n) {
    if (!(x > 0) || n < 1) return x == 0 ? 0.0L : NAN;
    if (n == 1) return x;
    int e = 0;
    const long double m = std::frexp(x, &e);  // x = m 2^e, m in [1/2, 1)
    const int q = (e >= 0 ? e : e - (n - 1)) / n, r = e - q * n;  // e = q n + r, 0 <= r < n
    const long double z = std::ldexp(m, r);
    // Bernoulli's inequality puts 1 + (z - 1)/n at or above the root; from above, Newton's steps fall to it.
    long double w = 1 + (z - 1) / n;
    for (int i = 0; i < 200; ++i) {
        long double power = 1;
        for (int k = 1; k < n; ++k) power *= w;  // w^(n-1)
        const long double next = ((n - 1) * w + z / power) / n;
        if (!(next < w)) break;
        w = next;
    }
    return std::ldexp(w, q);
}

/// Odeint's step adjuster (the same rules: shrink by 0.9 (error)^(-1/(order-1)), at most fivefold; grow by
/// 0.9 (error)^(-1/order), at most fivefold) with the powers taken by arithmeticRoot.
template <class Value, class Time>
class ArithmeticStepAdjuster {
public:
    using time_type = Time;
    using value_type = Value;

    time_type decrease_step(time_type dt, const value_type error, const int errorOrder) const {
        return dt * std::max<value_type>(static_cast<value_type>(0.9) / arithmeticRoot(error, errorOrder - 1),
                                         static_cast<value_type>(0.2));
    }
    time_type increase_step(time_type dt, value_type error, const int stepperOrder) const {
        if (error < 0.5) {
            value_type floor = 1;
            for (int k = 0; k < stepperOrder; ++k) floor /= 5;  // 5^-order: grow at most fivefold
            error = std::max(floor, error);
            dt *= static_cast<value_type>(0.9) / arithmeticRoot(error, stepperOrder);
        }
        return dt;
    }
    bool check_step_size_limit(const time_type) { return true; }
    time_type get_max_dt() { return 0; }
};

/// Runge-Kutta-Fehlberg 7(8) in long double with Odeint's error control at `tolerance` (relative and absolute)
/// and the arithmetic step adjuster. (Odeint's controlled stepper copies a new stepper whose scratch arrays are not
/// yet written, which GCC reports at -O1; they are written before they are read.)
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
template <class Y>
auto referenceStepper(long double tolerance) {
    namespace odeint = boost::numeric::odeint;
    using Stepper = odeint::runge_kutta_fehlberg78<Y, long double>;
    using Checker = odeint::default_error_checker<long double, typename Stepper::algebra_type,
                                                  typename Stepper::operations_type>;
    using Adjuster = ArithmeticStepAdjuster<long double, long double>;
    return odeint::controlled_runge_kutta<Stepper, Checker, Adjuster>(Checker(tolerance, tolerance), Adjuster());
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

/// A reference computed without Simbody: y' = f(y) for N long doubles (19 significant digits), integrated by
/// referenceStepper at `tolerance` and advanced to each time asked for. Times must not decrease; an earlier time
/// starts again from t = 0.
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
            auto stepper = referenceStepper<Y>(tolerance_);
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
        if (error > 0) worst = std::min(worst, -std::log10(static_cast<double>(error)));
    }
    return worst;
}

}  // namespace simlab
