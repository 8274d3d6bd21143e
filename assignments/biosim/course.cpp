#include "biosim/course.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>

#include "simlab/integrators.h"
#include "simlab/messages.h"

namespace biosim {

namespace {

std::string show(double value) {
    std::ostringstream s;
    s.precision(6);
    s << value;
    return s.str();
}

int simulations = 0;
bool simulationRefused = false;

/// The potential energy of the force elements Simbody implements itself (gravity, springs, ...), never a
/// Force::Custom's, which is the student's own code.
double builtInPotentialEnergy(const Model& model, const SimTK::State& state) {
    double energy = 0;
    for (int i = 0; i < model.forces.getNumForces(); ++i) {
        const SimTK::Force& force = model.forces.getForce(SimTK::ForceIndex(i));
        if (SimTK::Force::Custom::isInstanceOf(force) || force.isDisabled(state)) continue;
        energy += force.calcPotentialEnergyContribution(state);
    }
    return energy;
}

}  // namespace

int simulationCount() { return simulations; }

NoSimulation::NoSimulation() { simulationRefused = true; }
NoSimulation::~NoSimulation() { simulationRefused = false; }

std::vector<double> Run::column(const std::string& name) const {
    const Declaration declaration = declare();
    const int index = columnIndex(declaration, name);
    std::vector<double> values;
    values.reserve(rows.size());
    for (const std::vector<double>& row : rows) values.push_back(row.at(static_cast<std::size_t>(index)));
    return values;
}

Run simulate(const Parameters& parameters, const simlab::RunSettings& settings) {
    if (simulationRefused) throw std::logic_error("a formula may not call simulate(): it must compute its value itself");
    ++simulations;
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
    const int courseSubsystems = model.system.getNumSubsystems();
    buildModel(parameters, model);
    if (hooks.afterBuild) hooks.afterBuild(model);
    State initial = initialState(parameters, model);
    if (hooks.initial) hooks.initial(initial);

    Observed observed;
    observed.model = simlab::describeModel(model.matter, initial);
    observed.auxiliaryStates = initial.getNZ();
    observed.addedSubsystems = model.system.getNumSubsystems() - courseSubsystems;
    for (int i = 0; i < model.forces.getNumForces(); ++i) {
        if (Force::Custom::isInstanceOf(model.forces.getForce(ForceIndex(i)))) ++observed.customForces;
    }
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
        observed.potential.push_back(builtInPotentialEnergy(model, state));
        observed.time.push_back(t);
        if (hooks.onRow) hooks.onRow(t, row);
        observed.rows.push_back(std::move(row));
    };

    TimeStepper stepper(model.system, *integrator);
    try {
        stepper.initialize(initial);
    } catch (const std::exception& e) {
        throw std::runtime_error("the integrator could not start from the initial state: " + simlab::oneLineMessage(e.what()));
    }
    record(stepper.getState());
    for (int k = 1; k <= settings.sampleCount(); ++k) {
        const double target = settings.sampleTime(k);
        try {
            stepper.stepTo(target);
        } catch (const std::exception& e) {
            throw std::runtime_error("the integrator failed between t = " + show(stepper.getState().getTime()) +
                                     " s and " + show(target) + " s: " + simlab::oneLineMessage(e.what()));
        }
        record(stepper.getState());
    }
    observed.integrator = simlab::statsOf(*integrator);
    if (hooks.afterRun) hooks.afterRun();
    return observed;
}

}  // namespace biosim
