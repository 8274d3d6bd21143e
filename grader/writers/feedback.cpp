#include "feedback.h"

#include <algorithm>
#include <cctype>

#include "simlab/grading/report.h"
#include "simlab/common/text.h"

namespace simlab::engine::writers {

Feedback feedbackOf(const Assignment& assignment, const StudentRecord& r, const std::vector<ManualItem>& manual,
                    const std::vector<std::string>& attached) {
    Feedback f;
    f.title = assignment.title;
    f.id = r.id;
    f.score = points(r.total()) + "/" + points(r.maxTotal());
    if (r.status != SubmissionStatus::Graded) f.status = statusName(r.status);
    f.note = r.note;
    f.late = r.late.line;
    if (r.late.percent > 0) {
        f.late += ": " + points(r.latePoints()) + " points off the " + points(r.rawTotal()) + " earned";
    }
    f.slip = r.late.slip.ledger;
    f.sandbox = r.sandbox;
    if (!r.compiler.empty()) {
        f.compilerTitle = r.status == SubmissionStatus::DidNotCompile ? "The compiler's message:"
                          : r.status == SubmissionStatus::DidNotLink    ? "The linker's message:"
                          : r.status == SubmissionStatus::ForbiddenCode ? "Why the file was refused:"
                                                         : "The compiler's warnings:";
        f.compiler = printable(r.compiler, true);
    }
    const std::string file = r.file.empty() ? assignment.source : r.file;
    f.check = "simlab check " + assignment.id + " " + file;
    f.plainCommand = std::all_of(file.begin(), file.end(), [](unsigned char c) {
        return std::isalnum(c) || c == '.' || c == '_' || c == '-' || c == '/' || c == '+';
    });
    for (const TestResult& t : r.tests) {
        FeedbackTest shown;
        shown.result = &t;
        shown.points = points(t.score) + "/" + points(t.maxScore);
        shown.outcome = outcomeName(t.outcome);
        shown.detailed = !(t.outcome == Outcome::Passed && t.reason.empty());
        shown.hidden = t.visibility == "hidden";
        if (t.outcome != Outcome::Passed && t.visibility == "visible") {
            shown.reproduce = f.check + " --test \"" + t.name + "\"";
        }
        f.tests.push_back(shown);
    }
    f.attached = attached;
    // The points the instructor gave (manual.csv), or, without a sheet (a self-check), every item pending.
    f.manual = r.manual;
    if (f.manual.empty()) {
        for (const ManualItem& m : manual) f.manual.push_back({m.name, m.points, std::nullopt, ""});
    }
    for (const ManualGrade& m : f.manual) f.manualPoints += m.points ? 0 : m.maxPoints;
    return f;
}

}  // namespace simlab::engine::writers
