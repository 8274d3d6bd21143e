// The runner results GitHub Classroom's grading reporter (classroom-resources/autograding-grading-reporter@v1)
// reads, base64-encoded, from <RUNNER>_RESULTS: version 1, status, max_score, and tests[] with name, status, score,
// message, test_code, filename, line_no and duration, as its own graders (autograding-command-grader) write it.
//
// The reporter counts a runner's points twice, two ways: its console table gives each runner
// (tests passed / tests) x max_score, while the points it records for Classroom are the sum of the tests' scores
// over the sum of max_score. Under partial credit one runner cannot make the two agree. Two runners do: "earned"
// (max_score the points earned; one passing entry per test that earned points, worth them) and "missed"
// (max_score the points missed; one failing entry per test that missed points, worth 0). Both ways then give the
// score over the assignment's points. The texts are the record's account of its tests (report.h's testAccount), as
// Gradescope's document gives them.
#include <cmath>

#include "common.h"
#include "simlab/grading/report.h"
#include "simlab/common/text.h"
#include "simlab/writers/writers.h"

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
    StudentRecord record = recordOf(report);
    record.file = report.source;  // the file graded, as the command that runs a test alone names it
    return classroomJson(record);
}

std::string classroomJson(const StudentRecord& record) {
    const std::string file = record.file.empty() ? "" : " " + printable(record.file);
    const bool built = record.built;
    auto entry = [&](std::size_t i, const std::string& status, double score, const std::string& what) {
        const TestResult& t = record.tests[i];
        return nlohmann::json{{"name", printable(t.name) + " (" + what + ")"},
                              {"status", status},
                              {"score", score},
                              {"message", testAccount(record, t).text()},
                              {"test_code",
                               "build/bin/simlab check " + record.assignment + file + " --test \"" + t.name + "\""},
                              {"filename", printable(record.file)},
                              {"line_no", 0},  // the reporter prints " - line N" for any other value
                              {"duration", static_cast<long>(std::lround(t.seconds * 1000))}};
    };
    // The points each test earned, every one a pass worth its points; the points each test missed, a fail (or an
    // error, where nothing ran) worth nothing. A test with part of its points is in both.
    nlohmann::json earned = nlohmann::json::array(), missed = nlohmann::json::array();
    for (std::size_t i = 0; i < record.tests.size(); ++i) {
        const TestResult& t = record.tests[i];
        const double lost = roundScore(t.maxScore - t.score);
        if (t.score > 0) earned.push_back(entry(i, "pass", t.score, points(t.score) + " of " + points(t.maxScore) + " points"));
        if (lost > 0) {
            missed.push_back(entry(i, testStatus(t.outcome) == "pass" ? "fail" : testStatus(t.outcome), 0,
                                   points(lost) + " of " + points(t.maxScore) + " points missed"));
        }
    }
    // The reporter divides by the number of tests: neither runner is ever empty (an entry worth nothing).
    auto nothing = [](const std::string& name, const std::string& status) {
        return nlohmann::json{{"name", name}, {"status", status}, {"score", 0}, {"message", ""}, {"line_no", 0}};
    };
    if (earned.empty()) earned.push_back(nothing("no points earned", "fail"));
    if (missed.empty()) missed.push_back(nothing("no points missed", "pass"));
    const double score = record.score, max = record.maxScore;
    const nlohmann::json earnedRunner = {{"version", 1}, {"status", built ? "pass" : "error"}, {"max_score", score},
                                         {"tests", earned}};
    const nlohmann::json missedRunner = {{"version", 1},
                                         {"status", !built ? "error" : score < max ? "fail" : "pass"},
                                         {"max_score", roundScore(max - score)},
                                         {"tests", missed}};
    return earnedRunner.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace) + "\n" +
           missedRunner.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace simlab::engine
