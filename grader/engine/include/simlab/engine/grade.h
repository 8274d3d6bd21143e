// Grading one submission: build it against the assignment's grader and run each rubric test in its own
// limited process.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "simlab/engine/build.h"
#include "simlab/engine/manifest.h"
#include "simlab/rubric.h"

namespace simlab::engine {

/// How a test ended. Every outcome has a name in the report.
enum class Outcome {
    Passed, Failed, TimedOut, OutOfMemory, Crashed, OutputTruncated, DidNotFinish, DidNotCompile, MissingFile
};

/// "passed", "failed", "timed out", "killed for memory", "crashed", "output truncated", "did not finish",
/// "did not compile", "missing file".
std::string outcomeName(Outcome outcome);
/// The outcome of that name; throws std::invalid_argument for another.
Outcome outcomeNamed(const std::string& name);

struct TestResult {
    std::string name;
    std::string visibility;
    double maxScore = 0;
    double score = 0;
    Outcome outcome = Outcome::DidNotFinish;
    std::string reason;                 ///< one line: the measured figure, or why it failed
    std::vector<std::string> feedback;  ///< further lines for the student
    std::optional<double> figure;       ///< what the test measured, e.g. 14.8
    std::string unit;                   ///< e.g. "digits"
    double seconds = 0;
    std::string output;                 ///< what the test process printed (cut short), for instructors
};

struct GradeReport {
    std::string assignment;
    std::string title;
    std::string source;
    BuildResult build;
    std::vector<TestResult> tests;  ///< those that ran (all, or the visible ones in a self-check)
    int notRunCount = 0;            ///< tests left for the instructor in a self-check
    double notRunPoints = 0;
    double seconds = 0;
    std::string status = "graded";  ///< or "misnamed file", "missing file", "did not compile", "did not link"
    std::string note;               ///< about the file: "graded apple.cpp; expected NewtonsApple.cpp"

    double score() const;
    double maxScore() const;
};

struct GradeOptions {
    bool includeHidden = false;          ///< run every test (instructors), not only the visible ones
    std::optional<Limits> limits;        ///< instead of the rubric's
    std::string workRoot;                ///< parent of the temporary directories; $TMPDIR when empty
    int slot = 0;                        ///< which sandbox user runs the tests (one per concurrent grading)
    std::vector<std::string> onlyTests;  ///< run just these tests (by name); all selected ones when empty
};

/// Grade `source` for `assignment` with `rubric`. Never throws for anything the student's code does; throws
/// UsageError for a source that is not a readable C++ file.
GradeReport gradeSource(const Builder& builder, const Assignment& assignment, const Rubric& rubric,
                        const std::string& source, const GradeOptions& options);

/// Round a score to hundredths, as reports show it.
double roundScore(double points);

/// The report of a submission that has no file to grade: every selected test scores 0 as "missing file".
GradeReport missingReport(const Assignment& assignment, const Rubric& rubric, const std::string& note,
                          bool includeHidden);

}  // namespace simlab::engine
