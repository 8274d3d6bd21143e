// feedback.html: what a student reads, as a page of its own.
#include <algorithm>
#include <cctype>
#include <sstream>

#include "common.h"
#include "feedback.h"
#include "simlab/writers/html.h"
#include "simlab/grading/report.h"
#include "simlab/writers/writers.h"

namespace simlab::engine {

namespace {

using writers::htmlText;

// "14.8 digits": what the test measured.
std::string figureText(const TestResult& t) {
    // A count of one is singular: "1 degree of freedom", "1 evaluation" (the unit's first word loses its s).
    std::string unit = t.unit;
    const std::size_t word = unit.find(' ');
    const std::string first = unit.substr(0, word);
    if (*t.figure == 1 && first.size() > 3 && first.back() == 's' &&
        std::all_of(first.begin(), first.end(), [](unsigned char c) { return std::isalpha(c); })) {
        unit.erase(first.size() - 1, 1);
    }
    return writers::number(*t.figure) + (unit.empty() ? "" : " " + unit);
}

}  // namespace

std::string feedbackHtml(const Assignment& assignment, const StudentRecord& record,
                         const std::vector<ManualItem>& manual, const std::vector<Attachment>& attached) {
    std::vector<std::string> names;
    for (const Attachment& a : attached) names.push_back(a.name);
    const writers::Feedback f = writers::feedbackOf(assignment, record, manual, names);
    std::ostringstream out;
    out << writers::pageStart(f.title + ": " + f.id);
    out << "<header>\n<h1>" << htmlText(f.title) << ": " << htmlText(f.id) << "</h1>\n";
    out << "<p class=\"score\">Score: <strong>" << f.score << "</strong>";
    if (!f.status.empty()) out << " " << writers::outcomeBadge(f.status);
    out << "</p>\n";
    if (!f.note.empty()) out << "<p>" << htmlText(f.note) << ".</p>\n";
    if (!f.late.empty()) out << "<p class=\"late\">Lateness: " << htmlText(f.late) << ".</p>\n";
    if (!f.slip.empty()) out << "<p class=\"late\">Slip days: " << htmlText(f.slip) << ".</p>\n";
    out << "</header>\n";

    if (!f.compilerTitle.empty()) {
        const std::string heading = f.compilerTitle.substr(0, f.compilerTitle.size() - 1);  // without the colon
        out << "<h2>" << htmlText(heading) << "</h2>\n<pre>" << writers::htmlBlock(f.compiler) << "</pre>\n";
    }

    out << "<h2>Tests</h2>\n<table class=\"tests\">\n<thead><tr><th class=\"num\">points</th><th>outcome</th>"
           "<th>test</th><th>measured</th></tr></thead>\n<tbody>\n";
    for (std::size_t i = 0; i < f.tests.size(); ++i) {
        const writers::FeedbackTest& t = f.tests[i];
        const std::string name = htmlText(t.result->name);
        out << "<tr><td class=\"num\">" << t.points << "</td><td>" << writers::outcomeBadge(t.outcome)
            << "</td><td class=\"name\">"
            << (t.detailed ? "<a href=\"#test-" + std::to_string(i + 1) + "\">" + name + "</a>" : name)
            << "</td><td class=\"figure\">"
            << (t.result->figure && !t.hidden ? htmlText(figureText(*t.result)) : "") << "</td></tr>\n";
    }
    out << "</tbody>\n</table>\n";

    // The pictures the tests drew of the student's runs, in the page itself; each is also a file beside it.
    int pictures = 0;
    for (const Attachment& a : attached) {
        const std::string type = writers::pictureType(a.name);
        if (type.empty() || a.text.empty()) continue;
        if (!pictures) out << "<h2 id=\"runs\">Your runs, drawn</h2>\n";
        ++pictures;
        out << writers::figureHtml("picture-" + std::to_string(pictures), writers::dataUri(type, a.text),
                                   type == "image/svg+xml" ? a.text : "", a.name, a.name);
    }

    for (std::size_t i = 0; i < f.tests.size(); ++i) {
        const writers::FeedbackTest& t = f.tests[i];
        if (!t.detailed) continue;
        out << "<section class=\"test " << writers::outcomeClass(t.outcome) << "\" id=\"test-" << i + 1 << "\">\n"
            << "<h3>" << htmlText(t.result->name) << "</h3>\n<p><strong>" << t.points << "</strong> "
            << writers::outcomeBadge(t.outcome) << " ";
        if (t.hidden) {
            out << "A hidden test: your instructor has the details.</p>\n</section>\n";
            continue;
        }
        out << htmlText(t.result->reason) << "</p>\n";
        if (!t.result->feedback.empty()) {
            out << "<ul>\n";
            for (const std::string& line : t.result->feedback) out << "<li>" << htmlText(line) << "</li>\n";
            out << "</ul>\n";
        }
        if (!t.reproduce.empty()) out << "<p>Reproduce: <code>" << htmlText(t.reproduce) << "</code></p>\n";
        out << "</section>\n";
    }

    if (!f.attached.empty()) {
        out << "<p>Drawn from your model, beside this file:";
        for (const std::string& name : f.attached) {
            out << " <a href=\"" << writers::urlSegment(name) << "\">" << htmlText(name) << "</a>";
        }
        out << "</p>\n";
    }
    if (!f.manual.empty()) {
        out << "<h2>Graded by hand" << (f.manualPoints > 0 ? ", " + points(f.manualPoints) + " points pending" : "")
            << "</h2>\n<ul>\n";
        for (const ManualGrade& m : f.manual) {
            out << "<li>" << htmlText(m.name) << ": "
                << (m.points ? points(*m.points) + "/" + points(m.maxPoints) : "pending (" + points(m.maxPoints) + ")");
            if (!m.comment.empty()) out << " <span class=\"muted\">" << htmlText(m.comment) << "</span>";
            if (m.earlierFile) out << " <span class=\"badge\">" << writers::kEarlierFile << "</span>";
            out << "</li>\n";
        }
        out << "</ul>\n";
    }
    out << "<footer>";
    if (!f.sandbox.empty()) out << "Your code ran in simlab's sandbox: " << htmlText(f.sandbox) << ".<br>\n";
    out << "Check your file on the visible tests with <code>" << htmlText(f.check) << "</code>.</footer>\n";
    out << writers::pageEnd();
    return out.str();
}

}  // namespace simlab::engine
