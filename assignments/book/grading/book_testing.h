// What the book's visible and hidden tests share: the three spins, measurements on a student's own output, and
// their answers file.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <toml++/toml.h>
#include <vector>

#include "book/contract/BookSpin.h"
#include "book/program/exact.h"
#include "book/grading/observations.h"
#include "book/program/run_plot.h"
#include "simlab/harness/testing.h"

namespace book::testing {

namespace grading = simlab::grading;
using namespace simlab::testing;
using Run = simlab::RunResult<Sample>;

/// A vector's components for a message, "7, 0.2, 0.2" (SimTK's own << writes "~[7,0.2,0.2]").
inline std::string components(const SimTK::Vec3& v) {
    char text[96];
    std::snprintf(text, sizeof text, "%.9g, %.9g, %.9g", v[0], v[1], v[2]);
    return text;
}

inline Run simulate(const Scene& scene, const simlab::RunSettings& settings = defaultRunSettings()) {
    return simlab::testing::simulate<Sample>(scene, settings);
}

/// The student's simulation of `scene` with the lab's settings, checked to reach their final time: what a test
/// measures over the samples must cover the whole run.
inline Run simulateWhole(const Scene& scene) {
    Run run = simulate(scene);
    lastSample(run, defaultRunSettings().finalTime);
    return run;
}

/// The trade question (tests/trade-question.json): the scene it is asked on, the digits, and the front.
inline const simlab::trade::Question& tradeQuestion() {
    static const simlab::trade::Question question = simlab::trade::parseQuestion(
#include "trade_question.inc"
        , "the book's trade-question.json");
    return question;
}

/// What the trade question counts of a sample of a spin: the digits of w_B against Euler's equations in long
/// double, integrated once for the scene.
inline std::function<double(const Sample&)> tradeDigits(const Scene& scene, double) {
    auto reference = std::make_shared<simlab::OdeReference<3>>(exact::eulerReference(scene));
    return [scene, reference](const Sample& s) { return exact::spinDigits(scene, s.w_B, reference->at(s.time)); };
}

inline simlab::RunSettings settingsFor(double finalTime, double dt, double accuracy = 1e-10) {
    return simlab::testing::settingsFor(defaultRunSettings(), finalTime, dt, accuracy);
}

/// The book's mass properties in the student's model of `scene`.
inline MassObservation massProperties(const Scene& scene) {
    return simlab::observe::decode<MassObservation>(
        simlab::observe::ask("massProperties", {{"scene", simlab::wire::toJson(scene)}}), "massProperties");
}

/// `scene` spun about its "min", "intermediate" or "max" axis at `rate`, with the lab's 0.2 rad/s wobble.
inline Scene spun(Scene scene, const std::string& axis, double rate = 7.0) {
    scene.w_B0 = exact::spin(scene, axis, rate);
    return scene;
}

inline const std::vector<std::string>& axisNames() {
    static const std::vector<std::string> names = {"min", "intermediate", "max"};
    return names;
}

/// A vector as a comparison takes it.
inline std::vector<double> values(const SimTK::Vec3& v) { return {v[0], v[1], v[2]}; }

/// Digits of w_B at the last sample against the exact solution, and the two vectors.
inline WorstDigits finalDigits(const Scene& scene, const Run& run) {
    const Sample& last = lastSample(run, defaultRunSettings().finalTime);
    WorstDigits digits;
    digits.add(exact::angularVelocityDigits(scene, last.time, last.w_B),
               grading::compared(grading::at("w_B", last.time), values(last.w_B),
                                 values(exact::angularVelocity(scene, last.time)), "rad/s"));
    return digits;
}

/// The largest change of f over the run, relative to the size of its first value.
template <class F>
double relativeChange(const Run& run, F f) {
    requireSamples(run);
    const SimTK::Vec3 first(f(run.samples.front()));
    double worst = 0;
    for (const Sample& s : run.samples) {
        const double change = exact::magnitude(SimTK::Vec3(f(s)) - first);
        worst = std::isnan(change) ? INFINITY : std::max(worst, change);
    }
    return worst / exact::magnitude(first);
}

/// relativeChange(), kept with the sample where the change was largest: `name` there against its first value, in
/// `unit`, `components` of them (1 for a number, 3 for a vector).
template <class F>
WorstDrift driftOf(const Run& run, F f, const std::string& name, const std::string& unit, int components) {
    requireSamples(run);
    const SimTK::Vec3 first(f(run.samples.front()));
    const double size = exact::magnitude(first);
    auto shown = [components](const SimTK::Vec3& v) {
        return components == 1 ? std::vector<double>{v[0]} : values(v);
    };
    WorstDrift drift;
    for (const Sample& s : run.samples) {
        const SimTK::Vec3 now(f(s));
        const double change = exact::magnitude(now - first);
        drift.add((std::isnan(change) ? INFINITY : change) / size,
                  grading::compared(grading::at(name, s.time), shown(now), shown(first), unit) +
                      " (its value at t = 0)");
    }
    return drift;
}

/// The student's answers file, BookAnswers.toml: each section's values as written.
struct Answers {
    std::map<std::string, std::string> conserved;  // quantity -> "yes" / "no"
    std::map<std::string, std::string> stability;  // minimum, intermediate, maximum -> "stable" / ...
};

inline Answers readAnswers() {
    const std::string path = grading::submissionFile("BookAnswers.toml");
    toml::table file;
    try {
        file = toml::parse_file(path);
    } catch (const toml::parse_error& e) {
        FAIL("BookAnswers.toml is not valid TOML: " << e.description());
    }
    Answers answers;
    for (const auto& [section, into] : {std::pair<const char*, std::map<std::string, std::string>*>{"conserved", &answers.conserved},
                                        {"stability", &answers.stability}}) {
        if (const toml::table* table = file[section].as_table()) {
            for (auto&& [key, value] : *table) (*into)[std::string(key.str())] = value.value_or(std::string("(not text)"));
        }
    }
    return answers;
}

/// "6 of 9 right; no readable answer for Hx, Hy (write yes or no)".
inline std::string countLine(int right, std::size_t of, const std::vector<std::string>& unreadable,
                             const std::string& choices) {
    std::string line = std::to_string(right) + " of " + std::to_string(of) + " right";
    if (!unreadable.empty()) {
        line += "; no readable answer for ";
        for (std::size_t i = 0; i < unreadable.size(); ++i) line += (i ? ", " : "") + unreadable[i];
        line += " (write " + choices + ")";
    }
    return line;
}

/// The words a stability answer may be, as a message says them: what the whole motion does, which a linear analysis
/// ("neutrally stable") does not decide.
inline std::string stabilityWords() { return "stable or unstable, for the whole motion, not its linearization"; }

/// The quantities the answers file asks about, and how to read each from a sample.
inline const std::vector<std::pair<std::string, SimTK::Vec3 (*)(const Sample&)>>& quantities() {
    static const std::vector<std::pair<std::string, SimTK::Vec3 (*)(const Sample&)>> all = {
        {"wx", [](const Sample& s) { return SimTK::Vec3(s.w_B[0], 0, 0); }},
        {"wy", [](const Sample& s) { return SimTK::Vec3(s.w_B[1], 0, 0); }},
        {"wz", [](const Sample& s) { return SimTK::Vec3(s.w_B[2], 0, 0); }},
        {"K", [](const Sample& s) { return SimTK::Vec3(s.kineticEnergy, 0, 0); }},
        {"Hx", [](const Sample& s) { return SimTK::Vec3(s.H_B[0], 0, 0); }},
        {"Hy", [](const Sample& s) { return SimTK::Vec3(s.H_B[1], 0, 0); }},
        {"Hz", [](const Sample& s) { return SimTK::Vec3(s.H_B[2], 0, 0); }},
        {"Hmag", [](const Sample& s) { return SimTK::Vec3(s.Hmag, 0, 0); }},
        {"HG", [](const Sample& s) { return s.H_G; }}};
    return all;
}

/// How the wobble behaves in a run spun about `axis`: whether the spin component changes sign, and the
/// largest size the other two reach.
struct Wobble {
    bool spinReverses = false;
    double largestWobble = 0;  // rad/s
};

inline Wobble wobbleOf(const Scene& scene, const std::string& axis, const Run& run) {
    const std::array<int, 3> order = exact::axesByMoment(scene);
    const int spin = order[axis == "min" ? 0 : axis == "intermediate" ? 1 : 2];
    Wobble w;
    for (const Sample& s : run.samples) {
        w.spinReverses = w.spinReverses || s.w_B[spin] * scene.w_B0[spin] < 0;
        for (int i = 0; i < 3; ++i) {
            if (i != spin) w.largestWobble = std::max(w.largestWobble, std::abs(s.w_B[i]));
        }
    }
    return w;
}

}  // namespace book::testing
