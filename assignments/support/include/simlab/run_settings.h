// How a lab simulation runs: which integrator, how accurately, how often it is sampled and for how long.
// The lab programs fill these from their command line; the grader varies them.
#pragma once

#include <string>

namespace simlab {

struct RunSettings {
    std::string integrator = "RungeKuttaMerson";  ///< one of simlab::integratorNames()
    double accuracy = 1e-7;  ///< relative accuracy the error-controlled integrators keep each step to
    double dt = 0.01;        ///< s, interval between samples; also the step of fixed-step integration
    double finalTime = 4.0;  ///< s, the simulation runs from t = 0 to here
    bool fixedStep = false;  ///< step at exactly dt with no error control (SemiExplicitEuler always does)

    /// Number of sampling intervals: samples are taken at k = 0, 1, ..., sampleCount().
    int sampleCount() const;
    /// Time of sample k: k * dt, except that the last sample is at finalTime exactly.
    double sampleTime(int k) const;
};

/// Whether the run steps at exactly dt: asked to (fixedStep), or by an integrator without error control
/// (SemiExplicitEuler).
bool takesFixedSteps(const RunSettings& run);

/// How the run steps, for a title: "accuracy 1e-07", or "fixed step 0.01 s" (SemiExplicitEuler's always is), or
/// where a fixed step reads the accuracy too, "fixed step 0.01 s at accuracy 1e-07": Verlet's (see
/// fixedStepUsesAccuracy), and with `events` (a model with event triggers, whose times the accuracy localizes at any
/// step) every method's. The trade question's lines say a setting the same way.
std::string describeStepping(const RunSettings& run, bool events = false);

/// What runs, for a title: "RungeKuttaMerson, accuracy 1e-07".
std::string describeRun(const RunSettings& run, bool events = false);

/// What a lab program runs, for its banner: "RungeKuttaMerson, accuracy 1e-07, dt 0.01 s, 0 <= t <= 4 s" (dt: the
/// sample interval); at fixed steps, sampled at each, "Verlet, fixed step 0.04 s at accuracy 1e-10, 0 <= t <= 4 s",
/// and where the final time is no whole number of steps, the shorter last one: "ExplicitEuler, fixed step 3 s (the
/// last 1 s), 0 <= t <= 4 s".
std::string describeProgramRun(const RunSettings& run, bool events = false);

/// The last step of a run at fixed steps of run.dt (takesFixedSteps) to run.finalTime, where the final time is no
/// whole number of steps: the shorter step that ends it, s; 0 otherwise (and for a run with error control).
double shortLastStep(const RunSettings& run);

/// Throws std::invalid_argument, with a message naming the setting, unless the settings are usable.
void validate(const RunSettings& run);

}  // namespace simlab
