// results.json: Gradescope's document for a graded submission (report.h's toGradescope), as a file.
#include "common.h"
#include "simlab/grading/record.h"
#include "simlab/grading/report.h"
#include "simlab/writers/writers.h"

namespace simlab::engine {

std::string resultsJson(const StudentRecord& record) { return writers::jsonText(toGradescope(record)); }

std::string resultsJson(const GradeReport& report) { return resultsJson(recordOf(report)); }

}  // namespace simlab::engine
