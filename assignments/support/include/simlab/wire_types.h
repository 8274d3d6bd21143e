// The JSON forms of the course's types every lab shares (run settings, the integrator's statistics, the model's
// description, a measured run): what the probe sends and the judge reads, in the protocol's strict form.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "simlab/driver.h"
#include "simlab/measured_run.h"
#include "simlab/model_info.h"
#include "simlab/protocol/wire.h"
#include "simlab/run_settings.h"

namespace simlab {

SIMLAB_WIRE(RunSettings, integrator, accuracy, dt, finalTime, fixedStep)
SIMLAB_WIRE(IntegratorStats, method, stepsTaken, stepsAttempted, realizations, accuracyInUse, errorControl)
SIMLAB_WIRE(MobilizerInfo, body, kind, nq, nu, mass)
SIMLAB_WIRE(ModelInfo, bodies, mobilities, constraintEquations, independentConstraints, mobilizers)
SIMLAB_WIRE(MeasuredRun, status, message, reached, integrator)

template <class Sample>
nlohmann::json toJsonObject(const RunResult<Sample>& o) {
    return {{"samples", wire::toJson(o.samples)}, {"model", wire::toJson(o.model)},
            {"integrator", wire::toJson(o.integrator)}};
}

template <class Sample>
void fromJson(const nlohmann::json& j, RunResult<Sample>& o, const std::string& where) {
    wire::readField(j, "samples", o.samples, where);
    wire::readField(j, "model", o.model, where);
    wire::readField(j, "integrator", o.integrator, where);
}

template <class Sample>
nlohmann::json toJsonObject(const ChoiceRun<Sample>& o) {
    return {{"choice", wire::toJson(o.choice)}, {"samples", wire::toJson(o.samples)}, {"run", wire::toJson(o.run)}};
}

template <class Sample>
void fromJson(const nlohmann::json& j, ChoiceRun<Sample>& o, const std::string& where) {
    wire::readField(j, "choice", o.choice, where);
    wire::readField(j, "samples", o.samples, where);
    wire::readField(j, "run", o.run, where);
}

}  // namespace simlab
