// The end of biosim's precompiled header (cmake/Simlab.cmake, after simlab/pch.h): the project contract, and the
// templates every project file instantiates with its types (the declaration's lists, the parameters and bodies
// by name, the experiments), instantiated once per build rather than at each compile.
#pragma once

#include "biosim/Project.h"

namespace biosim::precompiled {
inline void uses(Model& model, const SimTK::State& state) {
    Declaration d;
    d.parameters = {{"m", "kg", 1, 0, 2, "a mass"}, {"q", "deg", 0, -180, 180, "an angle"}};
    d.rules = {{"a rule", [](const Parameters& p) { return p["m"] <= 2 * p["q"]; }}};
    d.columns = {{"q", "deg", "an angle"}, {"energy", "J", "the energy"}};
    d.claims.atRest = {{"g", 0}};
    std::map<std::string, double> values;
    for (const Parameter& parameter : d.parameters) values[parameter.name] = parameter.value;
    const Parameters p(values);
    model.bodies["A"] = model.body("B");
    const std::vector<double> row = {p["q"], model.system.calcEnergy(state)};
    const std::vector<Experiment> list = {
        conserved("c", "energy").with({{"q", 60}}).within(1e-6),
        periodic("p", "q", 1.0).with({{"q", 60}}).until(2),
        matches("m", "q", [](const Parameters& p, double t) { return p["q"] * std::cos(t); }).against(1),
        symmetric("s", "q", {{"q", -90}}),
        atRest("r"),
    };
    const Run run = simulate(p, d.run);
    (void)(run.column("q").size() + row.size() + list.size());
}
}  // namespace biosim::precompiled
