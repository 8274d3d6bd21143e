#include "simlab/measured_run.h"

#include <time.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "simlab/integrators.h"

namespace simlab {

namespace {

double cpuSeconds() {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

bool finite(const SimTK::State& state) {
    const SimTK::Vector& y = state.getY();
    for (int i = 0; i < y.size(); ++i) {
        if (!std::isfinite(y[i])) return false;
    }
    return std::isfinite(state.getTime());
}

std::string at(double reached, double finalTime) {
    char text[96];
    std::snprintf(text, sizeof text, " at t = %.4g s of %g s", reached, finalTime);
    return text;
}

}  // namespace

std::unique_ptr<SimTK::Integrator> integratorFor(const RunSettings& choice, const SimTK::System& system,
                                                 double finalTime) {
    requireIntegratorName(choice.integrator);
    const bool fixed = takesFixedSteps(choice);
    if (fixed && !(choice.dt > 0 && choice.dt <= finalTime)) {
        std::ostringstream s;
        s << "a fixed step must be a positive number of seconds no longer than the run (" << finalTime << " s), got "
          << choice.dt;
        throw std::invalid_argument(s.str());
    }
    // The accuracy, as a lab program sets it: a fixed step reads it too (Verlet's implicit velocity update is solved
    // to it, fixedStepUsesAccuracy; events are localized and constraints projected by it). Where only rounding
    // would show it (another method's fixed step), one outside (0, 1) is left at Simbody's default.
    const bool valid = choice.accuracy > 0 && choice.accuracy < 1;
    if (!valid && (!fixed || fixedStepUsesAccuracy(choice.integrator))) {
        std::ostringstream s;
        s << "accuracy must be between 0 and 1, got " << choice.accuracy;
        throw std::invalid_argument(s.str());
    }
    std::unique_ptr<SimTK::Integrator> integrator =
        integratorNamed(choice.integrator, system, fixed ? choice.dt : finalTime / 1000);
    if (valid) integrator->setAccuracy(choice.accuracy);
    if (fixed) integrator->setFixedStepSize(choice.dt);
    integrator->setFinalTime(finalTime);
    return integrator;
}

double nextStepEnd(double fixedStep, double finalTime, double time) {
    if (!(fixedStep > 0)) return finalTime;
    RunSettings grid;
    grid.dt = fixedStep;
    grid.finalTime = finalTime;
    // The first k * fixedStep past `time` (by more than rounding), counted as the lab program counts its samples.
    int k = static_cast<int>(std::floor(time / fixedStep));
    while (k < grid.sampleCount() && grid.sampleTime(k) <= time * (1 + 1e-15) + 1e-300) ++k;
    return grid.sampleTime(k);
}

MeasuredRun measureRun(const SimTK::System& system, SimTK::Integrator& integrator, const SimTK::State& initial,
                       double finalTime, const MeasureLimits& limits,
                       const std::function<void(const SimTK::State&, bool)>& check, double fixedStep) {
    MeasuredRun out;
    integrator.setReturnEveryInternalStep(true);
    SimTK::TimeStepper stepper(system, integrator);
    stepper.setReportAllSignificantStates(true);
    using Clock = std::chrono::steady_clock;
    Clock::duration stepping{};
    Clock::time_point start = Clock::now();
    stepper.initialize(initial);
    stepping += Clock::now() - start;
    check(stepper.getState(), false);
    const double every = finalTime / limits.checks;
    double nextCheck = every;
    const double began = cpuSeconds();
    while (true) {
        const double before = stepper.getState().getTime();
        start = Clock::now();
        stepper.stepTo(nextStepEnd(fixedStep, finalTime, before));
        stepping += Clock::now() - start;
        const SimTK::State& state = stepper.getState();
        out.reached = state.getTime();
        if (!finite(state)) {
            out.status = "blew up";
            out.message = "the state is not finite" + at(out.reached, finalTime);
            break;
        }
        const bool over = integrator.isSimulationOver() || state.getTime() >= finalTime;
        if (!over && integrator.getNumRealizations() > limits.maxEvaluations) {
            out.status = "too costly";
            out.message = "past the cap of " + std::to_string(static_cast<long long>(limits.maxEvaluations)) +
                          " evaluations" + at(out.reached, finalTime);
        } else if (!over && cpuSeconds() - began > limits.cpuSeconds) {
            // A net for a run that would never end, not a measure of cost: what it stops is a failure, named.
            out.status = "failed";
            out.message = "stopped by the net of " + std::to_string(static_cast<long long>(limits.cpuSeconds)) +
                          " s of CPU time before the cap of " +
                          std::to_string(static_cast<long long>(limits.maxEvaluations)) + " evaluations" +
                          at(out.reached, finalTime);
        }
        const bool last = over || out.status != "ok";
        if (state.getTime() >= nextCheck || last) {
            nextCheck = state.getTime() + every;
            check(state, last);
        }
        if (last) break;
        if (!(state.getTime() > before) && integrator.getNumStepsTaken() > 10000000) {
            out.status = "failed";
            out.message = "the step size collapsed" + at(out.reached, finalTime);
            break;
        }
    }
    out.integrator = statsOf(integrator);
    out.stepSeconds = std::chrono::duration<double>(stepping).count();
    return out;
}

}  // namespace simlab
