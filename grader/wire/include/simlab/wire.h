// The wire format of observations: how the student's process (the probe) and the judge exchange the course's
// types as JSON. Each assignment declares the JSON form of its Scene and Sample with SIMLAB_WIRE; this header
// gives the types every lab shares.
//
// Reading is strict (simlab/wire/json.h), because the probe runs student code and what it sends is data to be
// checked. A non-finite number arrives as NaN: the judge reports where a simulation produced one.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "Simbody.h"
#include "simlab/bounded_json.h"
#include "simlab/measured_run.h"
#include "simlab/driver.h"
#include "simlab/model_info.h"
#include "simlab/run_settings.h"
#include "simlab/wire/json.h"

namespace simlab::wire {

inline void readValue(const nlohmann::json& j, SimTK::Vec3& value, const std::string& where) {
    if (!j.is_array() || j.size() != 3) throw WireError(where + " is not a list of 3 numbers");
    for (int i = 0; i < 3; ++i) readValue(j[i], value[i], where + "[" + std::to_string(i) + "]");
}

inline nlohmann::json toJson(const SimTK::Vec3& v) { return {toJson(v[0]), toJson(v[1]), toJson(v[2])}; }

}  // namespace simlab::wire

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
