// The probe: the one process of a grader test that holds the student's code. It answers the judge's requests
// for observations - "run this scene with these settings", "describe the model you build" - by calling the
// contract through the course's driver, and sends back data. It decides nothing: every figure and every point
// is computed by the judge, from what the probe says, checked.
//
// Each assignment's probe.cpp registers what can be observed of its contract:
//
//     SIMLAB_PROBE(appleObservations) { simlab::probe::addLab<apple::Sample, apple::Scene, apple::Model>(); }
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <typeinfo>

#include "simlab/driver.h"
#include "simlab/measured_run.h"
#include "simlab/wire_types.h"

namespace simlab::probe {

/// Computes an observation from the request's arguments. Exceptions (the student's included) become the answer.
using Handler = std::function<nlohmann::json(const nlohmann::json& arguments)>;

/// Make `kind` observable. Called by SIMLAB_PROBE, before any of the student's code runs; a kind already there is
/// never replaced, and once the probe serves nothing is added (std::logic_error): what the course registered is
/// what answers.
void add(const std::string& kind, Handler handler);

/// No more kinds from now on (the probe's main calls it before it serves).
void seal();

/// The answer to one request line, as one line of JSON without its newline: {"id": N, "answer": ...}, or
/// {"id": N, "threw": {"type": ..., "message": ...}} when the handler threw.
std::string answer(const std::string& request);

/// Called with each exception of the student's code that answer() turns into the answer, and the name of its type;
/// the probe's main sets it (to tell where it was thrown), a floor leaves it unset.
using ThrowReporter = void (*)(const std::exception& caught, const std::string& type);
void reportThrows(ThrowReporter reporter);

/// "std::runtime_error" for typeid(std::runtime_error): the name an exception's type has in C++.
std::string typeName(const std::type_info& type);

/// `arguments[key]` read as a T.
template <class T>
T argument(const nlohmann::json& arguments, const char* key) {
    T value{};
    wire::readField(arguments, key, value, "arguments");
    return value;
}

/// The observations every lab offers. "run": the student's simulation of a scene with run settings, driven as
/// the lab program drives it (simlab::run); "model": the description of the model built for a scene.
template <class Sample, class Scene, class Model>
void addLab() {
    add("run", [](const nlohmann::json& arguments) {
        const Scene scene = argument<Scene>(arguments, "scene");
        const RunSettings settings = argument<RunSettings>(arguments, "settings");
        Model model;
        return wire::toJson(simlab::run<Sample>(scene, model, settings));
    });
    add("model", [](const nlohmann::json& arguments) {
        const Scene scene = argument<Scene>(arguments, "scene");
        Model model;
        buildModel(scene, model);
        const SimTK::State initial = initialState(scene, model);
        requireSimulatedMotion(model.matter);
        return wire::toJson(describeModel(model.matter, initial));
    });
}

/// The trade question: "choice" measures the student's `cheapest()` (their answer, a RunSettings) on their own
/// model of a scene, as the work-precision study measures a setting (simlab/measured_run.h), under the judge's
/// cap on evaluations, reading the states with the course's `read` (the lab's readState), not the student's
/// sample().
template <class Sample, class Scene, class Model>
void addTrade(RunSettings (*cheapest)(), Sample (*read)(const Model&, const SimTK::State&)) {
    add("choice", [cheapest, read](const nlohmann::json& arguments) {
        const Scene scene = argument<Scene>(arguments, "scene");
        MeasureLimits limits;
        limits.maxEvaluations = argument<double>(arguments, "max_evaluations");
        const RunSettings choice = cheapest();
        Model model;
        return wire::toJson(measureChoice(scene, model, choice, argument<double>(arguments, "final_time"), limits, read));
    });
}

}  // namespace simlab::probe

/// Registers an assignment's observations when the probe starts, before any of the student's static initializers
/// (course code alone may use a constructor priority): SIMLAB_PROBE(name) { ... }.
#define SIMLAB_PROBE(name)                                                     \
    static void name();                                                        \
    __attribute__((constructor(101))) static void name##Register() { name(); } \
    static void name()
