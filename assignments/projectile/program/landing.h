// The ground hit, the course's way: run the student's simulation until their event handler ends it at the
// ground, and read what it recorded. The lab program and the grader both use this.
#pragma once

#include <algorithm>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>

#include "projectile/contract/ProjectileMotion.h"
#include "projectile/program/exact.h"
#include "simlab/driver.h"

namespace projectile {

struct Landing {
    GroundHit hit;                      ///< what the student's handler recorded (found = false if nothing)
    double endTime = 0;                 ///< s, the time of the last sample: where the simulation stopped
    simlab::IntegratorStats integrator;
};

/// Moves the ball's origin of `state` to `depth` metres below Ground's origin (a launch from a trench), keeping its
/// velocity: Simbody's Assembler fits the q's of whatever mobilizers the student chose. Throws std::runtime_error
/// if they cannot put it there.
inline void startBelowGround(const Model& model, SimTK::State& state, double depth) {
    SimTK::Assembler assembler(model.system);
    assembler.setAccuracy(1e-14);
    auto* markers = new SimTK::Markers();  // the assembler adopts it
    markers->addMarker("ball", model.ball.getMobilizedBodyIndex(), SimTK::Vec3(0));
    assembler.adoptAssemblyGoal(markers);
    assembler.initialize(state);
    markers->moveOneObservation(SimTK::Markers::ObservationIx(0), SimTK::Vec3(0, -depth, 0));
    assembler.assemble();
    assembler.updateFromInternalState(state);
    model.system.realize(state, SimTK::Stage::Position);
    const SimTK::Vec3 p_GB = model.ball.getBodyOriginLocation(state);
    if (!((p_GB - SimTK::Vec3(0, -depth, 0)).norm() <= 1e-9 * std::max(1.0, depth))) {
        char what[160];
        std::snprintf(what, sizeof what, "could not start the ball %g m below the ground: the model's mobilities put "
                      "it at (%g, %g, %g) m", depth, p_GB[0], p_GB[1], p_GB[2]);
        throw std::runtime_error(what);
    }
}

/// Simulate `scene` with `run` (its dt and integrator settings) for up to twice the exact flight time plus a
/// second: a handler that ends the simulation at the ground stops it long before that. The samples are only where
/// the simulation may stop, so with error control their interval is fitted to the flight: at most a twentieth of
/// it, so that the ball is seen in the air before it comes down (a flight shorter than dt would otherwise start
/// and end inside the first sampling interval), and no more than a hundred thousand of them over a flight of
/// days. At fixed steps (--fixed-step, or an integrator without error control: SemiExplicitEuler) dt is the step
/// the user asked for and is kept, and a flight it cannot resolve is an error (std::invalid_argument). With a
/// `depth`, the ball starts that far below the ground's level (startBelowGround) and rises through it first.
/// Why fixed steps of `run` cannot follow a flight of `tStar` s to the ground, or "": steps past a quarter of it
/// (a step may jump over the whole flight), or over ten million of them.
inline std::string fixedStepProblem(const simlab::RunSettings& run, double tStar) {
    if (!simlab::takesFixedSteps(run)) return "";
    char what[200];
    if (run.dt > tStar / 4) {
        std::snprintf(what, sizeof what, "the flight lasts t* = %.3g s, too short for fixed steps of --dt %g s to "
                      "see it; use --dt %.2g or smaller", tStar, run.dt, tStar / 20);
        return what;
    }
    if ((2 * tStar + std::min(1.0, 100 * std::min(run.dt, tStar / 20))) / run.dt > 1e7) {
        std::snprintf(what, sizeof what, "the flight lasts t* = %.3g s: at fixed steps of --dt %g s that is %.2g "
                      "steps, over ten million; use a larger --dt", tStar, run.dt, tStar / run.dt);
        return what;
    }
    return "";
}

inline Landing simulateLanding(const Scene& scene, simlab::RunSettings run,
                               const std::function<void(const Sample&)>& onSample = {}, double depth = 0) {
    const double tStar = depth > 0 ? exact::flightTimeFrom(scene, depth) : exact::flightTime(scene);
    run.finalTime = 2 * tStar + std::min(1.0, 100 * std::min(run.dt, tStar / 20));
    if (!simlab::takesFixedSteps(run)) {
        run.dt = std::max(std::min(run.dt, tStar / 20), run.finalTime / 1e5);
    } else if (const std::string problem = fixedStepProblem(run, tStar); !problem.empty()) {
        throw std::invalid_argument(problem);
    }
    Model model;
    simlab::RunHooks<Model> hooks;
    if (depth > 0) hooks.atStart = [depth](const Model& m, SimTK::State& state) { startBelowGround(m, state, depth); };
    const simlab::RunResult<Sample> result = simlab::run<Sample>(scene, model, run, onSample, hooks);
    return {model.groundHit, result.samples.empty() ? 0 : result.samples.back().time, result.integrator};
}

}  // namespace projectile
