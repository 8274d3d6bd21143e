// A biosimulation project: the contract between a student's own Project.cpp and the course.
//
// Your project is a multibody model of your own choosing. You describe it to the course in code, here, and in
// words, in project.toml beside it. The course's lab program, the self-check and the grader all call the
// functions below:
//
//     declare                      what the model is: its parameters, the columns it samples, what you claim
//     buildModel -> initialState   the model for a set of parameter values, and its state at t = 0
//     sample                       one row of results, read from a state (the course steps the integrator)
//     experiments                  your own checks of the model, each named in project.toml
//     answer                       the number that answers your project's question
//
// The course varies the parameters within the ranges you declare, switches gravity and motion off, tightens the
// accuracy, and compares what your model does with what you claim. Nothing may be hard-wired: a number that
// could change belongs in a parameter, read with p["name"]. Do not edit this header.
//
// Frames and names, as in the labs: G is Ground, the Newtonian frame, with y up; a body's name is its letter
// (A, B, ...); p_GA is the position of A's origin from G's origin, expressed in G. SI units throughout, except
// where a parameter's unit says otherwise (angles are given in degrees and converted by you).
#pragma once

#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "Simbody.h"
#include "simlab/multibody_model.h"
#include "simlab/run_settings.h"

namespace biosim {

class Parameters;

/// One quantity the model is built from, settable on the command line as --set name=value.
struct Parameter {
    std::string name;     ///< a letter, then letters, digits or _ (e.g. "mA")
    std::string unit;     ///< "kg", "m", "kg m^2", "deg", "rad/s", "m/s^2", "1", ...
    double value = 0;     ///< the default
    double min = 0;       ///< the allowed range, min <= value <= max: every value in it must simulate
    double max = 0;
    std::string meaning;  ///< one line, e.g. "mass of the rod A"
};

/// One sampled quantity: a column of the results file (after `time`, which the course adds). sample() reads it
/// from the state: the grader checks that it moves when the state does (and is the same for the same state), or,
/// for a column declared constant (a total mass, a parameter shown beside the motion), that it never moves.
struct Column {
    std::string name;  ///< e.g. "qA"
    std::string unit;  ///< e.g. "deg"
    std::string meaning;
    bool constant = false;  ///< true for a column that does not depend on the state
};

/// A condition the parameters must meet together, beyond each one's range: a rigid body's central moments obey
/// the triangle inequality, say, so its three moments cannot be chosen one by one. --set and the grader respect
/// it: a combination that breaks it is refused, naming it, and the grader tries each range as far as it allows.
struct Rule {
    std::string meaning;  ///< one line, e.g. "B's moments: each at most the sum of the other two"
    std::function<bool(const Parameters&)> holds;
};

/// A column that keeps its value at t = 0 for the whole run, when the parameters take the values in `when`
/// (the others keep their defaults).
struct Conserved {
    std::string column;
    std::map<std::string, double> when;
};

/// What you claim about the model. The grader checks each claim.
struct Claims {
    int degreesOfFreedom = 0;  ///< the motions the scene requires (the model must have exactly these)
    bool energyConserved = false;              ///< no dissipation: the mechanical energy keeps its value ...
    std::map<std::string, double> energyWhen;  ///< ... when the parameters take these values
    std::vector<Conserved> conserved;          ///< further columns that keep their value
    /// Parameter values with no gravity, no other forces and no initial motion: the model must stay at rest, from
    /// its initial configuration and from one nearby (the grader moves every coordinate a little).
    std::map<std::string, double> atRest;
};

/// The whole declaration of a project.
struct Declaration {
    std::string program;                ///< the lab program's name, e.g. "babyboot"
    std::string title;                  ///< one line
    std::vector<Parameter> parameters;
    std::vector<Rule> rules;            ///< conditions on several parameters at once (may be empty)
    std::vector<Column> columns;        ///< what sample() returns, in this order
    Claims claims;
    simlab::RunSettings run;            ///< the defaults: integrator, accuracy, dt, final time
};

/// The value of every declared parameter, by name.
class Parameters {
public:
    Parameters() = default;
    explicit Parameters(std::map<std::string, double> values) : values_(std::move(values)) {}

    /// The value of `name`; a name that was not declared is an error that names it.
    double operator[](const std::string& name) const {
        const auto found = values_.find(name);
        if (found == values_.end()) throw std::out_of_range("no parameter named '" + name + "' was declared");
        return found->second;
    }
    const std::map<std::string, double>& values() const { return values_; }

private:
    std::map<std::string, double> values_;
};

/// The Simbody model. The course makes the system and its subsystems; buildModel adds the bodies to `matter`,
/// each also kept in `bodies` under the name project.toml's schematic gives it, and the forces to `forces`.
struct Model : simlab::MultibodyModel {
    std::map<std::string, SimTK::MobilizedBody> bodies;  ///< e.g. bodies["A"]

