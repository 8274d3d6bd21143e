// The course's side of a biosimulation project: checking a declaration, resolving --set values against it, and
// driving the student's model (the course owns the stepping loop, so that every project is sampled, timed and
// observed the same way). Used by the lab program and by the probe; the student's file never includes it.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "biosim/contract/Project.h"
#include "simlab/driver.h"
#include "simlab/model_info.h"

namespace biosim {

/// Throws std::invalid_argument, in one line, unless the declaration is usable: a program name, parameters with
/// valid unique names and finite ranges holding their defaults, at least one column, unique column names, claims
/// that name declared parameters and columns, and run settings that validate.
void checkDeclaration(const Declaration& declaration);

/// The declared defaults, changed by `changes`. A name that was not declared, a non-finite value or one outside
/// its range, or values that together break one of the declaration's rules, is std::invalid_argument in one line
/// naming it.
Parameters resolve(const Declaration& declaration, const std::map<std::string, double>& changes = {});

/// The meanings of the declaration's rules that `parameters` break (empty: they meet them all).
std::vector<std::string> brokenRules(const Declaration& declaration, const Parameters& parameters);

/// "NAME=VALUE" read as a change; anything else is std::invalid_argument in one line.
std::pair<std::string, double> parseSetting(const std::string& text);

/// The index of the declared column `name`; std::invalid_argument if there is none.
int columnIndex(const Declaration& declaration, const std::string& name);

/// What the course observes of one run: the student's rows, and beside them what the course reads from the
/// state itself (generalized coordinates and speeds, kinetic and potential energy from Simbody's own sums).
struct Observed {
    std::vector<double> time;
    std::vector<std::vector<double>> rows;  ///< sample()'s values, one per declared column
    std::vector<std::vector<double>> q;     ///< the state's generalized coordinates at each sample
    std::vector<std::vector<double>> u;     ///< and its generalized speeds
    std::vector<double> kinetic;            ///< J
    /// J: the potential energy of Simbody's own force elements in model.forces. A Force::Custom's is not counted:
    /// the student writes it, and a potential written to match could hide a damper from the energy test.
    std::vector<double> potential;
    simlab::ModelInfo model;
    int auxiliaryStates = 0;  ///< z variables (a Measure's, a Force's): state the mobilities do not show
    int customForces = 0;     ///< Force::Custom elements in model.forces
    int addedSubsystems = 0;  ///< subsystems buildModel added beside the course's matter and forces
    simlab::IntegratorStats integrator;
    /// J, over the integrator's own steps between the samples, which alone can miss the largest exchange of
    /// energy, or a change of it, when they are far apart: the largest kinetic energy or change of potential
    /// energy, and the largest |E - E(0)| (NaN where the energy was not finite). energyBalance counts them.
    double stepExchanged = 0;
    double stepDrift = 0;
};

/// Digits to which two runs of one model agree at their last samples, in every generalized coordinate and speed:
/// each q relative to the largest |q| of run `b` and each u to the largest |u|, so that one that stays at zero is
/// measured against the motion, never against its own round-off.
double agreementDigits(const Observed& a, const Observed& b);

/// The mechanical energy over a run, measured where a relative error means something: its largest departure from
/// the value at t = 0, against the energy the motion exchanges (the largest kinetic energy or change of potential
/// energy in the run), both over the samples and the integrator's steps between them.
struct EnergyBalance {
    double initial = 0;    ///< J, kinetic plus potential at t = 0
    double drift = 0;      ///< J, the largest |E(t) - E(0)|
    double exchanged = 0;  ///< J, the scale
};

inline EnergyBalance energyBalance(const Observed& run) {
    EnergyBalance b;
    if (run.time.empty()) return b;
    b.initial = run.kinetic.front() + run.potential.front();
    for (std::size_t k = 0; k < run.time.size(); ++k) {
        b.exchanged = std::max({b.exchanged, run.kinetic[k], std::abs(run.potential[k] - run.potential.front())});
        b.drift = std::max(b.drift, std::abs(run.kinetic[k] + run.potential[k] - b.initial));
    }
    if (std::isnan(run.stepExchanged) || std::isnan(run.stepDrift)) {
        b.drift = NAN;  // the energy broke between samples: no figure stands
    } else {
        b.exchanged = std::max(b.exchanged, run.stepExchanged);
        b.drift = std::max(b.drift, run.stepDrift);
    }
    return b;
}

/// A change the grader makes to a student's model to see whether an experiment can fail on it (a mutant): its
/// motion damped, its gravity scaled, its start moved. An experiment that holds on the model and on every mutant
/// cannot fail, and so shows nothing.
struct Mutation {
    double damping = 0;       ///< 1/s: every generalized speed damped at this rate, in proportion to the mass matrix
    double gravityScale = 1;  ///< Simbody's own gravity elements (UniformGravity, Gravity) scaled by this
    double nudge = 0;         ///< every generalized coordinate moved by this much at t = 0 (rad or m)
};

/// Applies the damping and the gravity of `mutation` to a model just built (before its topology is realized).
void mutate(Model& model, const Mutation& mutation);

/// What a column of sample() depends on, found by sampling states the course changes one thing at a time: each
/// generalized coordinate, each speed, the time alone, each parameter alone (sample() given other values for the
/// same state), and the same state twice.
struct ColumnTraits {
    bool repeatable = true;   ///< the same state gives the same value
    bool state = false;       ///< moves when a coordinate or a speed does
    bool time = false;        ///< moves when only the time does
    bool parameters = false;  ///< moves when only the parameters given to sample() do
};

/// The traits of every declared column, at t = 0 and a tenth of the way through the run `settings` describes.
std::vector<ColumnTraits> columnTraits(const Declaration& declaration, const Parameters& parameters,
                                       const simlab::RunSettings& settings);

/// The value of `p` as far from its default toward `target` as `allowed` lets it go: `target` itself if allowed,
/// else the boundary between them, found by halving the way back (the default is taken to be allowed).
double reachable(const Parameter& p, double target, const std::function<bool(double)>& allowed);

/// The value the grader moves `p` to, to see whether it changes anything: halfway from its default to the far
/// end of its range; where the declaration's rules stop it short of that (a moment of a thin plate sits on the
/// triangle inequality's edge), halfway to the near end if that goes farther.
double movedValue(const Parameter& p, const std::function<bool(double)>& allowed);

/// movedValue with the declaration's own rules (the other parameters at `others`, else at their defaults).
double movedValue(const Declaration& declaration, const Parameter& p, const std::map<std::string, double>& others = {});

/// Hooks for the lab program between the course's steps; each may be empty.
struct ObserveHooks {
    std::function<void(Model&)> afterBuild;  ///< e.g. attach a visualizer
    std::function<void(SimTK::State&)> initial;  ///< change the initial state (the grader nudges it)
    std::function<void(double time, const std::vector<double>& row)> onRow;
    /// After each step the integrator takes (a cost cap: what it throws, simlab::TooCostly, ends the run as it is).
    std::function<void(const SimTK::Integrator&)> afterStep;
    std::function<void()> afterRun;
};

/// Build the model for `parameters`, set its initial state, integrate with the integrator `settings` name at its
/// accuracy and sample at t = 0 and at every settings.sampleTime(k). A row of the wrong length, an integrator
/// failure or a non-finite value throws std::runtime_error saying where (the time and the column).
Observed observe(const Declaration& declaration, const Parameters& parameters, const simlab::RunSettings& settings,
                 const ObserveHooks& hooks = {});

/// How many times simulate() has run in this process (the grader asks whether answer() simulated).
int simulationCount();

/// While one lives, simulate() refuses to run: a formula an experiment checks a column against must be a formula,
/// not a copy of the run it is checked against.
class NoSimulation {
public:
    NoSimulation();
    ~NoSimulation();
    NoSimulation(const NoSimulation&) = delete;
    NoSimulation& operator=(const NoSimulation&) = delete;
};

}  // namespace biosim
