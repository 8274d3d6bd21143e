// The files grading a class writes, one writer per format, each in a file of its own under writers/:
//
//     gradebook.csv          gradebook.cpp          gradebookCsv
//     summary.csv, stdout    summary.cpp            summaryCsv, summaryTable
//     JUnit XML              junit.cpp              junitXml
//     feedback.md            feedback_markdown.cpp  feedbackMarkdown
//     feedback.html          feedback_html.cpp      feedbackHtml
//     report.html            report_html.cpp        classReportHtml
//     results.json           results_json.cpp       resultsJson, resultsErrorJson (the document is report.h's
//                                                     toGradescope)
//     record.json            record_json.cpp        recordJson, readRecordJson
//     output.txt             output_text.cpp        testOutputText
//     PrairieLearn's         prairielearn_json.cpp  prairieLearnJson, prairieLearnErrorJson
//       results.json
//     GitHub Classroom's     classroom_json.cpp     classroomJson
//       runner result
//     Canvas's gradebook     canvas_csv.cpp         canvasCsv
//       import CSV
//
// Every writer makes the students' bytes (ids, file names, compiler messages, reasons) safe for its format with
// text.h, and none throws for anything those bytes hold.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "simlab/grading/grade.h"
#include "simlab/grading/record.h"
#include "simlab/writers/roster.h"

