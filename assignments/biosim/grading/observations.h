// What the grader observes of a student's project: the JSON forms of its declaration, its experiments, a run and
// its schematic (see simlab/wire.h). Shared by the probe, which answers, and the judge, which asks.
#pragma once

#include "biosim/contract/Project.h"
#include "biosim/program/course.h"
#include "biosim/program/schematic.h"
#include "simlab/wire_types.h"

namespace biosim {

SIMLAB_WIRE(Parameter, name, unit, value, min, max, meaning)
SIMLAB_WIRE(Column, name, unit, meaning, constant)
SIMLAB_WIRE(Conserved, column, when)
SIMLAB_WIRE(Claims, degreesOfFreedom, energyConserved, energyWhen, conserved, atRest)
SIMLAB_WIRE(Declaration, program, title, parameters, columns, claims, run)
SIMLAB_WIRE(Observed, time, rows, q, u, kinetic, potential, model, integrator, auxiliaryStates, customForces,
            addedSubsystems, stepExchanged, stepDrift)
SIMLAB_WIRE(ColumnTraits, repeatable, state, time, parameters)
SIMLAB_WIRE(Mutation, damping, gravityScale, nudge)
SIMLAB_WIRE(SchematicBody, name, index, parent, mass, com, moments, products, joint, dof, axes, jointLocation, origin,
            massCenter)
SIMLAB_WIRE(Schematic, title, bodies, degreesOfFreedom, constraints)

/// An experiment as data: everything but its formula, which only the student's process can evaluate.
struct ExperimentInfo {
    std::string name;
    std::string kind;
    std::string column;
    std::map<std::string, double> set;
    double finalTime = 0;
    double tolerance = 0;
    double period = 0;
    std::map<std::string, double> mirror;
    double sign = -1;
    bool hasFormula = false;
    double scale = 0;
};
SIMLAB_WIRE(ExperimentInfo, name, kind, column, set, finalTime, tolerance, period, mirror, sign, hasFormula, scale)

inline ExperimentInfo infoOf(const Experiment& e) {
    return {e.name, e.kind, e.column, e.set, e.finalTime, e.tolerance, e.period, e.mirror, e.sign,
            static_cast<bool>(e.formula), e.scale};
}

/// The answer to the project's question, as the program computes it.
struct Answer {
    double value = 0;
    int simulations = 0;  ///< runs of simulate() it took
};
SIMLAB_WIRE(Answer, value, simulations)

}  // namespace biosim
