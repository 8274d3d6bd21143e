// feedback.md: what a student reads, in Markdown.
#include <sstream>

#include "feedback.h"
#include "simlab/grading/report.h"
#include "simlab/common/text.h"
#include "simlab/writers/writers.h"

namespace simlab::engine {

std::string feedbackMarkdown(const Assignment& assignment, const StudentRecord& record,
                             const std::vector<ManualItem>& manual, const std::vector<std::string>& attached) {
    const writers::Feedback f = writers::feedbackOf(assignment, record, manual, attached);
    // A command to copy: in code when the file's name is plain, else as escaped text.
    auto command = [&](const std::string& text) { return f.plainCommand ? "`" + text + "`" : markdownText(text); };
    std::ostringstream out;
    out << "# " << markdownText(f.title) << ": " << markdownText(f.id) << "\n\n";
    out << "**Score: " << f.score << "**";
    if (!f.status.empty()) out << " (" << f.status << ")";
    out << "\n\n";
    if (!f.note.empty()) out << markdownText(f.note) << ".\n\n";
    if (!f.late.empty()) out << "Lateness: " << markdownText(f.late) << ".\n\n";
    if (!f.slip.empty()) out << "Slip days: " << markdownText(f.slip) << ".\n\n";
    if (!f.compilerTitle.empty()) {
        // An indented block: shown as the compiler wrote it (escaped), and nothing in it can end the block.
        out << f.compilerTitle << "\n\n";
        std::istringstream lines(f.compiler);
        for (std::string line; std::getline(lines, line);) out << "    " << line << "\n";
        out << "\n";
    }
    out << "| points | outcome | test |\n| ---: | --- | --- |\n";
    for (const writers::FeedbackTest& t : f.tests) {
        out << "| " << t.points << " | " << t.outcome << " | " << markdownText(t.result->name) << " |\n";
    }
    out << "\n";
    for (const writers::FeedbackTest& t : f.tests) {
        if (!t.detailed) continue;
        out << "## " << markdownText(t.result->name) << "\n\n" << t.points << ", " << t.outcome;
        if (t.hidden) {
            out << ". (A hidden test: your instructor has the details.)\n\n";
            continue;
        }
        out << (t.result->reason.empty() ? "" : ": " + markdownText(t.result->reason)) << "\n\n";
        for (const std::string& line : t.result->feedback) out << "- " << markdownText(line) << "\n";
        if (!t.result->feedback.empty()) out << "\n";
        if (!t.reproduce.empty()) out << "Reproduce: " << command(t.reproduce) << "\n\n";
    }
    if (!f.attached.empty()) {
        out << "Drawn from your model, beside this file:";
        for (const std::string& name : f.attached) out << " " << markdownText(name);
        out << "\n\n";
    }
    if (!f.manual.empty()) {
        out << "Graded by hand" << (f.manualPoints > 0 ? ", " + points(f.manualPoints) + " points pending" : "")
            << ":\n\n";
        for (const ManualGrade& m : f.manual) {
            out << "- " << markdownText(m.name) << ": "
                << (m.points ? points(*m.points) + "/" + points(m.maxPoints) : "pending (" + points(m.maxPoints) + ")");
            if (!m.comment.empty()) out << " (" << markdownText(m.comment) << ")";
            if (m.earlierFile) out << " (" << writers::kEarlierFile << ")";
            out << "\n";
        }
        out << "\n";
    }
    if (!f.sandbox.empty()) out << "Your code ran in simlab's sandbox: " << markdownText(f.sandbox) << ".\n\n";
    out << "Check your file on the visible tests with " << command(f.check) << ".\n";
    return out.str();
}

}  // namespace simlab::engine