    /// The body of that name; an unknown name is an error that names it.
    const SimTK::MobilizedBody& body(const std::string& name) const {
        const auto found = bodies.find(name);
        if (found == bodies.end()) throw std::out_of_range("the model has no body named '" + name + "'");
        return found->second;
    }
};

/// One of your own numerical experiments: a run of the model (with `set` changed from the defaults) and what
/// its column must do. Make one with the functions below and adjust it with the chained setters:
///
///     conserved("the plate's spin is constant without gravity", "uB").with({{"g", 0}}).within(1e-9)
struct Experiment {
    std::string name;    ///< as project.toml's [[experiment]] names it
    std::string kind;    ///< "conserved", "at rest", "periodic", "symmetric" or "formula"
    std::string column;  ///< the column it is about ("" for "at rest": the course checks every speed)
    std::map<std::string, double> set;     ///< parameter values for this run; the others keep their defaults
    double finalTime = 0;                  ///< s; 0 for the declaration's final time
    double tolerance = 1e-6;               ///< allowed error, relative to the column's largest magnitude
    double scale = 0;                      ///< what errors are measured against instead (0: that magnitude)
    double period = 0;                     ///< s, for "periodic": the column repeats after this time
    std::map<std::string, double> mirror;  ///< for "symmetric": the mirrored run's values ...
    double sign = -1;                      ///< ... whose column is `sign` times this one's at every sample
    std::function<double(const Parameters&, double t)> formula;  ///< for "formula": the column's exact value

    Experiment& with(std::map<std::string, double> values) {
        for (auto& [name, value] : values) set[name] = value;
        return *this;
    }
    Experiment& until(double seconds) {
        finalTime = seconds;
        return *this;
    }
    Experiment& within(double relativeError) {
        tolerance = relativeError;
        return *this;
    }
    /// Errors relative to `columnScale` (in the column's unit), for a column that starts at or passes near zero,
    /// where its own magnitude is no scale: a momentum that starts at zero, say, against m times a typical speed.
    Experiment& against(double columnScale) {
        scale = columnScale;
        return *this;
    }
};

/// The column keeps its value at t = 0.
inline Experiment conserved(std::string name, std::string column) {
    Experiment e;
    e.name = std::move(name);
    e.kind = "conserved";
    e.column = std::move(column);
    return e;
}

/// Every generalized speed stays zero (tolerance in rad/s or m/s) and every coordinate keeps its value.
inline Experiment atRest(std::string name) {
    Experiment e;
    e.name = std::move(name);
    e.kind = "at rest";
    return e;
}

/// The column at time `period` equals its value at t = 0 (the run lasts one period unless until() says more).
inline Experiment periodic(std::string name, std::string column, double period) {
    Experiment e;
    e.name = std::move(name);
    e.kind = "periodic";
    e.column = std::move(column);
    e.period = period;
    return e;
}

/// A second run with `mirror` changed too gives the column times `sign` (-1: the motion is mirrored).
inline Experiment symmetric(std::string name, std::string column, std::map<std::string, double> mirror,
                            double sign = -1) {
    Experiment e;
    e.name = std::move(name);
    e.kind = "symmetric";
    e.column = std::move(column);
    e.mirror = std::move(mirror);
    e.sign = sign;
    return e;
}

/// The column follows formula(parameters, t) at every sample.
inline Experiment matches(std::string name, std::string column,
                          std::function<double(const Parameters&, double t)> formula) {
    Experiment e;
    e.name = std::move(name);
    e.kind = "formula";
    e.column = std::move(column);
    e.formula = std::move(formula);
    return e;
}

/// One run of a model as the course drives it, for answer() to use: the sample times and, for each, the row
/// sample() returned.
struct Run {
    std::vector<double> time;
    std::vector<std::vector<double>> rows;

    /// The column of that name, one value per sample.
    std::vector<double> column(const std::string& name) const;
};

/// Simulate your model with these parameter values and run settings, exactly as the lab program does. Written
/// by the course; call it from answer().
Run simulate(const Parameters& parameters, const simlab::RunSettings& settings);

// ---- What you write, in Project.cpp -------------------------------------------------------------------------

/// The declaration of your project (called first, and often: keep it cheap and the same every time).
Declaration declare();

/// Add your bodies (each also in model.bodies) and forces for these parameter values. Do not realize the
/// topology here.
void buildModel(const Parameters& p, Model& model);

/// Realize the topology and return the state at t = 0 for these parameter values.
SimTK::State initialState(const Parameters& p, const Model& model);

/// One row of results: a value for each declared column, in order, read from `state`.
std::vector<double> sample(const Parameters& p, const Model& model, const SimTK::State& state);

/// Your own numerical experiments, each named in project.toml.
std::vector<Experiment> experiments();

/// The number that answers your project's question (project.toml's [question]), computed by simulating.
double answer(const Parameters& p);

}  // namespace biosim
