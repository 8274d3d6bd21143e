// A run as the work-precision study measures one, and as the graded trade question measures a student's choice:
// the integrator reports only where it stops of its own accord, so no sampling interval cuts a step short, and
// what it costs (steps, evaluations) is the integrator's alone.
#pragma once

#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "Simbody.h"
#include "simlab/driver.h"
#include "simlab/run_settings.h"

namespace simlab {

/// How a measured run ended. "too costly" is decided by the count of evaluations alone, so that it is the same
/// on every machine at any load; a run stopped by the CPU-time net is "failed", and says so.
struct MeasuredRun {
    std::string status = "ok";  ///< "ok", "too costly", "blew up" or "failed"
    std::string message;        ///< one line, for any status but "ok"
    double reached = 0;         ///< s of simulated time
    IntegratorStats integrator;
    /// Wall seconds the integrator took: its initialization and its steps, the checks between them left out.
    double stepSeconds = 0;
};

/// Where a measured run stops short.
struct MeasureLimits {
    double maxEvaluations = INFINITY;  ///< evaluations of the equations of motion
    double cpuSeconds = INFINITY;      ///< a net: CPU time of this process spent in the run (never a cost)
    int checks = 1000;                 ///< about this many states are checked, spread evenly in time
};

/// The integrator `choice` names: at choice.accuracy, or at fixed steps of choice.dt when choice.fixedStep
/// (SemiExplicitEuler always), set to stop at `finalTime`. A fixed step gets choice.accuracy too, as a lab program
/// sets it: Verlet solves its implicit velocity update to it (fixedStepUsesAccuracy), and any method localizes events
/// by it. Throws std::invalid_argument, naming the setting, for a
/// choice that is not one (an unknown integrator, an accuracy outside (0, 1), a step that is not positive).
std::unique_ptr<SimTK::Integrator> integratorFor(const RunSettings& choice, const SimTK::System& system,
                                                 double finalTime);

/// Steps `integrator` (made by integratorFor) from `initial` to `finalTime`, returning at each of its own steps,
/// and calls `check(state, last)` on the state at t = 0, at steps at least finalTime / limits.checks apart, and
/// on the state where the run ends or passes a limit (with last = true). Stops, saying where in one line, past a
/// limit, at a state that is not finite, or when the step size collapses (neither of which is checked).
/// Exceptions from the model (an event handler, say) propagate.
/// At a fixed step (`fixedStep`, s; 0 for a run with error control) each step ends at k * fixedStep, and the last at
/// the final time, where a lab program's samples end them (RunSettings::sampleTime), rather than where adding up the
/// steps puts it: the same run, to the last bit, as the lab program's at that step.
MeasuredRun measureRun(const SimTK::System& system, SimTK::Integrator& integrator, const SimTK::State& initial,
                       double finalTime, const MeasureLimits& limits,
                       const std::function<void(const SimTK::State& state, bool last)>& check, double fixedStep = 0);

/// Where the run of `choice` steps to next from `time`, `finalTime` its end: the final time, or at a fixed step
/// (takesFixedSteps) the next whole multiple of it (RunSettings::sampleTime), as a lab program's samples end them.
double nextStepEnd(double fixedStep, double finalTime, double time);

/// A student's choice of integrator, measured on their own model: the samples at the checked states, the cost,
/// and how the run ended.
template <class Sample>
struct ChoiceRun {
    RunSettings choice;
    std::vector<Sample> samples;
    MeasuredRun run;
};

/// Builds the student's model for `scene` and measures `choice` on it to `finalTime` (see measureRun), reading
/// each checked state with `read`: the course's own reading, never the contract's sample(), so that the digits
/// are those of the state the integrator reached.
template <class Sample, class Scene, class Model>
ChoiceRun<Sample> measureChoice(const Scene& scene, Model& model, const RunSettings& choice, double finalTime,
                                const MeasureLimits& limits, Sample (*read)(const Model&, const SimTK::State&)) {
    ChoiceRun<Sample> result;
    result.choice = choice;
    buildModel(scene, model);
    const SimTK::State initial = initialState(scene, model);
    requireSimulatedMotion(model.matter);
    const std::unique_ptr<SimTK::Integrator> integrator = integratorFor(choice, model.system, finalTime);
    result.run = measureRun(
        model.system, *integrator, initial, finalTime, limits,
        [&](const SimTK::State& state, bool) { result.samples.push_back(read(model, state)); },
        takesFixedSteps(choice) ? choice.dt : 0.0);
    return result;
}

/// What in a reported ChoiceRun does not add up, in one line (empty if it all does): each sample after the first
/// is taken at one of the integrator's own steps (or at the last state), every step taken was attempted, and every
/// attempt evaluated the equations of motion at least once. A grader reads a ChoiceRun from the student's process,
/// so its counts are data to check.
template <class Sample>
std::string inconsistencyOf(const ChoiceRun<Sample>& result) {
    const IntegratorStats& stats = result.run.integrator;
    long long laterTimes = 0;
    for (std::size_t i = 1; i < result.samples.size(); ++i) laterTimes += result.samples[i].time > result.samples[i - 1].time;
    const std::string counts = std::to_string(stats.stepsTaken) + " steps taken, " +
                               std::to_string(stats.stepsAttempted) + " attempted, " +
                               std::to_string(stats.realizations) + " evaluations";
    if (laterTimes > static_cast<long long>(stats.stepsTaken) + 1) {
        return "the run reports " + counts + " but samples " + std::to_string(laterTimes) + " later times";
    }
    if (stats.stepsTaken < 0 || stats.stepsAttempted < stats.stepsTaken || stats.realizations < stats.stepsAttempted) {
        return "the run reports " + counts + ", which cannot all be true";
    }
    return "";
}

}  // namespace simlab
