// What the grader can observe of a student's ProjectileMotion.cpp: its simulation of a scene, its model, its answer to
// the trade question (measured), and the ground hit its event handler records when the simulation runs until the
// handler ends it (from the launch point, or from a trench "depth" metres below the ground's level).
#include "projectile/grading/observations.h"
#include "simlab/probe/probe.h"

SIMLAB_PROBE(projectileObservations) {
    using namespace projectile;
    simlab::probe::addLab<Sample, Scene, Model>();
    simlab::probe::addTrade<Sample, Scene, Model>(cheapestSettings, readState);
    simlab::probe::add("landing", [](const nlohmann::json& arguments) {
        const double depth = arguments.contains("depth") ? simlab::probe::argument<double>(arguments, "depth") : 0.0;
        Landing landing = simulateLanding(simlab::probe::argument<Scene>(arguments, "scene"),
                                          simlab::probe::argument<simlab::RunSettings>(arguments, "settings"), {},
                                          depth);
        if (!landing.hit.found) landing.hit.time = landing.hit.x = 0;  // nothing recorded: no time, no range
        return simlab::wire::toJson(landing);
    });
}
