// results.json: Gradescope's document for a graded submission (report.h's toGradescope), as a file.
#include "common.h"
#include "simlab/engine/record.h"
#include "simlab/engine/report.h"
#include "simlab/engine/writers.h"

namespace simlab::engine {

std::string resultsJson(const StudentRecord& record) { return writers::jsonText(toGradescope(record)); }

std::string resultsJson(const GradeReport& report) { return resultsJson(recordOf(report)); }

}  // namespace simlab::engine
