// The course's driver: runs a student's simulation through the contract every assignment shares.
//
// Each assignment's header declares, in its own namespace, the functions a student writes:
//   void buildModel(const Scene&, Model&);
//   SimTK::State initialState(const Scene&, const Model&);
//   std::unique_ptr<SimTK::Integrator> makeIntegrator(const Model&, const simlab::RunSettings&);
//   void simulate(const Model&, SimTK::Integrator&, const SimTK::State&, const simlab::RunSettings&,
//                 simlab::Recorder<Sample>&);
// run() calls them in that order (found by argument-dependent lookup), so the lab program and the grader
// drive student code the same way.
#pragma once

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "Simbody.h"
#include "simlab/model_info.h"
#include "simlab/recorder.h"
#include "simlab/run_settings.h"

namespace simlab {

/// What a run stopped at its cost cap throws (a trade table's run, say): too costly, and where it stopped.
struct TooCostly : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// What the integrator reports once a run is over.
struct IntegratorStats {
    std::string method;  ///< Simbody's name for it, e.g. "RungeKuttaMerson"
    int stepsTaken = 0;
    int stepsAttempted = 0;
    int realizations = 0;  ///< evaluations of the equations of motion
    double accuracyInUse = 0;
    bool errorControl = false;
};

IntegratorStats statsOf(const SimTK::Integrator& integrator);

template <class Sample>
struct RunResult {
    std::vector<Sample> samples;
    ModelInfo model;
    IntegratorStats integrator;
};

/// Hooks for the caller between the contract's steps; each may be empty.
template <class Model>
struct RunHooks {
    std::function<void(Model&)> afterBuild;                             ///< e.g. attach a visualizer
    std::function<void(const Model&, SimTK::State&)> atStart;           ///< e.g. move the initial state
    std::function<void(const Model&, const SimTK::Integrator&)> afterRun;  ///< e.g. read what the model kept
};

/// Build the model for `scene`, set its initial state, make the integrator and simulate, recording every
/// sample (passing each to `onSample` too). Exceptions from student code propagate.
template <class Sample, class Scene, class Model>
RunResult<Sample> run(const Scene& scene, Model& model, const RunSettings& settings,
                      const std::function<void(const Sample&)>& onSample = {},
                      const RunHooks<Model>& hooks = {}) {
    buildModel(scene, model);
    if (hooks.afterBuild) hooks.afterBuild(model);
    SimTK::State initial = initialState(scene, model);
    if (hooks.atStart) hooks.atStart(model, initial);
    requireSimulatedMotion(model.matter);
    RunResult<Sample> result;
    result.model = describeModel(model.matter, initial);
    const std::unique_ptr<SimTK::Integrator> integrator = makeIntegrator(model, settings);
    if (!integrator) throw std::logic_error("makeIntegrator returned no integrator");
    // Room for twice the samples the settings call for: more means the stepping loop does not stop.
    Recorder<Sample> recorder(onSample, 2 * static_cast<std::size_t>(settings.sampleCount() + 1) + 10);
    simulate(model, *integrator, initial, settings, recorder);
    requireSimulatedMotion(model.matter);  // nothing added along the way either
    result.samples = recorder.rows();
    result.integrator = statsOf(*integrator);
    if (hooks.afterRun) hooks.afterRun(model, *integrator);
    return result;
}

}  // namespace simlab
