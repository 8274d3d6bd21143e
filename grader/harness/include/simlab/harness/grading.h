// What a grader test case can say beyond pass or fail: the figure it measured, partial credit, feedback,
// and the thresholds the rubric sets for it.
//
//     TEST_CASE("y at the final time has the target accuracy digits", "[apple]") {
//         const double digits = ...;
//         CHECK(grading::atLeast(digits, grading::param("floor"), grading::param("target"), "digits"));
//     }
//
// Each test case runs in its own process under `simlab check` / `simlab grade`; a listener reports its result to
// the engine through a private channel (see harness.cpp), never through the test's stdout.
#pragma once

#include <string>
#include <vector>

namespace simlab {
struct Plot;
}

namespace simlab::grading {

/// The rubric's number `key` for the running test (e.g. "target"). Throws if the rubric has none.
double param(const std::string& key);

/// Record the figure this test measured and the one line that explains it, e.g.
/// measured(9.8, "digits", "9.8 digits, need 10"). The line is the test's reason in the report.
void measured(double value, const std::string& unit, const std::string& text);

/// Credit (0 to 1) the test earns if it fails. Without it a failing test earns nothing.
void partialCredit(double fraction);

/// A further line of feedback for the student, shown under the test.
void feedback(const std::string& line);

/// A figure that should reach `target` (digits, say): records it ("9.8 digits, need 10") and gives partial
/// credit in proportion between `floor` (none) and `target` (full). Returns value >= target.
bool atLeast(double value, double floor, double target, const std::string& unit);

/// A figure that should not exceed `allowed`: records it as "<what> <value>, allowed <allowed>".
/// Returns value <= allowed (false for NaN).
bool atMost(double value, double allowed, const std::string& what);

/// A measured value beside the one expected: "y(4) = +88.4 m, expected -68.4 m" for
/// compared("y(4)", 88.4, -68.4, "m"). Each is shown to as many significant digits (3 at least, 17 at most) as it
/// takes to tell them apart, and signed where their signs differ.
std::string compared(const std::string& what, double value, double expected, const std::string& unit);

/// compared() for vectors: "w_B(4) = (6.91, 0.2, 0.15) rad/s, expected (7, 0.2, 0.15) rad/s", every component to as
/// many digits as it takes to tell the two apart, all signed where any two differ in sign.
std::string compared(const std::string& what, const std::vector<double>& value, const std::vector<double>& expected,
                     const std::string& unit);

/// The value that reveals a failed figure's mistake, at its worst point (a compared(), and what it means): a
/// failing test's reason shows it after its figure, "0.0 digits, need 10: y(4) = +88.4 m, expected -68.4 m"; a
/// passing test's shows the figure alone. The last call of a test counts.
void worstPoint(const std::string& text);

/// A file for the student's feedback folder, e.g. attach("schematic-tree.svg", svg): a plain name (letters,
/// digits, '.', '-', '_'; no leading dot), at most 256 KiB, three per test. simlab writes it beside the report.
void attach(const std::string& name, const std::string& text);

/// Draws `plot` as SVG (simlab/plot.h, with gnuplot) and attaches it as `name`, which ends in ".svg": the student's
/// run as their feedback page shows it. A drawing that cannot be made (no gnuplot, a file over the size) is said on
/// the judge's output, for instructors, and leaves the test as it was: a picture is never part of a verdict.
void attachPlot(const std::string& name, const Plot& plot);

/// The path of a file the student handed in beside their source (one of the rubric's extra_files). Throws,
/// saying where the file belongs, if they did not.
std::string submissionFile(const std::string& name);

/// An entry for the platform's leaderboard (Gradescope's): a figure this test measured, ranked lowest first
/// ("asc") or highest first ("desc").
void leaderboard(const std::string& name, double value, const std::string& order);

/// What picks the student's own scene of a question: on where the rubric's [variants] has per_student and the engine
/// names the student (a class's folder, autograde's metadata, check --student).
struct StudentVariant {
    bool on = false;
    std::string seed;
    std::string student;
};
StudentVariant studentVariant();

/// Format a number the way reports show it: 3 significant digits, scientific when small or large.
std::string show(double value);

/// "y(4)" for at("y", 4): a quantity at a time, as a reason names it (the time to 6 significant digits).
std::string at(const std::string& quantity, double time);

}  // namespace simlab::grading
