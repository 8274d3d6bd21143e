// report.html: the class at a glance, for the instructor.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <sstream>

#include "common.h"
#include "simlab/writers/html.h"
#include "simlab/grading/report.h"
#include "simlab/common/text.h"
#include "simlab/writers/writers.h"

namespace simlab::engine {

namespace {

using writers::htmlText;
using writers::number;

constexpr int kScoreBins = 10;           // the score histogram's bins, each a tenth of the points
constexpr int kFigureBins = 10;          // a figure's distribution, between its min and max
constexpr double kFigureBarWidth = 20;   // the one bar of a figure every student shares
constexpr double kLogSpan = 1e3;         // positive values spanning this factor or more are drawn on log axes
constexpr std::size_t kListed = 10;      // the lowest scores and the slowest submissions listed
constexpr std::size_t kNoteChars = 240;  // a note longer than this (in bytes) is cut

// A coordinate in an SVG.
std::string at(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", v);
    return text;
}

std::string plural(std::size_t n, const std::string& one, const std::string& many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

// The start of printable `text`, cut on a character boundary, "…" added when cut.
std::string shortened(const std::string& text, std::size_t limit) {
    std::string s = printable(text);
    if (s.size() <= limit) return s;
    std::size_t cut = limit;
    while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;
    return s.substr(0, cut) + "\u2026";
}

std::string studentLink(const std::string& id) {
    return "<a href=\"students/" + writers::urlSegment(id) + "/feedback.html\">" + htmlText(id) + "</a>";
}

// --- The scores -------------------------------------------------------------------------------------------------

std::string scoreHistogram(const std::vector<StudentRecord>& records, double total) {
    std::vector<int> counts(kScoreBins, 0);
    for (const StudentRecord& r : records) {
        const double of = r.maxTotal() > 0 ? r.maxTotal() : total;
        const double fraction = of > 0 && std::isfinite(r.total()) ? std::clamp(r.total() / of, 0.0, 1.0) : 0.0;
        ++counts[std::min(kScoreBins - 1, static_cast<int>(fraction * kScoreBins))];
    }
    const int most = std::max(1, *std::max_element(counts.begin(), counts.end()));
    const double width = 640, height = 180, left = 8, top = 18, bottom = 22, gap = 6;
    const double slot = (width - left) / kScoreBins;
    // Its text alternative: the count of each tenth that has students.
    std::string said = "Students per tenth of the points";
    for (int i = 0, listed = 0; i < kScoreBins; ++i) {
        if (counts[i] == 0) continue;
        said += std::string(listed++ ? "; " : ": ") + points(total * i / kScoreBins) + " to " +
                (i + 1 == kScoreBins ? points(total) + " inclusive" : "under " + points(total * (i + 1) / kScoreBins)) +
                ", " + plural(counts[i], "student", "students");
    }
    std::ostringstream svg;
    svg << "<svg width=\"" << at(width + 8) << "\" height=\"" << at(height) << "\" role=\"img\" aria-label=\""
        << htmlText(said) << "\">\n";
    svg << "<line class=\"axis\" x1=\"" << at(left) << "\" x2=\"" << at(width) << "\" y1=\""
        << at(height - bottom) << "\" y2=\"" << at(height - bottom) << "\"/>\n";
    for (int i = 0; i < kScoreBins; ++i) {
        const double x = left + i * slot;
        const double h = counts[i] == 0 ? 0 : std::max(2.0, (height - top - bottom) * counts[i] / most);
        const std::string from = points(total * i / kScoreBins), to = points(total * (i + 1) / kScoreBins);
        svg << "<rect class=\"bar\" x=\"" << at(x + gap / 2) << "\" y=\"" << at(height - bottom - h) << "\" width=\""
            << at(slot - gap) << "\" height=\"" << at(h) << "\"><title>" << from << " to "
            << (i + 1 == kScoreBins ? to + " inclusive" : "under " + to) << ": "
            << plural(counts[i], "student", "students") << "</title></rect>\n";
        if (counts[i] > 0) {
            svg << "<text class=\"count\" x=\"" << at(x + slot / 2) << "\" y=\"" << at(height - bottom - h - 4)
                << "\" text-anchor=\"middle\">" << counts[i] << "</text>\n";
        }
        svg << "<text x=\"" << at(x) << "\" y=\"" << at(height - 6) << "\" text-anchor=\"middle\">" << from
            << "</text>\n";
    }
    svg << "<text x=\"" << at(width) << "\" y=\"" << at(height - 6) << "\" text-anchor=\"middle\">" << points(total)
        << "</text>\n</svg>\n";
    return svg.str();
}

// --- Each test --------------------------------------------------------------------------------------------------

std::string passBar(int passed, int graded) {
    const double width = 120, height = 12;
    const double rate = graded > 0 ? double(passed) / graded : 0;
    std::ostringstream svg;
    svg << "<svg width=\"" << at(width) << "\" height=\"" << at(height) << "\" role=\"img\" aria-label=\"" << passed
        << " of " << graded << " passed\"><rect class=\"track\" x=\"0\" y=\"0\" width=\"" << at(width)
        << "\" height=\"" << at(height) << "\" rx=\"3\"/>";
    if (passed > 0) {
        svg << "<rect class=\"passbar\" x=\"0\" y=\"0\" width=\"" << at(width * rate) << "\" height=\"" << at(height)
            << "\" rx=\"3\"/>";
    }
    svg << "</svg>";
    return svg.str();
}

// The values a test measured, as a small histogram between their min and max. Values that span many orders of
// magnitude (an energy drift from 1e-14 to 2) are binned on log axes, with the zeros in a bar of their own.
std::string figureDistribution(const std::vector<double>& sorted, double median, const std::string& unit) {
    std::vector<double> values;
    for (double v : sorted) {
        if (std::isfinite(v)) values.push_back(v);
    }
    if (values.empty()) return "";
    const double lo = values.front(), hi = values.back();
    int zeros = 0;
    double smallestPositive = 0;
    for (double v : values) {
        if (v == 0) ++zeros;
        if (v > 0 && smallestPositive == 0) smallestPositive = v;
    }
    const bool logScale = lo >= 0 && smallestPositive > 0 && hi / smallestPositive >= kLogSpan;
    const double from = logScale ? std::log10(smallestPositive) : lo, to = logScale ? std::log10(hi) : hi;
    const int bins = from == to ? 1 : kFigureBins;
    std::vector<int> counts(bins, 0);
    auto position = [&](double v) {  // 0..1 across the bins
        const double x = logScale ? std::log10(v) : v;
        return from == to ? 0.5 : (x - from) / (to - from);
    };
    for (double v : values) {
        if (logScale && v == 0) continue;
        ++counts[std::min(bins - 1, static_cast<int>(position(v) * bins))];
    }
    const int most = std::max({1, zeros, *std::max_element(counts.begin(), counts.end())});

    const double width = 220, barsHeight = 30, height = 46, zeroWidth = logScale && zeros > 0 ? 16 : 0;
    const double start = zeroWidth > 0 ? zeroWidth + 6 : 0, slot = (width - start) / bins;
    const std::string shownUnit = unit.empty() ? "" : " " + unit;
    auto edge = [&](int k) {  // the value where bin k starts
        const double x = from + (to - from) * k / bins;
        return number(logScale ? std::pow(10.0, x) : x);
    };
    // Its text alternative: the span, and how many students each bar holds.
    std::string said = "from " + number(lo) + " to " + number(hi) + shownUnit + (logScale ? ", log scale" : "");
    if (zeroWidth > 0) said += "; 0" + shownUnit + ": " + std::to_string(zeros);
    for (int i = 0; i < bins && bins > 1; ++i) {
        if (counts[i] > 0) said += "; " + edge(i) + " to " + edge(i + 1) + shownUnit + ": " + std::to_string(counts[i]);
    }
    std::ostringstream svg;
    svg << "<svg width=\"" << at(width) << "\" height=\"" << at(height) << "\" role=\"img\" aria-label=\""
        << htmlText(said) << "\">\n<line class=\"axis\" x1=\"0\" x2=\"" << at(width) << "\" y1=\"" << at(barsHeight)
        << "\" y2=\"" << at(barsHeight) << "\"/>\n";
    auto bar = [&](double x, double w, int count, const std::string& title) {
        if (count == 0) return;
        const double h = std::max(2.0, barsHeight * count / most);
        svg << "<rect class=\"bar\" x=\"" << at(x + 0.5) << "\" y=\"" << at(barsHeight - h) << "\" width=\""
            << at(std::max(1.0, w - 1)) << "\" height=\"" << at(h) << "\"><title>" << htmlText(title) << ": "
            << count << "</title></rect>\n";
    };
    if (zeroWidth > 0) bar(0, zeroWidth, zeros, "0" + shownUnit);
    if (bins == 1) bar((width - kFigureBarWidth) / 2, kFigureBarWidth, counts[0], number(lo) + shownUnit);
    for (int i = 0; i < bins && bins > 1; ++i) {
        bar(start + i * slot, slot, counts[i], edge(i) + " to " + edge(i + 1) + shownUnit);
    }
    // The median, as a line across the bars.
    if (std::isfinite(median) && (!logScale || median > 0 || zeros > 0)) {
        const double x = logScale && median <= 0 ? zeroWidth / 2 : start + (width - start) * position(median);
        svg << "<line class=\"median\" x1=\"" << at(x) << "\" x2=\"" << at(x) << "\" y1=\"0\" y2=\""
            << at(barsHeight + 3) << "\"><title>median " << htmlText(number(median) + shownUnit)
            << "</title></line>\n";
    }
    const double labels = height - 3;
    if (zeroWidth > 0) {
        svg << "<text x=\"" << at(zeroWidth / 2) << "\" y=\"" << at(labels) << "\" text-anchor=\"middle\">0</text>\n";
    }
    if (bins == 1) {
        svg << "<text x=\"" << at(width / 2) << "\" y=\"" << at(labels) << "\" text-anchor=\"middle\">all "
            << htmlText(number(lo)) << "</text>\n";
    } else {
        svg << "<text x=\"" << at(start) << "\" y=\"" << at(labels) << "\">"
            << htmlText(number(logScale ? smallestPositive : lo)) << "</text>\n";
        if (logScale) {
            svg << "<text x=\"" << at(start + (width - start) / 2) << "\" y=\"" << at(labels)
                << "\" text-anchor=\"middle\">log</text>\n";
        }
        svg << "<text x=\"" << at(width) << "\" y=\"" << at(labels) << "\" text-anchor=\"end\">" << htmlText(number(hi))
            << "</text>\n";
    }
    svg << "</svg>";
    return svg.str();
}

std::string testsTable(const Rubric& rubric, const std::vector<StudentRecord>& records) {
    std::ostringstream out;
    out << "<table>\n<thead><tr><th>test</th><th class=\"num\">points</th><th class=\"num\">passed</th><th></th>"
           "<th>measured: median [min, max]</th></tr></thead>\n<tbody>\n";
    for (const writers::TestSummary& s : writers::summarize(rubric, records)) {
        out << "<tr><td class=\"name\">" << htmlText(s.test->name);
        if (!s.test->visible()) out << " <span class=\"muted\">(" << htmlText(s.test->visibility) << ")</span>";
        out << "</td><td class=\"num\">" << points(s.test->points) << "</td><td class=\"num\">";
        if (s.graded > 0) {
            out << s.passed << "/" << s.graded << " (" << static_cast<int>(std::lround(100.0 * s.passed / s.graded))
                << "%)</td><td>" << passBar(s.passed, s.graded);
        } else {
            out << "-</td><td>";
        }
        out << "</td><td>";
        if (s.figures.count > 0) {
            out << htmlText(number(s.figures.median) + " [" + number(s.figures.min) + ", " + number(s.figures.max) +
                            "] " + s.unit)
                << figureDistribution(s.values, s.figures.median, s.unit);
        }
        out << "</td></tr>\n";
    }
    out << "</tbody>\n</table>\n";
    return out.str();
}

// --- Who needs a look, the slowest ---------------------------------------------------------------------------

// A table of students, each linked to their feedback: score, status (flagged unless graded), and with `withTime`
// how long they took and their slowest test; the notes in a column when one has a note.
std::string studentsTable(const std::vector<const StudentRecord*>& rows, bool withTime,
                          const std::function<std::string(const StudentRecord&)>& tests = {}) {
    const bool notes = std::any_of(rows.begin(), rows.end(), [](const StudentRecord* r) { return !r->note.empty(); });
    std::ostringstream out;
    out << "<table>\n<thead><tr><th>student</th><th class=\"num\">score</th>"
        << (withTime ? "<th class=\"num\">seconds</th><th>its slowest test</th>" : "")
        << (tests ? "<th>tests</th>" : "") << "<th>status</th>" << (notes ? "<th>note</th>" : "")
        << "</tr></thead>\n<tbody>\n";
    for (const StudentRecord* r : rows) {
        out << "<tr><td class=\"name\">" << studentLink(r->id) << "</td><td class=\"num\">" << points(r->total()) << "/"
            << points(r->maxTotal()) << "</td>";
        if (withTime) {
            char seconds[32];
            std::snprintf(seconds, sizeof seconds, "%.1f", r->seconds);
            out << "<td class=\"num\">" << seconds << "</td><td class=\"name\">";
            const auto slowest = std::max_element(r->tests.begin(), r->tests.end(), [](const TestResult& a,
                                                                                       const TestResult& b) {
                return a.seconds < b.seconds;
            });
            if (slowest != r->tests.end() && slowest->seconds > 0) {
                std::snprintf(seconds, sizeof seconds, "%.1f", slowest->seconds);
                out << htmlText(slowest->name) << " <span class=\"muted\">(" << seconds << " s, "
                    << htmlText(outcomeName(slowest->outcome)) << ")</span>";
            }
            out << "</td>";
        }
        if (tests) out << "<td class=\"name\">" << htmlText(shortened(tests(*r), kNoteChars)) << "</td>";
        if (r->status == SubmissionStatus::Graded) out << "<td class=\"muted\">graded</td>";
        else out << "<td>" << writers::outcomeBadge(statusName(r->status)) << "</td>";
        if (notes) out << "<td class=\"name\">" << htmlText(shortened(r->note, kNoteChars)) << "</td>";
        out << "</tr>\n";
    }
    out << "</tbody>\n</table>\n";
    return out.str();
}

bool byScore(const StudentRecord* a, const StudentRecord* b) {
    return a->total() != b->total() ? a->total() < b->total() : a->id < b->id;
}

// Whether a test ended other than by passing or failing: it crashed, ran out of time or memory, flooded, broke its
// report, or was refused.
bool endedBadly(Outcome o) {
    return o != Outcome::Passed && o != Outcome::Failed && o != Outcome::MissingFile && o != Outcome::DidNotCompile;
}

// "name (crashed); name (timed out)": the tests of `r` that ended badly.
std::string badEnds(const StudentRecord& r) {
    std::string out;
    for (const TestResult& t : r.tests) {
        if (endedBadly(t.outcome)) out += (out.empty() ? "" : "; ") + t.name + " (" + outcomeName(t.outcome) + ")";
    }
    return out;
}

// Every submission graded as handed in with a test that ended badly, whatever its score, lowest score first.
std::vector<const StudentRecord*> withBadEnds(const std::vector<StudentRecord>& records) {
    std::vector<const StudentRecord*> rows;
    for (const StudentRecord& r : records) {
        if (r.status == SubmissionStatus::Graded && !badEnds(r).empty()) rows.push_back(&r);
    }
    std::sort(rows.begin(), rows.end(), byScore);
    return rows;
}

// Every submission not graded as handed in (any status but "graded"), lowest score first.
std::vector<const StudentRecord*> notGraded(const std::vector<StudentRecord>& records) {
    std::vector<const StudentRecord*> rows;
    for (const StudentRecord& r : records) {
        if (r.status != SubmissionStatus::Graded) rows.push_back(&r);
    }
    std::sort(rows.begin(), rows.end(), byScore);
    return rows;
}

// The lowest scores below full marks among the graded submissions.
std::vector<const StudentRecord*> lowest(const std::vector<StudentRecord>& records) {
    std::vector<const StudentRecord*> rows;
    for (const StudentRecord& r : records) {
        if (r.status == SubmissionStatus::Graded && r.total() < r.maxTotal()) rows.push_back(&r);
    }
    std::sort(rows.begin(), rows.end(), byScore);
    if (rows.size() > kListed) rows.resize(kListed);
    return rows;
}

std::vector<const StudentRecord*> slowest(const std::vector<StudentRecord>& records) {
    std::vector<const StudentRecord*> rows;
    for (const StudentRecord& r : records) {
        if (r.seconds > 0) rows.push_back(&r);
    }
    std::stable_sort(rows.begin(), rows.end(),
                     [](const StudentRecord* a, const StudentRecord* b) { return a->seconds > b->seconds; });
    if (rows.size() > kListed) rows.resize(kListed);
    return rows;
}

// The manual points given to an earlier file than the one graded (manual.h): kept and counted, to confirm.
std::string earlierFileSection(const std::vector<StudentRecord>& records) {
    std::ostringstream rows;
    for (const StudentRecord& r : records) {
        for (const ManualGrade& m : r.manual) {
            if (!m.earlierFile || !m.points) continue;
            rows << "<tr><td class=\"name\">" << studentLink(r.id) << "</td><td class=\"name\">" << htmlText(m.name)
                 << "</td><td class=\"num\">" << points(*m.points) << "/" << points(m.maxPoints) << "</td></tr>\n";
        }
    }
    if (rows.str().empty()) return "";
    return "<section id=\"earlier-file\">\n<h2>Manual points given to an earlier file</h2>\n<p class=\"muted\">The "
           "student's file changed since these points were given in manual.csv. They still count; to confirm them "
           "for the file graded now, clear the row's file cell and run simlab grade again."
           "</p>\n<table>\n<thead><tr><th>student</th><th>item</th><th class=\"num\">points</th></tr></thead>\n"
           "<tbody>\n" +
           rows.str() + "</tbody>\n</table>\n</section>\n";
}

// The course's late policy (course.toml): who lost points to it, gradebook.csv having each one's figures; its bank of
// slip days: what this lab spent of it, and who has none left. Empty without a policy.
std::string lateWork(const std::vector<StudentRecord>& records) {
    std::string text;
    const auto late =
        std::count_if(records.begin(), records.end(), [](const StudentRecord& r) { return r.late.percent > 0; });
    if (std::any_of(records.begin(), records.end(), [](const StudentRecord& r) { return !r.late.line.empty(); })) {
        text = "<p>Late work (course.toml): " +
               (late == 0 ? std::string("nobody lost points to lateness")
                          : plural(static_cast<std::size_t>(late), "student", "students") +
                                " lost points to it (the scores here are after it; "
                                "gradebook.csv has each one's raw score and penalty)") +
               ".</p>\n";
    }
    int bank = 0, spent = 0;
    std::size_t spenders = 0, emptied = 0;
    for (const StudentRecord& r : records) {
        const StudentRecord::Lateness::Slip& s = r.late.slip;
        if (s.ledger.empty()) continue;
        bank = s.bank;
        spent += s.used;
        spenders += s.used > 0;
        emptied += s.had == s.used;
    }
    if (bank == 0) return text;
    return text + "<p>Slip days (course.toml: " + std::to_string(bank) +
           " for each student, spent in the order of the labs' due dates): " +
           (spenders == 0 ? std::string("nobody spent any on this lab")
                          : plural(spenders, "student", "students") + " spent " + std::to_string(spent) +
                                (spent == 1 ? " day" : " days") + " on this lab") +
           "; " + plural(emptied, "student has", "students have") +
           " none left after it (gradebook.csv has each one's ledger).</p>\n";
}

}  // namespace

std::string classReportHtml(const Assignment& assignment, const Rubric& rubric, const ClassResult& result) {
    const std::vector<StudentRecord>& records = result.records;
    // With manual.csv, the points given by hand count, and every point there is is the total.
    const bool byHand = std::any_of(records.begin(), records.end(), [](const StudentRecord& r) { return !r.manual.empty(); });
    const double total = rubric.totalPoints() + (byHand ? rubric.manualPoints() : 0);
    std::vector<double> scores;
    std::map<std::string, int> statuses;
    int pendingStudents = 0;
    for (const StudentRecord& r : records) {
        scores.push_back(r.total());
        ++statuses[statusName(r.status)];
        pendingStudents += r.pendingPoints() > 0;
    }
    const writers::Spread spread = writers::spreadOf(scores);

    std::ostringstream out;
    out << writers::pageStart(assignment.title + " (" + assignment.id + "): the class");
    out << "<header>\n<h1>" << htmlText(assignment.title) << " <span class=\"muted\">(" << htmlText(assignment.id)
        << ")</span>: the class</h1>\n<p class=\"score\">" << plural(records.size(), "student", "students");
    if (!records.empty()) {
        out << ": median <strong>" << number(spread.median) << "</strong>, min " << number(spread.min) << ", max "
            << number(spread.max) << " of " << points(total) << " points";
    }
    out << "</p>\n<p>";
    // "graded" first, then the other statuses in alphabetical order.
    const std::string& graded = statusName(SubmissionStatus::Graded);
    std::string counted;
    if (statuses.count(graded)) counted = graded + ": " + std::to_string(statuses[graded]);
    for (const auto& [status, count] : statuses) {
        if (status != graded) counted += (counted.empty() ? "" : ", ") + status + ": " + std::to_string(count);
    }
    out << htmlText(counted) << (result.skipped.empty() ? "" : "; " + plural(result.skipped.size(), "entry", "entries") +
                                                                   " of the folder skipped")
        << ".</p>\n";
    if (byHand) {
        out << "<p>Graded by hand (manual.csv): " << (pendingStudents == 0
                                                          ? std::string("every student's items have their points")
                                                          : plural(pendingStudents, "student", "students") +
                                                                " with items still pending (their scores hold the "
                                                                "points given so far)")
            << ".</p>\n";
    }
    out << lateWork(records);
    // What the times the lateness was measured from are worth: whose word, and where the sources disagree.
    for (const std::string& line : result.handIns) out << "<p>Hand-in times: " << htmlText(line) << ".</p>\n";
    // The sandboxes the students' code ran in (one, unless the class was graded in parts on other machines).
    std::map<std::string, std::size_t> sandboxes;
    for (const StudentRecord& r : records) {
        if (!r.sandbox.empty()) ++sandboxes[r.sandbox];
    }
    for (const auto& [sandbox, count] : sandboxes) {
        out << "<p class=\"muted\">Sandbox" << (sandboxes.size() > 1 ? " of " + plural(count, "student", "students") : "")
            << ": " << htmlText(sandbox) << ".</p>\n";
    }
    const std::string earlier = earlierFileSection(records);
    out << "<nav><a href=\"#scores\">Scores</a><a href=\"#tests\">Tests</a><a href=\"#attention\">Needs a look</a>"
        << (earlier.empty() ? "" : "<a href=\"#earlier-file\">Earlier files</a>") << "<a href=\"#slowest\">Slowest</a>"
        << (result.skipped.empty() ? "" : "<a href=\"#skipped\">Skipped</a>") << "</nav>\n</header>\n";

    out << "<section id=\"scores\">\n<h2>Scores</h2>\n";
    if (records.empty()) out << "<p>No students.</p>\n";
    else out << "<p class=\"muted\">Students per tenth of the points.</p>\n" << scoreHistogram(records, total);
    out << "</section>\n";

    out << "<section id=\"tests\">\n<h2>Tests</h2>\n<p class=\"muted\">Passed: of the students whose file was built "
           "and run. Measured: what the test measured, and how the students' values spread between the min and the "
           "max (the line is the median).</p>\n"
        << testsTable(rubric, records) << "</section>\n";

    out << "<section id=\"attention\">\n<h2>Needs a look</h2>\n";
    const std::vector<const StudentRecord*> refused = notGraded(records), low = lowest(records),
                                            troubled = withBadEnds(records);
    if (refused.empty() && low.empty() && troubled.empty()) {
        out << "<p>Every submission was graded as handed in and scored full marks.</p>\n";
    }
    if (!refused.empty()) {
        out << "<h3>Not graded as handed in</h3>\n<p class=\"muted\">Any status but graded: the file was missing, "
               "misnamed, refused, did not build, or simlab could not grade it.</p>\n"
            << studentsTable(refused, false);
    }
    if (!troubled.empty()) {
        out << "<h3>A test crashed, ran out of time or memory, or was refused</h3>\n<p class=\"muted\">Every "
               "graded submission with such a test, whatever its score ("
            << troubled.size() << "): the points it lost may be the code's, or the machine's.</p>\n"
            << studentsTable(troubled, false, badEnds);
    }
    if (!low.empty()) {
        out << "<h3>Lowest scores</h3>\n<p class=\"muted\">Graded, below full marks: the " << kListed
            << " lowest at most.</p>\n" << studentsTable(low, false);
    }
    out << "</section>\n" << earlier;

    out << "<section id=\"slowest\">\n<h2>Slowest</h2>\n";
    const std::vector<const StudentRecord*> slow = slowest(records);
    if (slow.empty()) out << "<p>No submission has a time.</p>\n";
    else out << "<p class=\"muted\">The submissions that took longest to grade, " << kListed << " at most.</p>\n"
             << studentsTable(slow, true);
    out << "</section>\n";

    if (!result.skipped.empty()) {
        out << "<section id=\"skipped\">\n<h2>Skipped</h2>\n<p class=\"muted\">Entries of the submissions folder "
               "that are not a student's folder.</p>\n<ul>\n";
        for (const Skipped& s : result.skipped) {
            out << "<li><code>" << htmlText(s.name) << "</code>: " << htmlText(s.why) << "</li>\n";
        }
        out << "</ul>\n</section>\n";
    }
    out << "<footer>Each student's name links to their feedback, <code>students/&lt;id&gt;/feedback.html</code>; "
           "the grades are in <code>gradebook.csv</code>, the figures in <code>summary.csv</code>.</footer>\n";
    out << writers::pageEnd();
    return out.str();
}

}  // namespace simlab::engine
