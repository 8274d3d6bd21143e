// The runner result GitHub Classroom's grading reporter (classroom-resources/autograding-grading-reporter) reads,
// base64-encoded, from <RUNNER>_RESULTS: version 1, status, max_score, and tests[] with name, status, score,
// message, test_code, filename, line_no and duration, as its own graders (autograding-command-grader) write it.
// Classroom takes the points from the sum of the tests' scores and max_score. The texts are the ones Gradescope's
// document holds (report.h's toGradescope).
#include <cmath>

#include "common.h"
#include "simlab/engine/report.h"
#include "simlab/engine/text.h"
#include "simlab/engine/writers.h"

namespace simlab::engine {

namespace {

// A test that could not run at all is an error in the reporter's words; one that ran and lost points, a fail.
std::string testStatus(Outcome outcome) {
    if (outcome == Outcome::Passed) return "pass";
    if (outcome == Outcome::DidNotCompile || outcome == Outcome::MissingFile || outcome == Outcome::Refused) {
        return "error";
    }
    return "fail";
}

}  // namespace

std::string classroomJson(const GradeReport& report) {
    const nlohmann::json gradescope = toGradescope(report);
    nlohmann::json tests = nlohmann::json::array();
    bool passed = true;
    const std::string file = report.source.empty() ? "" : " " + printable(report.source);
    for (std::size_t i = 0; i < report.tests.size(); ++i) {
        const TestResult& t = report.tests[i];
        passed = passed && t.outcome == Outcome::Passed;
        tests.push_back({{"name", t.name},
                         {"status", testStatus(t.outcome)},
                         {"score", t.score},
                         {"message", gradescope["tests"][i]["output"]},
                         {"test_code", "build/bin/simlab check " + report.assignment + file + " --test \"" + t.name + "\""},
                         {"filename", printable(report.source)},
                         {"line_no", 0},  // the reporter prints " - line N" for any other value
                         {"duration", static_cast<long>(std::lround(t.seconds * 1000))}});
    }
    const bool ran = report.build.ok;
    return writers::jsonText({{"version", 1},
                              {"status", !ran ? "error" : passed ? "pass" : "fail"},
                              {"max_score", report.maxScore()},
                              {"tests", tests}});
}

}  // namespace simlab::engine
