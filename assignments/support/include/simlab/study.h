// The work-precision study's measuring side: what each of Simbody's integrators pays, in steps, evaluations and
// time, for the digits it reaches on a lab's scene, against a reference that does not use Simbody.
//
// Each lab's study program (`<program>-study`, run by `simlab study trade`) lists its scenes as Subjects and hands
// them to studyMain, which runs every integrator at accuracies 1e-1 ... 1e-14 and, for the methods that can take
// fixed steps, a sweep of step sizes, each point under a cost cap, and prints one JSON object per line: the
// subject, then its points. simlab turns them into trade.csv, plots and the table of cheapest settings.
//
// How the cost of integrating is kept apart from the cost of sampling: the integrator reports only at the final
// time, so no sample interval ever cuts a step short. The error along the way is read at the integrator's own
// internal steps (returning after each does not change them), and the time is the fastest of N repeats that
// report only at the end, after the measured run has warmed the caches.
#pragma once

#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "Simbody.h"

namespace simlab::study {

/// One scene, built and ready to integrate, and how to judge any state of it against the reference.
class Instance {
public:
    virtual ~Instance() = default;
    virtual const SimTK::MultibodySystem& system() const = 0;
    virtual const SimTK::State& initial() const = 0;
    /// Digits to which `state` (realized through Velocity) agrees with the reference at its time: the worst
    /// component, each against its stated scale, never a relative error at a zero.
    virtual double digits(const SimTK::State& state) = 0;
    /// The quantity the motion conserves (its drift is the third measure).
    virtual double conserved(const SimTK::State& state) = 0;
    /// Digits of the figure the lab reports when the run is over (the ground hit's, say); the final state's by
    /// default.
    virtual double finalDigits(const SimTK::State& state) { return digits(state); }
};

/// A lab's scene in the study.
struct Subject {
    std::string name;               ///< e.g. "book-intermediate"
    std::string figure;             ///< what the digits measure, one line
    std::string conservedName;      ///< e.g. "energy"
    double conservedScale = 1;      ///< the drift is the largest |change| over this
    double finalTime = 1;           ///< s
    std::string reference;          ///< how the reference is computed, one line
    std::function<double()> referenceDigits;  ///< the reference's own accuracy at the final time, in digits
    std::function<std::unique_ptr<Instance>()> make;
    /// The same scene over-modelled: a Free (or Cartesian, Planar) mobilizer where the scene needs fewer motions,
    /// for `simlab study minimal`; empty where there is none. `overModelled` names it, e.g. "Free (6 dof)".
    std::function<std::unique_ptr<Instance>()> makeOverModelled;
    std::string minimal, overModelled;
};

/// Parses the study program's command line (--quick, --cap, --repeats, --subject, --list, --minimal), runs the
/// study of `subjects` (or, with --minimal, each scene minimal and over-modelled side by side) and prints it as JSON
/// lines on stdout (progress goes to stderr). Returns the exit status.
int studyMain(int argc, char** argv, const std::string& lab, const std::vector<Subject>& subjects);

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

}  // namespace simlab::study
