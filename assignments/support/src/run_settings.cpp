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

std::string describeStepping(const RunSettings& run) {
    char text[64];
    if (takesFixedSteps(run)) {
        std::snprintf(text, sizeof text, "fixed step %g s", run.dt);
    } else {
        std::snprintf(text, sizeof text, "accuracy %g", run.accuracy);
    }
    return text;
}

std::string describeRun(const RunSettings& run) { return run.integrator + ", " + describeStepping(run); }

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
