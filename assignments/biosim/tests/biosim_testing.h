// What the project's tests share: observing a student's project through the probe, reading its description, and
// measuring runs against one another. Every figure is computed here, in the judge, from observed data.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <toml++/toml.h>
#include <vector>

#include "biosim/observations.h"
#include "simlab/digits.h"
#include "simlab/testing.h"

namespace biosim::testing {

namespace grading = simlab::grading;
namespace observe = simlab::observe;
using Settings = std::map<std::string, double>;

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

/// A run of the student's model with `set` changed from the defaults, and every generalized coordinate moved by
/// `nudge` at t = 0.
inline Observed runWith(const Settings& set, const simlab::RunSettings& settings, double nudge = 0) {
    Observed o = observe::decode<Observed>(observe::ask("run", {{"set", simlab::wire::toJson(set)},
                                                                {"settings", simlab::wire::toJson(settings)},
                                                                {"nudge", nudge}}),
                                           "run");
    const std::size_t n = o.time.size();
    INFO("the run's lists have different lengths");
    REQUIRE(n > 0);
    REQUIRE((o.rows.size() == n && o.q.size() == n && o.u.size() == n && o.kinetic.size() == n &&
             o.potential.size() == n));
    return o;
}

inline Schematic schematicWith(const Settings& set) {
    return observe::decode<Schematic>(observe::ask("schematic", {{"set", simlab::wire::toJson(set)}}), "schematic");
}

inline std::vector<ExperimentInfo> declaredExperiments() {
    return observe::decode<std::vector<ExperimentInfo>>(observe::ask("experiments", nlohmann::json::object()),
                                                        "experiments");
}

/// `base` with `changes` applied over it.
inline Settings merged(Settings base, const Settings& changes) {
    for (const auto& [name, value] : changes) base[name] = value;
    return base;
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

/// Words in a text (runs of letters or digits).
inline int wordCount(const std::string& text) {
    int words = 0;
    bool inWord = false;
    for (const char c : text) {
        const bool letter = std::isalnum(static_cast<unsigned char>(c)) != 0;
        if (letter && !inWord) ++words;
        inWord = letter;
    }
    return words;
}

/// True if a text is still the template's placeholder.
inline bool isPlaceholder(const std::string& text) { return text.find("TODO") != std::string::npos; }

}  // namespace biosim::testing
