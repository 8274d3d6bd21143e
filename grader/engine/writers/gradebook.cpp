// gradebook.csv: one row per student, the points of each test.
#include <algorithm>
#include <sstream>

#include "simlab/engine/report.h"
#include "simlab/engine/text.h"
#include "simlab/engine/writers.h"

namespace simlab::engine {

std::string gradebookCsv(const Rubric& rubric, const std::vector<StudentRecord>& records) {
    std::ostringstream out;
    out << "student,score,max,status";
    for (const RubricTest& t : rubric.tests) out << "," << csvCell(t.name);
    // Items a person grades: a column each, "pending" until the instructor fills in the points.
    for (const ManualItem& m : rubric.manual) out << "," << csvCell("manual (" + points(m.points) + "): " + m.name);
    out << "\n";
    for (const StudentRecord& r : records) {
        out << csvCell(r.id) << "," << points(r.score) << "," << points(r.maxScore) << "," << csvCell(r.status);
        for (const RubricTest& t : rubric.tests) {
            const auto found = std::find_if(r.tests.begin(), r.tests.end(),
                                            [&](const TestResult& x) { return x.name == t.name; });
            out << "," << (found == r.tests.end() ? "" : points(found->score));
        }
        for (std::size_t i = 0; i < rubric.manual.size(); ++i) out << ",pending";
        out << "\n";
    }
    return out.str();
}

}  // namespace simlab::engine
