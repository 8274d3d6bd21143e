// Grading one submission: build its probe, then run each rubric test as two limited processes - the judge, which
// holds the tests and decides, and the probe, which holds the student's code and answers the judge's questions
// with observations - and name how each test ended.
#pragma once

#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "simlab/build/build.h"
#include "simlab/common/files.h"
#include "simlab/common/status.h"
#include "simlab/build/manifest.h"
#include "simlab/protocol/verdict.h"
#include "simlab/rubric/rubric.h"

namespace simlab::engine {

/// How a test ended. Every outcome has a name in the report.
enum class Outcome {
    Passed, Failed, TimedOut, Stalled, OutOfMemory, OutOfDisk, Crashed, OutputTruncated, BadReport, DidNotFinish,
    DidNotCompile, Refused, MissingFile
};

/// "passed", "failed", "timed out", "stalled", "killed for memory", "killed for disk", "crashed", "output
/// truncated", "bad report", "did not finish", "did not compile", "refused", "missing file".
std::string outcomeName(Outcome outcome);
/// The outcome of that name; throws std::invalid_argument for another.
Outcome outcomeNamed(const std::string& name);

/// An entry of Gradescope's leaderboard a test gave: a figure it measured, ranked "asc" (lowest first) or "desc",
/// as the judge's verdict holds it.
using wire::BoardEntry;
/// A file a test made for the student's feedback (a drawing of the model): its name and its bytes, as the judge's
/// verdict holds it.
using wire::Attachment;

struct TestResult {
    std::string name;
    std::string visibility;
    double maxScore = 0;
    double score = 0;
    double credit = 0;                  ///< the share of its points the judge gave, 0 to 1 (score = points x credit)
    Outcome outcome = Outcome::DidNotFinish;
    std::string reason;                 ///< one line: the measured figure, or why it failed
    std::vector<std::string> feedback;  ///< further lines for the student
    std::optional<double> figure;       ///< what the test measured, e.g. 14.8
    std::string unit;                   ///< e.g. "digits"
    std::vector<BoardEntry> leaderboard;  ///< for results.json's leaderboard (the trade question's figures)
    double seconds = 0;                 ///< the test's time in its judge, its student's process included
    double cpuSeconds = 0;              ///< the student's process's CPU time
    /// The judge's shared questions the test used (observe::askShared), by digest: the seconds the answer took
    /// where this test computed it, 0 where an earlier test of its judge had.
    std::map<std::string, double> shared;
    std::string output;                 ///< what the student's process printed (cut short), for instructors
    std::vector<Attachment> attachments;  ///< files the test made for the student's feedback
};

struct GradeReport {
    std::string assignment;
    std::string title;
    std::string source;             ///< the file graded, as reports name it
    BuildResult build;
    std::vector<TestResult> tests;  ///< those that ran (all, or the visible ones in a self-check)
    int notRunCount = 0;            ///< tests left for the instructor in a self-check
    double notRunPoints = 0;
    std::vector<ManualItem> manual; ///< the rubric's items graded by a person: pending, not in score()
    double seconds = 0;
    SubmissionStatus status = SubmissionStatus::Graded;
    std::string note;               ///< about the files: "graded apple.cpp; expected NewtonsApple.cpp"
    std::string graderOutput;       ///< what the judge printed (Catch2's account of the tests), for instructors
    std::string sandbox;            ///< the sandbox it ran in, one line (isolation::SandboxSupport::summary)

