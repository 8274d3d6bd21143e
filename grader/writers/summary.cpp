// The class summary per test: summary.csv, and the table `simlab grade` prints at the end.
#include <cstdio>
#include <sstream>

#include "common.h"
#include "simlab/grading/report.h"
#include "simlab/common/text.h"
#include "simlab/writers/writers.h"

namespace simlab::engine {

using writers::number;

std::string summaryCsv(const Rubric& rubric, const std::vector<StudentRecord>& records) {
    std::ostringstream out;
    out << "test,visibility,points,graded,passed,pass_rate,figure,median,min,max\n";
    for (const writers::TestSummary& s : writers::summarize(rubric, records)) {
        out << csvCell(s.test->name) << "," << s.test->visibility << "," << points(s.test->points) << ","
            << s.graded << "," << s.passed << "," << (s.graded ? number(double(s.passed) / s.graded) : "") << ","
            << csvCell(s.unit) << "," << number(s.figures.median) << "," << number(s.figures.min) << ","
            << number(s.figures.max) << "\n";
    }
    return out.str();
}

std::string summaryTable(const Rubric& rubric, const std::vector<StudentRecord>& records) {
    std::ostringstream out;
    std::vector<double> scores;
    bool byHand = false;
    for (const StudentRecord& r : records) {
        scores.push_back(r.total());
        byHand = byHand || !r.manual.empty();
    }
    const writers::Spread total = writers::spreadOf(scores);
    out << "Class of " << records.size() << ": median " << number(total.median) << ", min " << number(total.min)
        << ", max " << number(total.max) << " of "
        << points(rubric.totalPoints() + (byHand ? rubric.manualPoints() : 0)) << " points\n";
    char line[256];
    std::snprintf(line, sizeof line, "  %-6s %-6s  %-44s  %s\n", "passed", "points", "measured: median [min, max]",
                  "test");
    out << line;
    for (const writers::TestSummary& s : writers::summarize(rubric, records)) {
        const std::string rate = s.graded ? std::to_string(s.passed) + "/" + std::to_string(s.graded) : "-";
        std::string figure;
        if (s.figures.count > 0) {
            figure = number(s.figures.median) + " [" + number(s.figures.min) + ", " + number(s.figures.max) + "] " +
                     s.unit;
        }
        std::snprintf(line, sizeof line, "  %-6s %-6s  %-44s  %s\n", rate.c_str(), points(s.test->points).c_str(),
                      figure.substr(0, 44).c_str(), s.test->name.c_str());
        out << line;
    }
    return out.str();
}

}  // namespace simlab::engine
