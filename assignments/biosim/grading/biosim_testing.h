// What the project's tests share: observing a student's project through the probe, reading its description, and
// measuring runs against one another. Every figure is computed here, in the judge, from observed data.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <toml++/toml.h>
#include <vector>

#include "biosim/grading/description.h"
#include "biosim/grading/observations.h"
#include "simlab/digits.h"
#include "simlab/harness/testing.h"

namespace biosim::testing {

namespace grading = simlab::grading;
namespace observe = simlab::observe;
using Settings = std::map<std::string, double>;

/// `base` with `changes` applied over it.
inline Settings merged(Settings base, const Settings& changes) {
    for (const auto& [name, value] : changes) base[name] = value;
    return base;
}

/// The student's declaration, checked as the lab program checks it (a bad one fails the test, saying why).
inline Declaration declared() {
    const Declaration d = observe::decode<Declaration>(observe::ask("declare", nlohmann::json::object()), "declare");
    try {
        checkDeclaration(d);
    } catch (const std::invalid_argument& e) {
        FAIL("the declaration is not usable: " << e.what());
    }
    return d;
}

/// A run of the student's model with `set` changed from the defaults, or of a mutant of it (course.h's Mutation:
/// damped, gravity scaled, every generalized coordinate moved by its nudge at t = 0).
inline Observed runWith(const Settings& set, const simlab::RunSettings& settings, const Mutation& mutation = {}) {
    Observed o = observe::decode<Observed>(observe::askShared("run", {{"set", simlab::wire::toJson(set)},
                                                                {"settings", simlab::wire::toJson(settings)},
                                                                {"mutation", simlab::wire::toJson(mutation)}}),
                                           "run");
    const std::size_t n = o.time.size();
    INFO("the run's lists have different lengths");
    REQUIRE(n > 0);
    REQUIRE((o.rows.size() == n && o.q.size() == n && o.u.size() == n && o.kinetic.size() == n &&
             o.potential.size() == n));
    return o;
}

/// A run with every generalized coordinate moved by `nudge` at t = 0.
inline Observed nudgedRun(const Settings& set, const simlab::RunSettings& settings, double nudge) {
    Mutation mutation;
    mutation.nudge = nudge;
    return runWith(set, settings, mutation);
}

/// Why the student's declaration refuses these values (a range, a rule), or "" if it takes them.
inline std::string refusal(const Settings& set) {
    const std::vector<std::string> why = observe::decode<std::vector<std::string>>(
        observe::ask("allowed", {{"set", simlab::wire::toJson(set)}}), "allowed");
    return why.empty() ? "" : why.front();
}

/// The value the grader moves parameter `p` to (course.h's movedValue), the others at `others`: the rules that
/// bound it are the student's, so each candidate is asked of the student's process, and checked there again when
/// it runs.
inline double movedValueOf(const Parameter& p, const Settings& others = {}) {
    return movedValue(p, [&](double value) { return refusal(merged(others, {{p.name, value}})).empty(); });
}

/// What each column depends on (course.h's ColumnTraits), for the default parameters and run settings.
inline std::vector<ColumnTraits> columnTraitsOf(const simlab::RunSettings& settings) {
    return observe::decode<std::vector<ColumnTraits>>(
        observe::ask("columns", {{"set", simlab::wire::toJson(Settings{})}, {"settings", simlab::wire::toJson(settings)}}),
        "columns");
}

/// Whether a column reads the model's state, as declared: "" if it does (or is declared constant and never
/// moves), else why not, in a few words.
inline std::string columnProblem(const Column& c, const ColumnTraits& t) {
    if (!t.repeatable) return "gives two values for one state: sample() keeps a state of its own";
    if (c.constant) {
        if (t.state) return "is declared constant but moves with the state";
        if (t.time) return "is declared constant but moves with the time";
        return "";
    }
    if (t.state) return "";
    if (t.time) return "is a function of time alone: it ignores the state";
    if (t.parameters) return "is a function of the parameters alone: it ignores the state";
    return "never moves: read it from the state, or declare it constant";
}

/// The columns of the declaration that are observations of the state, and one line about those that are not.
struct ColumnVerdict {
    int observed = 0;   ///< columns read from the state (not counting those declared constant)
    int good = 0;       ///< those, and the constant ones that are constant
    std::string problems;
    std::map<std::string, std::string> byColumn;  ///< the problem of each column that has one
};

inline ColumnVerdict columnVerdict(const Declaration& d) {
    // The columns are checked once per grading: what the student's process said is the same in every test.
    static std::optional<ColumnVerdict> known;
    if (known) return *known;
    const std::vector<ColumnTraits> traits = columnTraitsOf(d.run);
    ColumnVerdict v;
    for (std::size_t i = 0; i < d.columns.size() && i < traits.size(); ++i) {
        const std::string problem = columnProblem(d.columns[i], traits[i]);
        if (problem.empty()) {
            ++v.good;
            if (!d.columns[i].constant) ++v.observed;
        } else {
            v.problems += (v.problems.empty() ? "" : "; ") + d.columns[i].name + " " + problem;
            v.byColumn[d.columns[i].name] = problem;
        }
    }
    if (traits.size() != d.columns.size()) v.problems = "the course read " + std::to_string(traits.size()) + " columns";
    known = v;
    return v;
}

/// The checks of the model itself certify the model the project reports on only if some column reads its state.
inline void requireReportedModel(const Declaration& d) {
    const ColumnVerdict v = columnVerdict(d);
    if (v.observed == 0) {
        FAIL("no column of sample() reads the model's state (" << v.problems << "): the project reports nothing of "
             "the model these checks would certify");
    }
}

/// The course's own reading of what a column shows, where the column is one (a generalized coordinate or speed,
/// in its SI unit or in degrees, or the mechanical energy up to a constant): then experiments on it are judged
/// on the course's values. `what` names it; empty when the column is none of these.
struct Reading {
    std::vector<double> values;
    std::string what;
    double scale = 0;  ///< the physical scale it is measured against near a zero
};

inline Reading readingOf(const Observed& run, const std::vector<double>& column) {
    // The same values, to 1e-9 of `scale` (up to a constant where `offsetAllowed`).
    auto matches = [&](const std::vector<double>& candidate, bool offsetAllowed, double scale) {
        if (!(scale > 0) || candidate.size() != column.size()) return false;
        const double offset = offsetAllowed ? column.front() - candidate.front() : 0;
        for (std::size_t k = 0; k < column.size(); ++k) {
            if (!(std::abs(column[k] - candidate[k] - offset) <= 1e-9 * scale)) return false;
        }
        return true;
    };
    auto largest = [](const std::vector<double>& values) {
        double scale = 0;
        for (const double v : values) scale = std::max(scale, std::abs(v));
        return scale;
    };
    const double degree = 180 / M_PI;
    for (const auto& [values, name, unitScale] : {std::tuple{&run.q, "q", 1.0}, std::tuple{&run.u, "u", 1.0}}) {
        const std::size_t n = values->empty() ? 0 : values->front().size();
        for (std::size_t i = 0; i < n; ++i) {
            for (const double factor : {1.0, degree}) {
                std::vector<double> candidate;
                for (const auto& v : *values) candidate.push_back(i < v.size() ? factor * v[i] : NAN);
                if (matches(candidate, false, largest(candidate))) {
                    return {candidate, std::string(name) + "[" + std::to_string(i) + "]" + (factor > 1 ? " in degrees" : ""),
                            unitScale * factor};
                }
            }
        }
    }
    // The energy against the energy the motion exchanges: a total near zero (a release from rest at the zero of
    // the potential) is no scale. A column that never changes is not read as the energy, though a conserved energy
    // matches it up to a constant: a constant it stays.
    if (std::all_of(column.begin(), column.end(), [&](double v) { return v == column.front(); })) return {};
    std::vector<double> energy;
    for (std::size_t k = 0; k < run.kinetic.size(); ++k) energy.push_back(run.kinetic[k] + run.potential[k]);
    if (matches(energy, true, energyBalance(run).exchanged)) {
        const double offset = column.front() - energy.front();
        for (double& e : energy) e += offset;
        return {energy, "the mechanical energy", energyBalance(run).exchanged};
    }
    return {};
}

inline Schematic schematicWith(const Settings& set) {
    return observe::decode<Schematic>(observe::ask("schematic", {{"set", simlab::wire::toJson(set)}}), "schematic");
}

inline std::vector<ExperimentInfo> declaredExperiments() {
    return observe::decode<std::vector<ExperimentInfo>>(observe::ask("experiments", nlohmann::json::object()),
                                                        "experiments");
}

/// The column `index` of a run, one value per sample.
inline std::vector<double> columnOf(const Observed& o, std::size_t index) {
    std::vector<double> values;
    for (const auto& row : o.rows) values.push_back(index < row.size() ? row[index] : NAN);
    return values;
}

/// Largest magnitude of a list; 1 if every value is zero (so that "relative to it" stays defined).
inline double scaleOf(const std::vector<double>& values) {
    double scale = 0;
    for (const double v : values) scale = std::max(scale, std::abs(v));
    return scale > 0 ? scale : 1.0;
}

/// Largest |a[k] - b[k]| over a list of vectors (the state's q or u at every sample).
inline double largestDifference(const std::vector<std::vector<double>>& a, const std::vector<std::vector<double>>& b) {
    double largest = 0;
    for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) {
        if (a[k].size() != b[k].size()) return INFINITY;
        for (std::size_t i = 0; i < a[k].size(); ++i) largest = std::max(largest, std::abs(a[k][i] - b[k][i]));
    }
    return a.size() == b.size() ? largest : INFINITY;
}

