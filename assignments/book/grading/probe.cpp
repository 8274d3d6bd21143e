// What the grader can observe of a student's BookSpin.cpp: its simulation of a scene, its model, its answer to the
// trade question (measured), and the book's
// mass properties in that model.
#include "book/grading/observations.h"
#include "simlab/probe/probe.h"

SIMLAB_PROBE(bookObservations) {
    using namespace book;
    simlab::probe::addLab<Sample, Scene, Model>();
    simlab::probe::addTrade<Sample, Scene, Model>(cheapestSettings, readState);
    simlab::probe::add("massProperties", [](const nlohmann::json& arguments) {
        const Scene scene = simlab::probe::argument<Scene>(arguments, "scene");
        Model model;
        buildModel(scene, model);
        SimTK::State state = initialState(scene, model);
        model.system.realize(state, SimTK::Stage::Instance);
        const SimTK::MassProperties props = model.book.getBodyMassProperties(state);
        const SimTK::Inertia inertia = props.getInertia();
        return simlab::wire::toJson(
            MassObservation{props.getMass(), props.getMassCenter(), inertia.getMoments(), inertia.getProducts()});
    });
}
