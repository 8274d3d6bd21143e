// What the grader can observe of a student's project: its declaration and experiments, runs of its model with
// parameters changed, its schematic, the values of its formulas and its answer. Each request names parameter
// changes; they are checked against the student's own declaration, as --set checks them.
#include "biosim/grading/observations.h"
#include "simlab/probe/probe.h"

namespace {

using simlab::probe::argument;

biosim::Experiment experimentNamed(const std::string& name) {
    for (biosim::Experiment& e : biosim::experiments()) {
        if (e.name == name) return e;
    }
    throw std::invalid_argument("experiments() has no experiment named '" + name + "'");
}

}  // namespace

SIMLAB_PROBE(projectObservations) {
    using namespace biosim;
    using Settings = std::map<std::string, double>;
    simlab::probe::add("declare", [](const nlohmann::json&) { return simlab::wire::toJson(declare()); });
    simlab::probe::add("experiments", [](const nlohmann::json&) {
        std::vector<ExperimentInfo> list;
        for (const Experiment& e : experiments()) list.push_back(infoOf(e));
        return simlab::wire::toJson(list);
    });
    simlab::probe::add("run", [](const nlohmann::json& arguments) {
        const Declaration declaration = declare();
        const Parameters parameters = resolve(declaration, argument<Settings>(arguments, "set"));
        // A mutant of the model, or the model itself: its nudge moves every generalized coordinate at t = 0 (the
        // integrator's initialization projects the state back onto any constraints and normalizes quaternions).
        const Mutation mutation = argument<Mutation>(arguments, "mutation");
        ObserveHooks hooks;
        hooks.afterBuild = [mutation](Model& model) { mutate(model, mutation); };
        if (mutation.nudge != 0) {
            hooks.initial = [nudge = mutation.nudge](SimTK::State& state) {
                for (int i = 0; i < state.getNQ(); ++i) state.updQ()[i] += nudge;
            };
        }
        return simlab::wire::toJson(
            observe(declaration, parameters, argument<simlab::RunSettings>(arguments, "settings"), hooks));
    });
    simlab::probe::add("columns", [](const nlohmann::json& arguments) {
        const Declaration declaration = declare();
        return simlab::wire::toJson(columnTraits(declaration, resolve(declaration, argument<Settings>(arguments, "set")),
                                                 argument<simlab::RunSettings>(arguments, "settings")));
    });
    simlab::probe::add("allowed", [](const nlohmann::json& arguments) {
        // The rules these values would break, as --set would refuse them (empty: allowed). A value outside its
        // range is the range's own refusal, one line.
        const Declaration declaration = declare();
        try {
            resolve(declaration, argument<Settings>(arguments, "set"));
            return simlab::wire::toJson(std::vector<std::string>{});
        } catch (const std::invalid_argument& e) {
            return simlab::wire::toJson(std::vector<std::string>{e.what()});
        }
    });
    simlab::probe::add("schematic", [](const nlohmann::json& arguments) {
        const Declaration declaration = declare();
        const Parameters parameters = resolve(declaration, argument<Settings>(arguments, "set"));
        Model model;
        buildModel(parameters, model);
        return simlab::wire::toJson(schematicOf(model, initialState(parameters, model), declaration.title));
    });
    simlab::probe::add("formula", [](const nlohmann::json& arguments) {
        const Experiment e = experimentNamed(argument<std::string>(arguments, "name"));
        if (!e.formula) throw std::invalid_argument("experiment '" + e.name + "' has no formula");
        const Parameters parameters = resolve(declare(), e.set);
        std::vector<double> values;
        const NoSimulation formulaOnly;
        for (const double t : argument<std::vector<double>>(arguments, "times")) values.push_back(e.formula(parameters, t));
        return simlab::wire::toJson(values);
    });
    simlab::probe::add("answer", [](const nlohmann::json& arguments) {
        const Declaration declaration = declare();
        const Parameters parameters = resolve(declaration, argument<Settings>(arguments, "set"));
        const int before = simulationCount();
        const double value = answer(parameters);
        return simlab::wire::toJson(Answer{value, simulationCount() - before});
    });
}