/// Largest |value| over a list of vectors; 1 if every value is zero (so that "relative to it" stays defined).
inline double largestMagnitude(const std::vector<std::vector<double>>& values) {
    double largest = 0;
    for (const auto& v : values) {
        for (const double x : v) largest = std::max(largest, std::abs(x));
    }
    return largest > 0 ? largest : 1.0;
}

/// Largest departure of every q and u from its value at t = 0.
inline double largestDrift(const std::vector<std::vector<double>>& values) {
    double largest = 0;
    for (const auto& v : values) {
        for (std::size_t i = 0; i < v.size() && i < values.front().size(); ++i) {
            largest = std::max(largest, std::abs(v[i] - values.front()[i]));
        }
    }
    return largest;
}

/// The run settings the declaration asks for, with another final time if `finalTime` > 0.
inline simlab::RunSettings settingsFor(const Declaration& d, double finalTime = 0) {
    simlab::RunSettings s = d.run;
    if (finalTime > 0) {
        s.finalTime = finalTime;
        s.dt = std::min(s.dt, finalTime);
    }
    return s;
}

/// The student's description, project.toml; a file that is not TOML fails the test, saying where.
inline toml::table description() {
    const std::string path = grading::submissionFile("project.toml");
    try {
        return toml::parse_file(path);
    } catch (const toml::parse_error& e) {
        FAIL("project.toml is not valid TOML: " << e.description() << " (line " << e.source().begin.line << ")");
    }
    return {};
}

}  // namespace biosim::testing