namespace simlab::engine {

/// gradebook.csv: student, score, max, status, the points of each rubric test, and a "pending" column for each
/// item graded by hand.
std::string gradebookCsv(const Rubric& rubric, const std::vector<StudentRecord>& records);

/// The class summary, per test: pass rate and median, min and max of its measured figure. As a text table and
/// as CSV (what summary.csv holds).
std::string summaryTable(const Rubric& rubric, const std::vector<StudentRecord>& records);
std::string summaryCsv(const Rubric& rubric, const std::vector<StudentRecord>& records);

/// JUnit XML: one test suite per student, one test case per test.
std::string junitXml(const Assignment& assignment, const std::vector<StudentRecord>& records);

/// What a student reads: each test with its points, outcome and reason, and how to reproduce it. `attached`
/// names the files beside it that the tests drew.
std::string feedbackMarkdown(const Assignment& assignment, const StudentRecord& record,
                             const std::vector<ManualItem>& manual = {}, const std::vector<std::string>& attached = {});

/// The same feedback as a self-contained HTML page (inline style, no script, nothing fetched): the same facts as
/// feedbackMarkdown, each test's measured figure where it has one, and the pictures among `attached` (SVG, PNG:
/// the files the tests drew, by their names beside the feedback) shown in the page as data URIs; the other files
/// are linked.
std::string feedbackHtml(const Assignment& assignment, const StudentRecord& record,
                         const std::vector<ManualItem>& manual = {}, const std::vector<Attachment>& attached = {});

/// The class as a self-contained HTML page (inline style and SVG, no script, nothing fetched): the scores'
/// histogram, each test's pass rate and the spread of its figure, the submissions that were not graded or scored
/// lowest, the slowest ones, and what was skipped; each student linked to students/<id>/feedback.html.
std::string classReportHtml(const Assignment& assignment, const Rubric& rubric, const ClassResult& result);

/// results.json: Gradescope's document for the record (toGradescope), as text in valid UTF-8: the scores it has
/// now and, with manual items, the points given by hand so far.
std::string resultsJson(const StudentRecord& record);
/// resultsJson(recordOf(report)).
std::string resultsJson(const GradeReport& report);

/// What results.json says of a submission against the course's cap on graded submissions (course.toml's
/// max_submissions): `line` first in its output, and extra_data.submissions (counted, number, max, window_hours,
/// left; checked false where the platform gave nothing to check the cap against).
struct SubmissionsNote {
    std::string line;
    bool checked = true;
    bool counted = true;
    int number = 0;
    int max = 0;
    int left = 0;
    double windowHours = 0;
};
/// resultsJson(record), with the note.
std::string resultsJson(const StudentRecord& record, const SubmissionsNote& note);
/// results.json of a submission past the cap, not graded: the results of the earlier one whose score it keeps, as
/// the platform kept them (`earlier`: Gradescope's previous_submissions[].results, its tests and leaderboard; an
/// object, else none), with that `score`, and the note.
std::string keptResultsJson(const nlohmann::json& earlier, double score, const SubmissionsNote& note);

/// results.json when simlab could not grade at all: score 0, no tests, why in its output, and extra_data.graded
/// false (a cap on graded submissions does not count it).
std::string resultsErrorJson(const std::string& why);

/// record.json: the record as simlab keeps it to resume a class.
std::string recordJson(const StudentRecord& record);
/// The record that `text` holds; empty if it is damaged or from another version (the student is regraded).
std::optional<StudentRecord> readRecordJson(const std::string& text);

/// output.txt: what each test's process printed and the grader's account of the tests, for instructors.
std::string testOutputText(const GradeReport& report);

/// PrairieLearn's results.json for an external grader (its documented fields): score in [0, 1], gradable (false,
/// with format_errors, when there was no file to grade), message, output, and tests[] with name, points,
/// max_points, message, output and, for visible tests, the pictures they drew as images (data URIs). Hidden tests
/// show their points and outcome only. Never longer than `limitBytes` (PrairieLearn takes 1 MB): pictures are
/// left out first, the largest first, then the texts are cut.
std::string prairieLearnJson(const StudentRecord& record, std::size_t limitBytes = 1000000);
/// prairieLearnJson(recordOf(report)).
std::string prairieLearnJson(const GradeReport& report, std::size_t limitBytes = 1000000);
/// PrairieLearn's results.json when simlab could not grade at all: not gradable (no attempt is charged), and why.
std::string prairieLearnErrorJson(const std::string& why);

/// The two runner results GitHub Classroom's grading reporter reads (each base64-encoded in <RUNNER>_RESULTS), one
/// JSON document a line: "earned" (max_score the points earned, a passing entry per test that earned points) and
/// "missed" (max_score the points missed, a failing entry per test that missed points), so that the reporter's
/// table and the points it records for Classroom agree (classroom_json.cpp says why). Each: version 1, status
/// (pass, fail, or error when nothing was built), max_score, and tests[] with name, status, score, message,
/// test_code (the command that runs the test alone), filename, line_no and duration (ms).
std::string classroomJson(const StudentRecord& record);
/// classroomJson(recordOf(report)).
std::string classroomJson(const GradeReport& report);

/// Canvas's gradebook import for one assignment column, from the class's records and the roster.
struct CanvasExport {
    std::string csv;
    int scored = 0;                        ///< roster students with a score in the file
    std::vector<std::string> notGraded;    ///< on the roster, no grade (no folder, or a grader error): left blank
    std::vector<std::string> noId;         ///< on the roster with no simlab id (by name): left blank
    std::vector<std::string> missingFile;  ///< their folder holds no file to grade: left blank, not a 0
    std::vector<std::string> manualPending;  ///< items graded by hand still pending: left blank
    std::vector<std::string> notOnRoster;  ///< graded, but not on the roster: not in the file
    std::vector<std::string> unmatched;    ///< scored, on a row with no ID, SIS User ID or SIS Login ID for Canvas
};
/// One row per roster student, in the roster's order: Student, ID, SIS User ID, SIS Login ID, Section, then the
/// score (the tests' points and the points given by hand) under the header `column` ("Newton's apple (1234)":
/// Canvas matches the assignment by the id in parentheses, else by name), after a "Points Possible" row. Members
/// of a group share its simlab id, and each gets the group's grade. A blank cell leaves Canvas's grade as it is:
/// a student with no id, no folder, no file, a grader error or manual items still pending gets one, and is listed.
CanvasExport canvasCsv(const std::string& column, double pointsPossible, const std::vector<RosterEntry>& roster,
                       const std::vector<StudentRecord>& records);

}  // namespace simlab::engine
