// PROJECT_TITLE: your own biosimulation project.
//
// Start here, then fill in each SIMLAB_TODO in turn; the program stops at the first one it reaches and says where.
// The contract is biosim/Project.h: read it first. The baby boot (`build/bin/simlab project new boot --from
// babyboot`) is a finished example of every function below.
//
//   1. declare():       your parameters (with units and ranges), the columns you sample, and your claims
//   2. buildModel():    bodies, joints and forces, every number read from a parameter: p["name"]
//   3. initialState():  the state at t = 0 from the initial-value parameters
//   4. sample():        one value per declared column
//   5. experiments():   your own checks, each also described in project.toml
//   6. answer():        the number that answers your question, computed with simulate()
//
// Build and run:  cmake --build build && ./build/PROJECT_NAME          (--help lists the options)
// Self-check:     build/bin/simlab check biosim Project.cpp
#include "biosim/Project.h"

#include <cmath>

#include "simlab/todo.h"

namespace biosim {

using namespace SimTK;

Declaration declare() {
    Declaration d;
    d.program = "PROJECT_NAME";
    d.title = "PROJECT_TITLE";
    // One Parameter per physical quantity: {name, unit, default, min, max, meaning}. Every value in a range
    // must simulate: the grader runs each parameter at both ends of its range (declare the range the model is
    // meant for, wider than a tenth of the default). Parameters bound together (a body's three moments) get a
    // rule in d.rules instead of narrow ranges: {"what it requires", [](const Parameters& p) { return ...; }}.
    d.parameters = {
        {"g", "m/s^2", 9.81, 0, 20, "gravity, along -y of Ground"},
    };
    // The quantities sample() returns, in order: {name, unit, meaning}, each read from the state (the grader
    // checks that it moves when the state does), or {name, unit, meaning, true} for one that is constant. The
    // course adds the time column.
    d.columns = {};
    // The degrees of freedom the scene requires, whether anything dissipates energy, and the settings with no
    // gravity, no other force and no initial motion (the model must then stay at rest, even when the grader moves
    // its coordinates a little), e.g. {{"g", 0}}.
    d.claims.degreesOfFreedom = 0;
    d.claims.energyConserved = false;
    d.claims.atRest = {};
    d.run.finalTime = 5;
    SIMLAB_TODO("declare your parameters, columns and claims (the baby boot shows a complete declaration)");
    return d;
}

void buildModel(const Parameters& p, Model& model) {
    // Each body: a Body::Rigid with its MassProperties, on a MobilizedBody whose type gives exactly the motions
    // the scene needs (a Pin turns about one axis, a Slider slides along one), kept in model.bodies["A"].
    SIMLAB_TODO("add your bodies, joints and forces to the model");
}

State initialState(const Parameters& p, const Model& model) {
    State state = model.system.realizeTopology();
    SIMLAB_TODO("set the initial coordinates and speeds from your parameters");
    return state;
}

std::vector<double> sample(const Parameters& p, const Model& model, const State& state) {
    SIMLAB_TODO("return one value for each declared column, read from the state");
    return {};
}

std::vector<Experiment> experiments() {
    // e.g. conserved("the energy keeps its value", "energy").within(1e-6), each named in project.toml too.
    SIMLAB_TODO("write at least two experiments that validate your model");
    return {};
}

double answer(const Parameters& p) {
    // Simulate with simulate(p, settings) and compute the number that answers project.toml's question.
    SIMLAB_TODO("compute the answer to your question");
    return 0;
}

}  // namespace biosim
