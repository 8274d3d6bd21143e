// Reports of a graded submission: the text a student reads and Gradescope's results.json.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "simlab/grading/grade.h"
#include "simlab/grading/record.h"

namespace simlab::engine {

/// "12.5" or "20": points as reports print them.
std::string points(double value);

/// One line per test ("  20/20  passed           <name>: <reason>"), feedback indented under it, the build's
/// messages when it failed, then "Score: N/M" and what is left for the instructor.
std::string renderText(const GradeReport& report);

/// What a record keeps of the report (no id, key or file: the class names those); its manual items pending.
StudentRecord recordOf(const GradeReport& report);

/// The record as a Gradescope results.json document: top-level score and output, one entry per test with
/// name, score, max_score, status (passed/failed), output and visibility; the manual items, pending or graded.
nlohmann::json toGradescope(const StudentRecord& record);
/// toGradescope(recordOf(report)).
nlohmann::json toGradescope(const GradeReport& report);

}  // namespace simlab::engine
