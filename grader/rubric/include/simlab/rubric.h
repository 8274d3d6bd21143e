// Rubric: an assignment's points, thresholds and limits, in one TOML file an instructor can edit.
//
//     assignment = "apple"
//     title = "Newton's apple"
//     submission = "NewtonsApple.cpp"      # the file each student hands in
//     extra_files = ["BookAnswers.toml"]   # optional: more files handed in beside it, which tests may read
//
//     [limits]                             # per test case, each in its own process
//     wall_seconds = 5
//
//     [[test]]
//     name = "y at the final time has the target accuracy digits"   # the Catch2 test case's name
//     points = 20
//     visibility = "visible"               # or hidden, after_due_date, after_published (Gradescope's words)
//     floor = 4                            # any other key is a number the test reads with grading::param
//     target = 10
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

/// Resource limits for one test case.
struct Limits {
    double wallSeconds = 5;   ///< real time
    double cpuSeconds = 5;    ///< processor time
    long memoryMiB = 2048;    ///< address space
    long outputKiB = 1024;    ///< stdout + stderr; more is cut off and the test is stopped
    long fileMiB = 16;        ///< largest file the test may write
    long processes = 32;      ///< processes and threads at once
};

struct RubricTest {
    std::string name;
    double points = 0;
    std::string visibility = "visible";
    std::string description;
    std::map<std::string, double> params;

    /// Visible tests run in a student's self-check; the others only when an instructor grades.
    bool visible() const { return visibility == "visible"; }
};

struct Rubric {
    std::string path;
    std::string assignment;
    std::string title;
    std::string submission;
    std::vector<std::string> extraFiles;  ///< handed in beside the submission; tests read them by name
    Limits limits;
    std::vector<RubricTest> tests;

    double totalPoints() const;
    /// The test of that name, or nullptr.
    const RubricTest* find(const std::string& name) const;
};

/// Read and check a rubric file. Throws RubricError.
Rubric loadRubric(const std::string& path);

/// Characters a test name may not hold: Catch2 reads them as test-spec syntax.
bool isValidTestName(const std::string& name, std::string* why = nullptr);

}  // namespace simlab
