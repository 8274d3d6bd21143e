// What grading a class keeps: each student's record (the grade and what it was made from) and the class as a whole.
// The batch (batch.h) makes them; the writers (writers.h) turn them into files.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "simlab/grading/grade.h"

namespace simlab::engine {

/// An item a person grades, for one student, as manual.csv holds it (manual.h).
struct ManualGrade {
    std::string name;
    double maxPoints = 0;
    std::optional<double> points;  ///< empty: pending
    std::string comment;
    bool earlierFile = false;  ///< given to an earlier file of the student's than the one graded now (manual.h)
};

/// A student's grade as kept in record.json and shown in the gradebook.
struct StudentRecord {
    std::string id;
    std::string key;     ///< what the grade was made from; a different key means regrade
    std::string basis;   ///< the part of the key that is not the student's: the grader, the rubric's tests, limits
    SubmissionStatus status = SubmissionStatus::Graded;
    std::string note;
    std::string file;    ///< the file graded, relative to the student's folder
    std::string content;  ///< a short hash of what was graded (the files' bytes): manual.csv's file column
    double score = 0;
    double maxScore = 0;
    double seconds = 0;
    std::string compiler;  ///< the compiler's message: why it failed, or its warnings (first lines)
    std::string sandbox;   ///< the sandbox its code ran in, one line (empty when nothing ran)
    std::string assignment;  ///< the lab's id
    bool built = false;      ///< the build succeeded: `compiler` holds its warnings, else why it failed
    std::string build;       ///< the build in one line: "compiled in 1.2 s, linked in 0.3 s", "did not compile"
    int notRunCount = 0;     ///< hidden tests left for the instructor (a self-check)
    double notRunPoints = 0;
    std::vector<TestResult> tests;
    /// The rubric's manual items with the points manual.csv gives them (not in record.json: the sheet is the
    /// instructor's); pending where the sheet gives none.
    std::vector<ManualGrade> manual;
    /// When the file was handed in (UTC, "2026-10-02T23:59:00Z") and how simlab knows it ("Canvas's download",
    /// "the file's time"); empty when it is not known.
    std::string submitted;
    std::string submittedFrom;
    /// The course's late policy applied to it (course/policy.h), made again from the policy at every grading run.
    struct Lateness {
        double hours = 0;    ///< past the student's due date (after grace)
        double percent = 0;  ///< of the raw score taken
        std::string line;    ///< "handed in 26 h late (1 grace day): 20 % taken"; empty without a policy
        /// The course's bank of slip days (course.toml's [late] slip_days) as this lab spent it; bank 0: the course
        /// keeps none. The labs graded side by side spend each student's bank in the order of their due dates.
        struct Slip {
            int bank = 0;        ///< days each student has for the whole course
            std::string due;     ///< the lab's due date (UTC): where it stands in that order
            int needed = 0;      ///< whole days past the student's due date, after grace, that days could cover
            int had = 0;         ///< days the bank held for this lab, after the labs due before it
            int used = 0;        ///< days this lab spent: the fewer of needed and had
            std::string ledger;  ///< "2 on apple, 1 on projectile (this lab); 0 of 3 left"
        } slip;
    } late;

    /// The tests' points and the manual points given so far, less the late penalty: the score.
    double total() const;
    /// The same before the late penalty.
    double rawTotal() const;
    /// The points the late penalty takes.
    double latePoints() const;
    /// Every point there is: the tests' and the manual items'.
    double maxTotal() const;
    /// The points of the manual items still pending.
    double pendingPoints() const;
};

/// An entry of the submissions folder that is not a student: a hidden folder (its name starts with a dot), a
/// file, a link. Listed, never dropped silently.
struct Skipped {
    std::string name;
    std::string why;
};

struct ClassResult {
    std::vector<StudentRecord> records;  ///< every student in the folder, sorted by id
    std::vector<Skipped> skipped;
    int graderErrors = 0;                ///< students simlab itself could not grade (recorded; retried next run)
    int reused = 0;                      ///< records kept as they were: up to date with the files and the grader
    int graded = 0;                      ///< students graded by this run (with --only, those asked for)
    std::vector<std::string> warnings;   ///< one line each, for the instructor (a manual.csv row that counts for nothing)
    std::vector<std::string> handIns;    ///< what the run says of the hand-in times, one line each naming the students
};

}  // namespace simlab::engine
