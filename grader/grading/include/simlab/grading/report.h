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

/// What the platforms' documents say of a test (Gradescope's, PrairieLearn's, GitHub Classroom's): `line`, its
/// outcome and reason ("failed: 3.1 digits"), and `more`, a line per feedback line ("- ...") and, when it did not
/// compile, the compiler's first lines as the record keeps them; every text printable.
struct TestAccount {
    std::string line;
    std::vector<std::string> more;
    /// line and more, a line each: the test's output in results.json.
    std::string text() const;
};
TestAccount testAccount(const StudentRecord& record, const TestResult& test);

/// What the platforms' documents say of the submission above its tests (results.json's output): the note, the
/// build line, the sandbox, the compiler's message (when it failed or warned), the hidden tests left, the manual
/// items, the lateness and slip days; every text printable.
std::string recordAccount(const StudentRecord& record);

/// The record as a Gradescope results.json document: top-level score and output, one entry per test with
/// name, score, max_score, status (passed/failed), output and visibility; the manual items, pending or graded.
nlohmann::json toGradescope(const StudentRecord& record);
/// toGradescope(recordOf(report)).
nlohmann::json toGradescope(const GradeReport& report);

}  // namespace simlab::engine
