#include "simlab/grading/report.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "simlab/common/text.h"

namespace simlab::engine {

namespace {

int warningCount(const std::string& log) {
    int count = 0;
    for (std::size_t at = log.find(": warning: "); at != std::string::npos; at = log.find(": warning: ", at + 1)) ++count;
    return count;
}

std::string buildLine(const BuildResult& b) {
    char text[160];
    const int warnings = warningCount(b.warnings);
    const std::string counted = warnings == 0 ? "" : warnings == 1 ? " (1 warning)" : " (" + std::to_string(warnings) + " warnings)";
    if (b.stage == "missing") {
        std::snprintf(text, sizeof text, "nothing to build");
    } else if (!b.ok) {
        std::snprintf(text, sizeof text, "%s", statusName(buildFailure(b)).c_str());
    } else if (b.cached) {
        std::snprintf(text, sizeof text, "compiled (unchanged since last time)%s, linked in %.1f s", counted.c_str(),
                      b.linkSeconds);
    } else {
        std::snprintf(text, sizeof text, "compiled in %.1f s%s, linked in %.1f s", b.compileSeconds, counted.c_str(),
                      b.linkSeconds);
    }
    return text;
}

// The compiler's warnings about the student's file, to show under the build line.
std::string warningLines(const BuildResult& b, int maxLines) {
    if (!b.ok || warningCount(b.warnings) == 0) return "";
    return isolation::firstLines(printable(b.warnings, true), maxLines);
}

std::string indent(const std::string& text, const std::string& prefix) {
    std::istringstream in(text);
    std::string line, out;
    while (std::getline(in, line)) out += prefix + line + "\n";
    return out;
}

std::string notRunLine(int count, double notRunPoints) {
    if (count == 0) return "";
    return std::to_string(count) + (count == 1 ? " hidden test" : " hidden tests") + " worth " + points(notRunPoints) +
           " points " + (count == 1 ? "is" : "are") + " left for instructor grading.";
}

/// "Graded by hand: 12.5/15 points (the schematic is clear, 7.5/10 (the axis is missing); ...)." for the items
/// given, then "Graded by hand, pending: 10 points (the write-up is sound, 10)." for those still pending; empty
/// without manual items.
std::string manualLine(const std::vector<ManualGrade>& manual) {
    double given = 0, givenMax = 0, pendingTotal = 0;
    std::string givenItems, pendingItems;
    for (const ManualGrade& m : manual) {
        if (m.points) {
            given += *m.points;
            givenMax += m.maxPoints;
            givenItems += (givenItems.empty() ? "" : "; ") + m.name + ", " + points(*m.points) + "/" +
                          points(m.maxPoints) + (m.comment.empty() ? "" : " (" + printable(m.comment) + ")") +
                          (m.earlierFile ? ", given to an earlier file" : "");
        } else {
            pendingTotal += m.maxPoints;
            pendingItems += (pendingItems.empty() ? "" : "; ") + m.name + ", " + points(m.maxPoints);
        }
    }
    std::string line;
    if (!givenItems.empty()) {
        line = "Graded by hand: " + points(given) + "/" + points(givenMax) + " points (" + givenItems + ").";
    }
    if (!pendingItems.empty()) {
        line += (line.empty() ? "" : "\n") + std::string("Graded by hand, pending: ") + points(pendingTotal) +
                " points (" + pendingItems + ").";
    }
    return line;
}

std::vector<ManualGrade> pending(const std::vector<ManualItem>& items) {
    std::vector<ManualGrade> manual;
    for (const ManualItem& m : items) manual.push_back({m.name, m.points, std::nullopt, ""});
    return manual;
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
    out << r.title << " (" << r.assignment << "): " << (r.source.empty() ? "no file" : printable(r.source)) << "\n";
    if (!r.note.empty()) out << "  " << printable(r.note) << "\n";
    out << "  " << buildLine(r.build) << "\n";
    if (!r.sandbox.empty() && r.build.ok) out << "  sandbox: " << r.sandbox << "\n";
    if (!r.build.ok) out << indent(isolation::firstLines(printable(r.build.log, true), 12), "    | ");
    out << indent(warningLines(r.build, 12), "    | ");
    const std::string* previous = nullptr;
    for (const TestResult& t : r.tests) {
        char head[64];
        std::snprintf(head, sizeof head, "  %5s/%-4s %-17s ", points(t.score).c_str(), points(t.maxScore).c_str(),
                      outcomeName(t.outcome).c_str());
        out << head << t.name;
        // A failure that stops every test (a SIMLAB_TODO in buildModel, say) is spelled out once.
        if (!t.reason.empty() && t.outcome != Outcome::DidNotCompile) {
            const bool repeated = t.outcome != Outcome::Passed && previous && *previous == t.reason;
            out << ": " << (repeated ? "(the same)" : printable(t.reason));
            if (t.outcome != Outcome::Passed) previous = &t.reason;
        }
        out << "\n";
        for (const std::string& line : t.feedback) out << "                            - " << printable(line) << "\n";
    }
    out << "Score: " << points(r.score()) << "/" << points(r.maxScore()) << "\n";
    const std::string left = notRunLine(r.notRunCount, r.notRunPoints);
    if (!left.empty()) out << left << "\n";
    const std::string manual = manualLine(pending(r.manual));
    if (!manual.empty()) out << manual << "\n";
    return out.str();
}

// What Gradescope shows of a test. Its specification: a "hidden" test is never shown to the student, and while any
// test is hidden the student cannot see the total score either. So a test that carries points is never "hidden":
// a hidden test of simlab's (not in the student bundle) is shown "after_due_date" unless the rubric chose
// "after_published"; only a test worth nothing may stay hidden.
std::string gradescopeVisibility(const TestResult& t) {
    if (t.visibility == "hidden" && t.maxScore > 0) return "after_due_date";
    return t.visibility;
}

StudentRecord recordOf(const GradeReport& report) {
    StudentRecord r;
    r.status = report.status;
    r.note = report.note;
    r.score = report.score();
    r.maxScore = report.maxScore();
    r.seconds = report.seconds;
    r.compiler = isolation::firstLines(report.build.ok ? report.build.warnings : report.build.log, 20);
    r.sandbox = report.sandbox;
    r.assignment = report.assignment;
    r.built = report.build.ok;
    r.build = buildLine(report.build);
    r.notRunCount = report.notRunCount;
    r.notRunPoints = report.notRunPoints;
    r.tests = report.tests;
    r.manual = pending(report.manual);
    return r;
}

TestAccount testAccount(const StudentRecord& r, const TestResult& t) {
    TestAccount account{outcomeName(t.outcome), {}};
    if (!t.reason.empty() && t.outcome != Outcome::DidNotCompile) account.line += ": " + printable(t.reason);
    for (const std::string& line : t.feedback) account.more.push_back("- " + printable(line));
    // The compiler's first lines, as the record keeps them.
    if (t.outcome == Outcome::DidNotCompile) {
        account.more.push_back(isolation::firstLines(printable(r.compiler, true), 12));
    }
    return account;
}

std::string TestAccount::text() const {
    std::string all = line;
    for (const std::string& l : more) all += "\n" + l;
    return all;
}

std::string recordAccount(const StudentRecord& r) {
    std::string output = r.note.empty() ? "" : printable(r.note) + "\n";
    if (!r.build.empty()) output += r.build + "\n";
    if (!r.sandbox.empty()) output += "sandbox: " + r.sandbox + "\n";
    if (!r.built || warningCount(r.compiler) > 0) output += printable(r.compiler, true);
    const std::string left = notRunLine(r.notRunCount, r.notRunPoints);
    if (!left.empty()) output += left + "\n";
    const std::string manual = manualLine(r.manual);
    if (!manual.empty()) output += manual + "\n";
    // A late penalty (the course's policy), and the course's bank of slip days: what this lab spent, and what is
    // left after it.
    if (!r.late.line.empty()) {
        output += "Lateness: " + printable(r.late.line) + "\n";
        if (!r.late.slip.ledger.empty()) output += "Slip days: " + printable(r.late.slip.ledger) + "\n";
    }
    return output;
}

nlohmann::json toGradescope(const StudentRecord& r) {
    nlohmann::json tests = nlohmann::json::array(), leaderboard = nlohmann::json::array();
    for (const TestResult& t : r.tests) {
        for (const BoardEntry& e : t.leaderboard) {
            leaderboard.push_back({{"name", e.name}, {"value", e.value}, {"order", e.order}});
        }
        nlohmann::json test = {{"name", t.name},
                               {"score", t.score},
                               {"max_score", t.maxScore},
                               {"status", t.outcome == Outcome::Passed ? "passed" : "failed"},
                               {"output", testAccount(r, t).text()},
                               {"visibility", gradescopeVisibility(t)},
                               {"extra_data", {{"outcome", outcomeName(t.outcome)}, {"seconds", t.seconds}}}};
        if (t.figure) {
            test["extra_data"]["figure"] = *t.figure;
            test["extra_data"]["unit"] = t.unit;
        }
        tests.push_back(test);
    }
    // The items a person grades: Gradescope grades them as questions of their own beside the autograder's score.
    nlohmann::json pendingItems = nlohmann::json::array(), given = nlohmann::json::array();
    for (const ManualGrade& m : r.manual) {
        if (m.points) {
            given.push_back({{"name", m.name},
                             {"score", *m.points},
                             {"max_score", m.maxPoints},
                             {"comment", m.comment},
                             {"earlier_file", m.earlierFile}});
        } else {
            pendingItems.push_back({{"name", m.name}, {"max_score", m.maxPoints}, {"status", "pending"}});
        }
    }
    nlohmann::json extra = {{"assignment", r.assignment},
                            {"status", statusName(r.status)},
                            {"sandbox", r.sandbox},
                            {"max_score", r.maxScore},
                            {"hidden_tests_not_run", r.notRunCount},
                            {"hidden_points_not_run", r.notRunPoints},
                            {"manual_pending", pendingItems},
                            {"manual_points_pending", r.pendingPoints()}};
    if (!r.manual.empty()) {
        extra["manual_graded"] = given;
        extra["total_with_manual"] = r.total();
        extra["max_with_manual"] = r.maxTotal();
    }
    // A late penalty (the course's policy) takes its share of the tests' points too.
    if (!r.late.line.empty()) {
        extra["late"] = {{"submitted", r.submitted}, {"hours", r.late.hours}, {"percent", r.late.percent}};
        if (const StudentRecord::Lateness::Slip& s = r.late.slip; !s.ledger.empty()) {
            extra["late"]["slip_days"] = {{"used", s.used}, {"left", s.had - s.used}, {"bank", s.bank}};
        }
    }
    const double score = roundScore(r.score * (1 - r.late.percent / 100));
    // Everything is plain text (never HTML or Markdown a student's bytes could shape), valid UTF-8.
    nlohmann::json document = {{"score", score},
                               {"execution_time", static_cast<int>(std::ceil(r.seconds))},
                               {"output", recordAccount(r)},
                               {"output_format", "text"},
                               {"test_output_format", "text"},
                               {"stdout_visibility", "hidden"},
                               {"tests", tests},
                               {"extra_data", extra}};
    if (!leaderboard.empty()) document["leaderboard"] = leaderboard;
    return document;
}

nlohmann::json toGradescope(const GradeReport& report) { return toGradescope(recordOf(report)); }

}  // namespace simlab::engine
