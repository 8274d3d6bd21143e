// A lab's trade question, as its data file states it (assignments/<lab>/grading/trade-question.json, and the hidden
// variants in trade-hidden.json): the scenes it is asked on - never the handout's worked example -, the digits it
// asks for, the integrators it allows, and for each scene the work-precision front it is graded against.
//
// The front is what `simlab study trade LAB --fronts` measured on the reference solution: every integrator at
// every accuracy and fixed step, each point from `starts` starts (the scene's number at `nudge` moved by 0, 1, 2 ...
// units in its last place), kept at its worst (the fewest digits, the most evaluations), then the points no
// cheaper point matches in digits. A setting that lands well from one start and badly from the next - a fragile
// point - counts at its worst, in the front and in a student's answer alike.
#pragma once

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "simlab/work_precision.h"

namespace simlab::trade {

/// One scene the question is asked on.
struct Scene {
    std::string name;         ///< "question", or a hidden variant's name
    nlohmann::json scene;     ///< the lab's Scene, as its wire form has it
    double finalTime = 0;     ///< s
    std::vector<work_precision::Point> front;  ///< (digits, evaluations), in order of cost
};

struct Question {
    std::string lab;
    double digits = 0;                     ///< kept at every step of the run, the worst step's
    std::vector<std::string> integrators;  ///< the integrators the question allows (empty: any)
    bool fixedStepOnly = false;            ///< the question asks for a fixed step
    std::string nudge;                     ///< JSON pointer to the number a start moves, e.g. "/dropHeight"
    int starts = 1;                        ///< starts each setting is measured from
    std::vector<Scene> scenes;
    /// A pool of other scenes with their fronts, for a rubric that gives each student a scene of their own
    /// (its [variants] table): variantFor picks one from the student's id.
    std::vector<Scene> variants;
};

/// FNV-1a (64 bits) of `text`: the same on every machine and build, unlike std::hash.
inline std::uint64_t fnv1a(const std::string& text) {
    std::uint64_t h = 14695981039346656037ULL;
    for (const unsigned char c : text) {
        h ^= c;
        h *= 1099511628211ULL;
    }
    return h;
}

/// Which of `count` variants is the student's: the hash of the course's seed and their id. A NUL between them
/// keeps "ab"+"c" and "a"+"bc" apart.
inline std::size_t variantIndex(const std::string& seed, const std::string& student, std::size_t count) {
    if (count == 0) return 0;
    return static_cast<std::size_t>(fnv1a(seed + std::string(1, '\0') + student) % count);
}

/// The scene `student` answers the question on: their variant when the course gives each student their own
/// (`perStudent`, an id and a pool to pick from), else the question's scene.
inline const Scene& sceneFor(const Question& q, bool perStudent, const std::string& seed, const std::string& student) {
    if (!perStudent || student.empty() || q.variants.empty()) return q.scenes.at(0);
    return q.variants.at(variantIndex(seed, student, q.variants.size()));
}

/// The scene of start `k` (0, 1, ...): the number at `pointer` moved up by k units in its last place.
inline nlohmann::json nudged(nlohmann::json scene, const std::string& pointer, int k) {
    if (pointer.empty() || k == 0) return scene;
    const nlohmann::json::json_pointer at(pointer);
    double value = scene.at(at).get<double>();
    for (int i = 0; i < k; ++i) value = std::nextafter(value, INFINITY);
    scene[at] = value;
    return scene;
}

/// Whether `integrator` (at a fixed step or not) answers `q` at all.
inline bool allows(const Question& q, const std::string& integrator, bool fixedStep) {
    if (q.fixedStepOnly && !fixedStep) return false;
    if (q.integrators.empty()) return true;
    for (const std::string& name : q.integrators) {
        if (name == integrator) return true;
    }
    return false;
}

/// What the front says of an answer that keeps `digits` (at least the `asked` ones) for `evaluations`.
struct Score {
    double readAt = 0;     ///< the digits the front is read at: those kept, counted up to `beyond` past those asked
    double frontCost = 0;  ///< the front's cost there (its dearest point's, past its end)
    double ratio = 0;      ///< evaluations / frontCost
    double credit = 0;     ///< 1 up to fullWithin, falling with log(ratio) to 0 at nonePast
};

/// The answer's score against `front` (frontOf's): full credit up to `fullWithin` times the front's cost at the digits
/// it keeps, less in proportion to the logarithm of the ratio up to `nonePast` times, nothing beyond. Digits kept
/// past `beyond` more than asked count as `asked + beyond`: more than that, nobody asked for.
inline Score score(const std::vector<work_precision::Point>& front, double asked, double digits, double evaluations,
                   double beyond, double fullWithin, double nonePast) {
    Score s;
    s.readAt = std::min(digits, asked + beyond);
    const std::optional<work_precision::Reading> r = work_precision::costAt(front, s.readAt);
    s.frontCost = r ? r->cost : front.empty() ? 0 : front.back().cost;
    s.ratio = s.frontCost > 0 ? evaluations / s.frontCost : INFINITY;
    s.credit = s.ratio <= fullWithin ? 1.0
               : s.ratio < nonePast  ? 1 - std::log(s.ratio / fullWithin) / std::log(nonePast / fullWithin)
                                     : 0.0;
    return s;
}

/// The most an answer may cost to earn anything: nonePast times the front's cost at `asked + beyond` digits.
inline double cap(const std::vector<work_precision::Point>& front, double asked, double beyond, double nonePast) {
    return nonePast * score(front, asked, asked + beyond, 0, beyond, 1, 2).frontCost;
}

/// The question in `text` (a data file's JSON); `what` names it in errors.
inline Question parseQuestion(const std::string& text, const std::string& what) {
    Question q;
    try {
        const nlohmann::json j = nlohmann::json::parse(text);
        q.lab = j.at("lab").get<std::string>();
        q.digits = j.at("digits").get<double>();
        if (j.contains("integrators")) q.integrators = j["integrators"].get<std::vector<std::string>>();
        q.fixedStepOnly = j.value("fixed_step_only", false);
        q.nudge = j.value("nudge", std::string());
        q.starts = j.value("starts", 1);
        for (const char* list : {"scenes", "variants"}) {
            if (!j.contains(list) && std::string(list) == "variants") continue;
            for (const nlohmann::json& s : j.at(list)) {
                Scene scene;
                scene.name = s.at("name").get<std::string>();
                scene.scene = s.at("scene");
                scene.finalTime = s.at("final_time").get<double>();
                for (const nlohmann::json& p : s.value("front", nlohmann::json::array())) {
                    scene.front.push_back({p.at(0).get<double>(), p.at(1).get<double>(), 0});
                }
                (std::string(list) == "scenes" ? q.scenes : q.variants).push_back(scene);
            }
        }
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error(what + " is damaged: " + e.what());
    }
    if (q.starts < 1 || q.starts > 10) throw std::runtime_error(what + ": starts must be 1 to 10");
    return q;
}

}  // namespace simlab::trade
