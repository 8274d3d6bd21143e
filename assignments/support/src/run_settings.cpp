#include "simlab/run_settings.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "simlab/integrators.h"

namespace simlab {

int RunSettings::sampleCount() const {
    // A final time within a billionth of a step of a multiple of dt is that multiple (4 / 0.01 is 400, not 401).
    return static_cast<int>(std::ceil(finalTime / dt - 1e-9));
}

double RunSettings::sampleTime(int k) const {
    return k >= sampleCount() ? finalTime : k * dt;
}

bool takesFixedSteps(const RunSettings& run) { return run.fixedStep || !hasErrorControl(run.integrator); }

std::string describeStepping(const RunSettings& run, bool events) {
    char text[80];
    if (takesFixedSteps(run) && (events || fixedStepUsesAccuracy(run.integrator))) {
        std::snprintf(text, sizeof text, "fixed step %g s at accuracy %g", run.dt, run.accuracy);
    } else if (takesFixedSteps(run)) {
        std::snprintf(text, sizeof text, "fixed step %g s", run.dt);
    } else {
        std::snprintf(text, sizeof text, "accuracy %g", run.accuracy);
    }
    return text;
}

std::string describeRun(const RunSettings& run, bool events) {
    return run.integrator + ", " + describeStepping(run, events);
}

double shortLastStep(const RunSettings& run) {
    if (!takesFixedSteps(run)) return 0;
    const int steps = run.sampleCount();
    const double last = run.finalTime - run.sampleTime(steps - 1);
    // A last step within a billionth of a step of a whole one is a whole one (sampleCount's own tolerance).
    return last < run.dt * (1 - 1e-9) ? last : 0;
}

std::string describeProgramRun(const RunSettings& run, bool events) {
    char text[160];
    if (!takesFixedSteps(run)) {
        std::snprintf(text, sizeof text, ", dt %g s, 0 <= t <= %g s", run.dt, run.finalTime);
    } else if (const double last = shortLastStep(run); last > 0) {
        std::snprintf(text, sizeof text, " (the last %.6g s), 0 <= t <= %g s", last, run.finalTime);
    } else {
        std::snprintf(text, sizeof text, ", 0 <= t <= %g s", run.finalTime);
    }
    return describeRun(run, events) + text;
}

void validate(const RunSettings& run) {
    auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
    requireIntegratorName(run.integrator);
    if (!(run.accuracy > 0 && run.accuracy < 1)) {
        std::ostringstream s;
        s << "accuracy must be between 0 and 1, got " << run.accuracy;
        fail(s.str());
    }
    if (run.fixedStep && run.integrator == "CPodes") {
        fail("CPodes takes no fixed steps: a multistep method, it chooses its own (Simbody's fails at its first "
             "fixed step); drop the fixed step or choose another integrator for it");
    }
    if (!(run.dt > 0 && std::isfinite(run.dt))) fail("dt must be a positive number of seconds");
    if (!(run.finalTime > 0 && std::isfinite(run.finalTime))) fail("final time must be a positive number of seconds");
    if (run.dt > run.finalTime) fail("dt must not exceed the final time");
    if (run.finalTime / run.dt > 1e7) fail("final time / dt is over ten million samples; use a larger dt");
}

}  // namespace simlab
