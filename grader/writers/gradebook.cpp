// gradebook.csv: one row per student, the points of each test and of each item graded by hand (manual.csv); the
// score is the tests' points and the manual points given so far, less a late penalty, the max every point there is.
#include <algorithm>
#include <sstream>

#include "simlab/grading/report.h"
#include "simlab/common/text.h"
#include "simlab/writers/writers.h"

namespace simlab::engine {

std::string gradebookCsv(const Rubric& rubric, const std::vector<StudentRecord>& records) {
    std::ostringstream out;
    // With a late policy (course.toml): the score before it, the points it took, when and how late.
    const bool late =
        std::any_of(records.begin(), records.end(), [](const StudentRecord& r) { return !r.late.line.empty(); });
    // With a bank of slip days: the days this lab spent and those left after it.
    const bool slip =
        std::any_of(records.begin(), records.end(), [](const StudentRecord& r) { return !r.late.slip.ledger.empty(); });
    out << "student,score,max,status";
    if (late) out << ",raw score,late penalty,submitted,lateness";
    if (slip) out << ",slip days used,slip days left,slip days";
    for (const RubricTest& t : rubric.tests) out << "," << csvCell(t.name);
    // Items a person grades: a column each, "pending" until the instructor fills in the points.
    for (const ManualItem& m : rubric.manual) out << "," << csvCell("manual (" + points(m.points) + "): " + m.name);
    out << "\n";
    for (const StudentRecord& r : records) {
        out << csvCell(r.id) << "," << points(r.total()) << "," << points(r.maxTotal()) << ","
            << csvCell(statusName(r.status));
        if (late) {
            out << "," << points(r.rawTotal()) << "," << points(r.latePoints()) << "," << csvCell(r.submitted) << ","
                << csvCell(r.late.line);
        }
        if (slip) {
            const StudentRecord::Lateness::Slip& s = r.late.slip;
            out << ",";
            if (!s.ledger.empty()) out << s.used << "," << s.had - s.used << "," << csvCell(s.ledger);
            else out << ",,";
        }
        for (const RubricTest& t : rubric.tests) {
            const auto found = std::find_if(r.tests.begin(), r.tests.end(),
                                            [&](const TestResult& x) { return x.name == t.name; });
            out << "," << (found == r.tests.end() ? "" : points(found->score));
        }
        for (const ManualItem& m : rubric.manual) {
            const auto given = std::find_if(r.manual.begin(), r.manual.end(),
                                            [&](const ManualGrade& g) { return g.name == m.name; });
            out << "," << (given != r.manual.end() && given->points ? points(*given->points) : "pending");
        }
        out << "\n";
    }
    return out.str();
}

}  // namespace simlab::engine
