#include "simlab/engine/report.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace simlab::engine {

namespace {

std::string buildLine(const BuildResult& b) {
    char text[160];
    if (b.stage == "missing") {
        std::snprintf(text, sizeof text, "nothing to build");
    } else if (!b.ok) {
        std::snprintf(text, sizeof text, "%s", b.stage == "link" ? "did not link" : "did not compile");
    } else if (b.cached) {
        std::snprintf(text, sizeof text, "compiled (unchanged since last time), linked in %.1f s", b.linkSeconds);
    } else {
        std::snprintf(text, sizeof text, "compiled in %.1f s, linked in %.1f s", b.compileSeconds, b.linkSeconds);
    }
    return text;
}

std::string indent(const std::string& text, const std::string& prefix) {
    std::istringstream in(text);
    std::string line, out;
    while (std::getline(in, line)) out += prefix + line + "\n";
    return out;
}

std::string notRunLine(const GradeReport& r) {
    if (r.notRunCount == 0) return "";
    return std::to_string(r.notRunCount) + (r.notRunCount == 1 ? " hidden test" : " hidden tests") + " worth " +
           points(r.notRunPoints) + " points " + (r.notRunCount == 1 ? "is" : "are") +
           " left for instructor grading.";
}

}  // namespace

std::string points(double value) {
    char text[32];
    if (std::abs(value - std::round(value)) < 0.005) std::snprintf(text, sizeof text, "%.0f", value);
    else std::snprintf(text, sizeof text, "%.2f", value);
    std::string s = text;
    if (s.find('.') != std::string::npos) {
        while (s.back() == '0') s.pop_back();
    }
    return s;
}

std::string renderText(const GradeReport& r) {
    std::ostringstream out;
    out << r.title << " (" << r.assignment << "): " << (r.source.empty() ? "no file" : r.source) << "\n";
    if (!r.note.empty()) out << "  " << r.note << "\n";
    out << "  " << buildLine(r.build) << "\n";
    if (!r.build.ok) out << indent(firstLines(r.build.log, 12), "    | ");
    const std::string* previous = nullptr;
    for (const TestResult& t : r.tests) {
        char head[64];
        std::snprintf(head, sizeof head, "  %5s/%-4s %-17s ", points(t.score).c_str(), points(t.maxScore).c_str(),
                      outcomeName(t.outcome).c_str());
        out << head << t.name;
        // A failure that stops every test (a SIMLAB_TODO in buildModel, say) is spelled out once.
        if (!t.reason.empty() && t.outcome != Outcome::DidNotCompile) {
            const bool repeated = t.outcome != Outcome::Passed && previous && *previous == t.reason;
            out << ": " << (repeated ? "(the same)" : t.reason);
            if (t.outcome != Outcome::Passed) previous = &t.reason;
        }
        out << "\n";
        for (const std::string& line : t.feedback) out << "                            - " << line << "\n";
    }
    out << "Score: " << points(r.score()) << "/" << points(r.maxScore()) << "\n";
    const std::string left = notRunLine(r);
    if (!left.empty()) out << left << "\n";
    return out.str();
}

nlohmann::json toGradescope(const GradeReport& r) {
    nlohmann::json tests = nlohmann::json::array();
    for (const TestResult& t : r.tests) {
        std::string output = outcomeName(t.outcome);
        if (!t.reason.empty() && t.outcome != Outcome::DidNotCompile) output += ": " + t.reason;
        for (const std::string& line : t.feedback) output += "\n- " + line;
        if (t.outcome == Outcome::DidNotCompile) output += "\n" + firstLines(r.build.log, 12);
        nlohmann::json test = {{"name", t.name},
                               {"score", t.score},
                               {"max_score", t.maxScore},
                               {"status", t.outcome == Outcome::Passed ? "passed" : "failed"},
                               {"output", output},
                               {"visibility", t.visibility},
                               {"extra_data", {{"outcome", outcomeName(t.outcome)}, {"seconds", t.seconds}}}};
        if (t.figure) {
            test["extra_data"]["figure"] = *t.figure;
            test["extra_data"]["unit"] = t.unit;
        }
        tests.push_back(test);
    }
    std::string output = r.note.empty() ? "" : r.note + "\n";
    output += buildLine(r.build) + "\n";
    if (!r.build.ok) output += firstLines(r.build.log, 20);
    const std::string left = notRunLine(r);
    if (!left.empty()) output += left + "\n";
    return {{"score", r.score()},
            {"execution_time", static_cast<int>(std::ceil(r.seconds))},
            {"output", output},
            {"stdout_visibility", "hidden"},
            {"tests", tests},
            {"extra_data",
             {{"assignment", r.assignment},
              {"status", r.status},
              {"max_score", r.maxScore()},
              {"hidden_tests_not_run", r.notRunCount},
              {"hidden_points_not_run", r.notRunPoints}}}};
}

}  // namespace simlab::engine