    double score() const;
    double maxScore() const;
};

/// What one test cost last time (TestResult's seconds and shared), a hint for sharing tests out.
struct TestCost {
    double seconds = 0;
    std::map<std::string, double> shared;
};

/// A test's cost as the judge's end record and check's cost file hold it ({"seconds": S, "shared": {DIGEST: S}}):
/// none unless its seconds are a finite number >= 0; of shared, only digests of up to 16 characters with such a
/// number, at most 256.
std::optional<TestCost> readTestCost(const nlohmann::json& record);

struct GradeOptions {
    bool includeHidden = false;          ///< run every test (instructors), not only the visible ones
    std::optional<Limits> limits;        ///< instead of the rubric's
    std::string workRoot;                ///< parent of the temporary directories; $TMPDIR when empty
    std::vector<std::string> onlyTests;  ///< run just these tests (by name); all selected ones when empty
    /// Judges run at once, each over its share of the tests (each test still alone in its own sandbox, as a user
    /// of its own): a self-check uses the machine's cores; a class, graded a submission per core, uses 1.
    int judges = 1;
    /// How long each test took last time (by name) and the shared questions it used, to share the tests out so
    /// that the judges end together (shareTests). Round-robin in the rubric's order without it.
    std::map<std::string, TestCost> expected;
    /// Told what grading is doing as it goes ("compiling", a test starting), for a person to watch; may be empty.
    std::function<void(const std::string&)> progress;
    /// The object check before the link (isolation::forbiddenCode). Off only where the corpus proves that the
    /// isolation holds without it (`simlab-corpus invariants`); no command of simlab's turns it off.
    bool checkObject = true;
    /// The student's id (a class's folder name, autograde's metadata, check --student): with the rubric's
    /// [variants] per_student, it picks the scene of their trade question. Empty: the question's own scene.
    std::string student;
};

/// The judge (0 to judges - 1) each of `tests` runs in, so that the last judge ends as soon as it can: round-robin
/// in the given order without `expected`. With it, a judge's time is its tests' own plus each shared answer
/// (observe::askShared) its tests ask for, once. Tests are grouped by the answers they share (a test joins when
/// computing its answers again would cost more than the test itself), and the costliest group goes first, each to
/// the judge with the least time so far. A test `expected` does not name counts as long as the longest it does. A
/// judge may be left without tests.
std::vector<std::size_t> shareTests(const std::vector<std::string>& tests,
                                    const std::map<std::string, TestCost>& expected, int judges);

/// What a student handed in, read as data (readHandedIn): the source and the rubric's extra files.
struct SubmissionFiles {
    std::string name;              ///< the source's file name, as the compiler's messages give it
    std::string shown;             ///< how reports name it (a path)
    std::string text;              ///< its bytes
    std::vector<HandedIn> extras;  ///< the rubric's extra files that are there, read or refused
};

/// Throws UsageError unless `id` is a usable student id: at most 256 bytes, no control characters (empty is fine).
void requireStudentId(const std::string& id);

/// Grade `files` for `assignment` with `rubric`. Never throws for anything the student's code or files do; throws
/// UsageError for a test name the rubric does not have, Interrupted if isolation::interruptChildren() cut it short.
GradeReport gradeSubmission(const Builder& builder, const Assignment& assignment, const Rubric& rubric,
                            const SubmissionFiles& files, const GradeOptions& options);

/// Where files are kept apart by their modes alone (limits only), what hidden tests must be kept from: every file
/// of simlab's places (isolation/reach.h: the course, its build and installation, its caches, the labs' folders, a
/// class and its grades, each added before) but what a grading's tools are lent (lentToTools), tried as a test's
/// throwaway user (isolation::exposedPlaces). One line naming the first file it could read and the command that
/// closes the places (`simlab lock`), for the caller to refuse hidden tests with; empty where none can be read,
/// and in the modes whose sandbox keeps the places out of reach whatever their modes (bubblewrap, Landlock).
std::string placesExposed(const Manifest& manifest);
/// Round a score to hundredths, as reports show it.
double roundScore(double points);

/// The status of a build that failed: forbidden code (the object check refused it), did not link, or did not
/// compile.
SubmissionStatus buildFailure(const BuildResult& build);

/// The report of a submission that was not graded (status missing file, unsafe file, file too large):
/// every selected test scores 0 with the note as its reason.
GradeReport notGradedReport(const Assignment& assignment, const Rubric& rubric, SubmissionStatus status,
                            const std::string& note, bool includeHidden);

}  // namespace simlab::engine
