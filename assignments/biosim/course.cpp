#include "biosim/course.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>

#include "simlab/integrators.h"

namespace biosim {

namespace {

std::string show(double value) {
    std::ostringstream s;
    s.precision(6);
    s << value;
    return s.str();
}

}  // namespace

std::vector<double> Run::column(const std::string& name) const {
    const Declaration declaration = declare();
    const int index = columnIndex(declaration, name);
    std::vector<double> values;
    values.reserve(rows.size());
    for (const std::vector<double>& row : rows) values.push_back(row.at(static_cast<std::size_t>(index)));
    return values;
}

Run simulate(const Parameters& parameters, const simlab::RunSettings& settings) {
    const Declaration declaration = declare();
    // The student's values are checked like the command line's: declared names, within their ranges.
    const Parameters checked = resolve(declaration, parameters.values());
    Observed observed = observe(declaration, checked, settings);
    return Run{std::move(observed.time), std::move(observed.rows)};
}

Observed observe(const Declaration& declaration, const Parameters& parameters, const simlab::RunSettings& settings,
                 const ObserveHooks& hooks) {
    using namespace SimTK;
    simlab::validate(settings);
    Model model;
    buildModel(parameters, model);
    if (hooks.afterBuild) hooks.afterBuild(model);
    const State initial = initialState(parameters, model);

    Observed observed;
    observed.model = simlab::describeModel(model.matter, initial);
    std::unique_ptr<Integrator> integrator = simlab::integratorNamed(settings.integrator, model.system, settings.dt);
    integrator->setAccuracy(settings.accuracy);
    if (settings.fixedStep) integrator->setFixedStepSize(settings.dt);

    const std::size_t columns = declaration.columns.size();
    auto record = [&](const State& state) {
        model.system.realize(state, Stage::Dynamics);
        std::vector<double> row = sample(parameters, model, state);
        const double t = state.getTime();
        if (row.size() != columns) {
            throw std::runtime_error("sample() returned " + std::to_string(row.size()) + " values at t = " + show(t) +
                                     " s; the declaration has " + std::to_string(columns) + " columns");
        }
        for (std::size_t i = 0; i < columns; ++i) {
            if (!std::isfinite(row[i])) {
                throw std::runtime_error(declaration.columns[i].name + " is " + show(row[i]) + " at t = " + show(t) +
                                         " s");
            }
        }
        auto listOf = [](const Vector& v) {
            std::vector<double> values(static_cast<std::size_t>(v.size()));
            for (int i = 0; i < v.size(); ++i) values[static_cast<std::size_t>(i)] = v[i];
            return values;
        };
        observed.q.push_back(listOf(state.getQ()));
        observed.u.push_back(listOf(state.getU()));
        observed.kinetic.push_back(model.system.calcKineticEnergy(state));
        observed.potential.push_back(model.system.calcPotentialEnergy(state));
        observed.time.push_back(t);
        if (hooks.onRow) hooks.onRow(t, row);
        observed.rows.push_back(std::move(row));
    };

    TimeStepper stepper(model.system, *integrator);
    stepper.initialize(initial);
    record(stepper.getState());
    for (int k = 1; k <= settings.sampleCount(); ++k) {
        const double target = settings.sampleTime(k);
        try {
            stepper.stepTo(target);
        } catch (const std::exception& e) {
            // Simbody's messages run over several lines: one line, and short.
            std::string what;
            for (const char c : std::string(e.what())) {
                const bool space = c == '\n' || c == '\t' || c == ' ';
                if (!space) what += c;
                else if (!what.empty() && what.back() != ' ') what += ' ';
            }
            if (what.size() > 240) what = what.substr(0, 240) + "...";
            throw std::runtime_error("the integrator failed between t = " + show(stepper.getState().getTime()) +
                                     " s and " + show(target) + " s: " + what);
        }
        record(stepper.getState());
    }
    observed.integrator = simlab::statsOf(*integrator);
    if (hooks.afterRun) hooks.afterRun();
    return observed;
}

}  // namespace biosim
