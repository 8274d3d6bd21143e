// Grading a class: every student's folder, in parallel, resumable, with a gradebook and a summary.
//
// Output folder layout:
//     gradebook.csv                  student, score, max, status, then the points of each test
//     summary.csv                    per test: pass rate and the spread of what it measured
//     report.html                    the class at a glance: scores, each test, who needs a look, the slowest
//     students/<id>/results.json     Gradescope's schema
//     students/<id>/feedback.md      what the student reads
//     students/<id>/feedback.html    the same as a page
//     students/<id>/record.json      what simlab keeps to resume: the grade and the key it was made with
// Each student's files are written atomically as they finish, record.json last, and gradebook.csv is rewritten
// (atomically) from the records after each one. A run killed at any moment loses at most the students being
// graded; the next run regrades exactly those whose record is missing or whose key changed (the submission's
// content, the grader, the rubric or the limits). An interrupt records nothing for a student it cut short.
// summary.csv and report.html are written (atomically) at the end of every run, an interrupted or resumed one
// too; a kept record whose feedback.html is missing (graded by an earlier simlab) gets one then.
//
// Folder and file names, compiler messages and test output are bytes from students: every writer makes them
// safe for its format (valid UTF-8 in JSON, control characters escaped for terminals and Markdown, formulas
// neutralized in CSV, every text escaped in HTML), and a student's files are read as data (files.h: readHandedIn).
// The writers of these formats are in writers.h, one file each under writers/.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "simlab/grading/grade.h"
#include "simlab/course/manual.h"
#include "simlab/course/policy.h"
#include "simlab/grading/record.h"
#include "simlab/writers/writers.h"

namespace simlab::engine {

/// Which file of a student's folder is graded.
struct Submission {
    std::string folder;  ///< the folder that holds it: the student's, or one of its subfolders
    std::string name;    ///< its file name; empty when none was found
    std::string shown;   ///< its path relative to the student's folder, as reports show it
    SubmissionStatus status = SubmissionStatus::MissingFile;  ///< Graded, MisnamedFile (the one C++ file there is
                                                              ///< graded) or MissingFile
    std::string note;    ///< e.g. "graded apple.cpp; expected NewtonsApple.cpp"
};

/// Look for `expected` in `folder` (and its subfolders when `recursive`), never following a link; failing that,
/// a lone C++ file. `followFolder` false: `folder` itself must not be a link (a student's folder in a class).
Submission findSubmission(const std::string& folder, const std::string& expected, bool recursive,
                          bool followFolder = false);

/// A student's folder made ready to grade: the file found and read with the rubric's extra files, or why not
/// (status missing file, unsafe file or file too large, with a one-line note).
struct Gathered {
    Submission found;
    std::optional<SubmissionFiles> files;  ///< empty when there is nothing to grade
    SubmissionStatus status = SubmissionStatus::MissingFile;  ///< found.status, or why nothing is graded
    std::string note;
};
Gathered gatherSubmission(const std::string& folder, const Rubric& rubric, const Limits& limits, bool recursive,
                          bool followFolder);

struct ClassProgress {
    int done = 0;     ///< students finished, reused ones included
    int total = 0;
    int reused = 0;   ///< unchanged since the last run: not regraded
    double elapsed = 0;
    double eta = -1;  ///< seconds left, once it can be estimated
    const StudentRecord* last = nullptr;  ///< the student just finished
    bool lastReused = false;
};

struct ClassOptions {
    int jobs = 1;
    std::vector<std::string> only;  ///< regrade just these students; keep everyone else's row
    GradeOptions grade;             ///< per submission (limits, work folder)
    /// One share of the class (shard of shards, from 1): the students at positions shard - 1, shard - 1 + shards,
    /// ... of the class in name order, graded into the students' folders alone; the gradebook, the summary, the
    /// report and the sheet of manual points are left to a whole-class run, which assembles them. 0: the class.
    int shard = 0;
    int shards = 0;
    /// The points given by hand (readManualSheet), read by the caller before anything changes; a shard has no use
    /// for them.
    ManualSheet manual;
    /// The course's late policy for the assignment (policy.h), and each student's hand-in as the platform or the
    /// instructor gave it (its time, how it is known, the platform's late flag), by id; a student not in it is
    /// timed by their file's own time. `handInNotes` is what the run says of those times (checkHandIns), for the
    /// report.
    LatePolicy late;
    HandIns submitted;
    std::vector<std::string> handInNotes;
    /// The caller holds the output folder's lock (OutputLock) already, taken before it wrote anything there.
    bool locked = false;
};

/// Grade every student folder of `submissionsDir` into `outDir`. Returns the records of every student in the
/// folder, including those reused from an earlier run, and what was skipped. Throws Interrupted after writing
/// what finished if isolation::interruptChildren() was called.
ClassResult gradeClass(const Builder& builder, const Assignment& assignment, const Rubric& rubric,
                       const std::string& submissionsDir, const std::string& outDir, const ClassOptions& options,
                       const std::function<void(const ClassProgress&)>& onProgress);

/// Grade one student folder the way gradeClass does (used by Gradescope's run_autograder, where the folder is
/// the uploaded submission, and by the corpus): find the file, read it with care, grade it on every test, or
/// say why not.
GradeReport gradeFolder(const Builder& builder, const Assignment& assignment, const Rubric& rubric,
                        const std::string& folder, bool recursive, bool followFolder, const GradeOptions& options);

}  // namespace simlab::engine
