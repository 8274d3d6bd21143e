// Rubric: an assignment's points, thresholds and limits, in one TOML file an instructor can edit.
//
//     assignment = "apple"
//     title = "Newton's apple"
//     submission = "NewtonsApple.cpp"      # the file each student hands in
//     extra_files = ["BookAnswers.toml"]   # optional: more files handed in beside it, which tests may read
//
//     [limits]                             # per test case: the student's process (the probe)
//     cpu_seconds = 5                      # CPU time: past it the test has "timed out"
//     wall_seconds = 30                    # a net for code that sleeps or blocks ("stalled")
//
//     [[test]]
//     name = "y at the final time has the target accuracy digits"   # the Catch2 test case's name
//     points = 20
//     visibility = "visible"               # or hidden, after_due_date, after_published (Gradescope's words)
//     floor = 4                            # any other key is a number the test reads with grading::param
//     target = 10
//
//     [[manual]]                           # graded by a person: listed as pending, with its points
//     name = "the schematic is clear"
//     points = 10
//
//     [variants]                           # optional: each student's own trade scene (trade_question.h)
//     per_student = true
//     seed = "fall 2026"                   # with the student's id, picks their scene from the pool
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace simlab {

/// A rubric that cannot be used; what() is one line "file:line:column: what is wrong".
class RubricError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Resource limits for one test case's student process, and for what a student hands in. CPU time decides "timed
/// out", whatever the machine's load; the wall clock is only a net for code that sleeps or blocks.
struct Limits {
    double wallSeconds = 30;   ///< real time: a generous net ("stalled")
    double cpuSeconds = 5;     ///< processor time ("timed out")
    long memoryMiB = 2048;     ///< address space
    long outputKiB = 1024;     ///< stdout + stderr; more is cut off and the test is stopped
    long fileMiB = 16;         ///< largest file the test may write, and the size of its scratch folders
    long processes = 32;       ///< processes and threads at once
    long observationMiB = 64;  ///< largest answer the student's process may send the judge
    long submissionKiB = 1024; ///< largest file a student may hand in

    /// Throws std::invalid_argument naming the limit, its value and its range, unless every limit is within its
    /// range (see limitRanges) and the wall-clock net is at least the CPU time.
    void check() const;
};

/// A limit's rubric key, its range and its unit: the one table the rubric reader and the command line check.
struct LimitRange {
    const char* key;
    double min, max;
    const char* unit;
};
const std::vector<LimitRange>& limitRanges();
/// The range of the rubric key `key` ("cpu_seconds"); throws std::invalid_argument for an unknown key.
const LimitRange& limitRange(const std::string& key);
/// "cpu_seconds must be between 0.1 and 3600 s, got 1e+10"; empty if `value` is within the range.
std::string outOfRange(const LimitRange& range, double value);

struct RubricTest {
    std::string name;
    double points = 0;
    std::string visibility = "visible";
    std::string description;
    std::map<std::string, double> params;

    /// Visible tests run in a student's self-check; the others only when an instructor grades.
    bool visible() const { return visibility == "visible"; }
};

/// A part of the grade only a person can judge (the clarity of a drawing, say): listed with its points as pending.
struct ManualItem {
    std::string name;
    double points = 0;
    std::string description;
};

/// Whether each student answers the trade question on a scene of their own, picked from its data file's pool by
/// the hash of `seed` and their id.
struct Variants {
    bool perStudent = false;
    std::string seed;
};

struct Rubric {
    std::string path;
    std::string assignment;
    std::string title;
    std::string submission;
    std::vector<std::string> extraFiles;  ///< handed in beside the submission; tests read them by name
    Limits limits;
    std::vector<RubricTest> tests;
    std::vector<ManualItem> manual;  ///< graded by hand, beside the tests
    Variants variants;

    /// Points of the tests (what simlab grades).
    double totalPoints() const;
    /// Points of the manual items (pending until a person grades them).
    double manualPoints() const;
    /// The test of that name, or nullptr.
    const RubricTest* find(const std::string& name) const;
};

/// Read and check a rubric file. Throws RubricError.
Rubric loadRubric(const std::string& path);
/// Read and check the rubric `document`, as the file `path` would hold it (errors name `path`). Throws RubricError.
Rubric readRubric(const std::string& document, const std::string& path);

/// Characters a test name may not hold: Catch2 reads them as test-spec syntax.
bool isValidTestName(const std::string& name, std::string* why = nullptr);

}  // namespace simlab
