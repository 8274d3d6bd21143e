#include "biosim/program/course.h"

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

namespace {

/// Damping in proportion to the mass matrix: the generalized forces -rate M u, which take kinetic energy away at
/// twice `rate` whatever the model's masses and units.
class MassProportionalDamping : public SimTK::Force::Custom::Implementation {
public:
    MassProportionalDamping(const SimTK::SimbodyMatterSubsystem& matter, double rate) : matter_(matter), rate_(rate) {}
    void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>&, SimTK::Vector_<SimTK::Vec3>&,
                   SimTK::Vector& mobilityForces) const override {
        SimTK::Vector Mu;
        matter_.multiplyByM(state, state.getU(), Mu);
        mobilityForces -= rate_ * Mu;
    }
    SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0; }

private:
    const SimTK::SimbodyMatterSubsystem& matter_;
    double rate_;
};

/// Whether two values of a column differ by more than round-off.
bool differs(double a, double b) {
    if (std::isnan(a) || std::isnan(b)) return std::isnan(a) != std::isnan(b);
    return std::abs(a - b) > 1e-14 * std::max(std::abs(a), std::abs(b));
}

}  // namespace

void mutate(Model& model, const Mutation& mutation) {
    using namespace SimTK;
    if (mutation.gravityScale != 1) {
        for (int i = 0; i < model.forces.getNumForces(); ++i) {
            Force& force = model.forces.updForce(ForceIndex(i));
            if (Force::UniformGravity::isInstanceOf(force)) {
                Force::UniformGravity& g = Force::UniformGravity::updDowncast(force);
                g.setGravity(g.getGravity() * mutation.gravityScale);
            } else if (Force::Gravity::isInstanceOf(force)) {
                Force::Gravity& g = Force::Gravity::updDowncast(force);
                g.setDefaultMagnitude(g.getDefaultMagnitude() * mutation.gravityScale);
            }
        }
    }
    if (mutation.damping > 0) Force::Custom(model.forces, new MassProportionalDamping(model.matter, mutation.damping));
}

std::vector<ColumnTraits> columnTraits(const Declaration& declaration, const Parameters& parameters,
                                       const simlab::RunSettings& settings) {
    using namespace SimTK;
    simlab::validate(settings);
    Model model;
    buildModel(parameters, model);
    State state = initialState(parameters, model);
    std::unique_ptr<Integrator> integrator = simlab::integratorNamed(settings.integrator, model.system, settings.dt);
    integrator->setAccuracy(settings.accuracy);
    TimeStepper stepper(model.system, *integrator);
    stepper.initialize(state);

    const std::size_t columns = declaration.columns.size();
    std::vector<ColumnTraits> traits(columns);
    auto read = [&](const Parameters& p, const State& s) {
        model.system.realize(s, Stage::Dynamics);
        std::vector<double> row = sample(p, model, s);
        if (row.size() != columns) {
            throw std::runtime_error("sample() returned " + std::to_string(row.size()) + " values; the declaration has " +
                                     std::to_string(columns) + " columns");
        }
        return row;
    };
    auto compare = [&](const std::vector<double>& a, const std::vector<double>& b, bool ColumnTraits::*trait) {
        for (std::size_t c = 0; c < columns; ++c) {
            if (differs(a[c], b[c])) traits[c].*trait = true;
        }
    };
    // At t = 0 and a tenth of the way through the run: a column may be still at the start (a speed from rest).
    for (const double at : {0.0, settings.finalTime / 10}) {
        if (at > 0) stepper.stepTo(at);
        const State here = stepper.getState();
        const std::vector<double> row = read(parameters, here);
        const std::vector<double> again = read(parameters, here);
        for (std::size_t c = 0; c < columns; ++c) {
            if (differs(row[c], again[c])) traits[c].repeatable = false;
        }
        for (int i = 0; i < here.getNQ(); ++i) {
            State moved = here;
            moved.updQ()[i] += 1e-4 * std::max(1.0, std::abs(here.getQ()[i]));
            compare(row, read(parameters, moved), &ColumnTraits::state);
        }
        for (int i = 0; i < here.getNU(); ++i) {
            State moved = here;
            moved.updU()[i] += 1e-4 * std::max(1.0, std::abs(here.getU()[i]));
            compare(row, read(parameters, moved), &ColumnTraits::state);
        }
        State later = here;
        later.setTime(here.getTime() + std::max(1e-3, settings.finalTime / 100));
        compare(row, read(parameters, later), &ColumnTraits::time);
        for (const Parameter& p : declaration.parameters) {
            std::map<std::string, double> values = parameters.values();
            values[p.name] = p.value == parameters[p.name] ? movedValue(declaration, p) : p.value;
            compare(row, read(Parameters(values), here), &ColumnTraits::parameters);
        }
    }
    return traits;
}

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
    // The student's own Force::Custom elements, before a hook adds the course's (a mutant's damper).
    int studentCustomForces = 0;
    for (int i = 0; i < model.forces.getNumForces(); ++i) {
        if (Force::Custom::isInstanceOf(model.forces.getForce(ForceIndex(i)))) ++studentCustomForces;
    }
    if (hooks.afterBuild) hooks.afterBuild(model);
    State initial = initialState(parameters, model);
    if (hooks.initial) hooks.initial(initial);

    Observed observed;
    observed.model = simlab::describeModel(model.matter, initial);
    observed.auxiliaryStates = initial.getNZ();
    observed.addedSubsystems = model.system.getNumSubsystems() - courseSubsystems;
    observed.customForces = studentCustomForces;
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

    // The integrator returns at each of its own steps as well as at the samples (its steps are the same either
    // way), so that the energy is followed where the motion is computed, however far apart the samples are.
    integrator->setReturnEveryInternalStep(true);
    TimeStepper stepper(model.system, *integrator);
    stepper.setReportAllSignificantStates(true);  // the stepper hands each step back only with this set
    try {
        stepper.initialize(initial);
    } catch (const std::exception& e) {
        throw std::runtime_error("the integrator could not start from the initial state: " + simlab::oneLineMessage(e.what()));
    }
    record(stepper.getState());
    const double potential0 = observed.potential.front(), energy0 = observed.kinetic.front() + potential0;
    auto atStep = [&](const State& state) {
        if (std::isnan(observed.stepDrift)) return;
        model.system.realize(state, Stage::Dynamics);
        const double kinetic = model.system.calcKineticEnergy(state), potential = builtInPotentialEnergy(model, state);
        if (!std::isfinite(kinetic + potential)) {
            observed.stepDrift = NAN;
            return;
        }
        observed.stepExchanged = std::max({observed.stepExchanged, kinetic, std::abs(potential - potential0)});
        observed.stepDrift = std::max(observed.stepDrift, std::abs(kinetic + potential - energy0));
    };
    for (int k = 1; k <= settings.sampleCount(); ++k) {
        const double target = settings.sampleTime(k);
        try {
            while (true) {
                stepper.stepTo(target);
                if (hooks.afterStep) hooks.afterStep(*integrator);
                if (stepper.getState().getTime() >= target || integrator->isSimulationOver()) break;
                // A state interpolated between steps (a report time, the replay's frames) is not one the
                // integrator computed: counting its energy would make the figure depend on what else is watching.
                if (!integrator->isStateInterpolated()) atStep(stepper.getState());
            }
        } catch (const simlab::TooCostly&) {
            throw;
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
