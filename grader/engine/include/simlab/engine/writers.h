// The files grading a class writes, one writer per format, each in a file of its own under engine/writers/:
//
//     gradebook.csv          gradebook.cpp          gradebookCsv
//     summary.csv, stdout    summary.cpp            summaryCsv, summaryTable
//     JUnit XML              junit.cpp              junitXml
//     feedback.md            feedback_markdown.cpp  feedbackMarkdown
//     feedback.html          feedback_html.cpp      feedbackHtml
//     report.html            report_html.cpp        classReportHtml
//     results.json           results_json.cpp       resultsJson (the document is report.h's toGradescope)
//     record.json            record_json.cpp        recordJson, readRecordJson
//     output.txt             output_text.cpp        testOutputText
//
// Every writer makes the students' bytes (ids, file names, compiler messages, reasons) safe for its format with
// text.h, and none throws for anything those bytes hold.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "simlab/engine/grade.h"
#include "simlab/engine/record.h"

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

/// A file a test drew for the student's feedback (a plot of their run, a drawing of their model): its name, as it
/// lies beside the feedback, and its bytes.
struct Attachment {
    std::string name;
    std::string bytes;
};

/// The same feedback as a self-contained HTML page (inline style, no script, nothing fetched): the same facts as
/// feedbackMarkdown, each test's measured figure where it has one, and the pictures among `attached` (SVG, PNG)
/// shown in the page as data URIs; the other files are linked.
std::string feedbackHtml(const Assignment& assignment, const StudentRecord& record,
                         const std::vector<ManualItem>& manual = {}, const std::vector<Attachment>& attached = {});

/// The class as a self-contained HTML page (inline style and SVG, no script, nothing fetched): the scores'
/// histogram, each test's pass rate and the spread of its figure, the submissions that were not graded or scored
/// lowest, the slowest ones, and what was skipped; each student linked to students/<id>/feedback.html.
std::string classReportHtml(const Assignment& assignment, const Rubric& rubric, const ClassResult& result);

/// results.json: Gradescope's document for the report (toGradescope), as text in valid UTF-8.
std::string resultsJson(const GradeReport& report);

/// record.json: the record as simlab keeps it to resume a class.
std::string recordJson(const StudentRecord& record);
/// The record that `text` holds; empty if it is damaged or from another version (the student is regraded).
std::optional<StudentRecord> readRecordJson(const std::string& text);

/// output.txt: what each test's process printed and the grader's account of the tests, for instructors.
std::string testOutputText(const GradeReport& report);

}  // namespace simlab::engine
