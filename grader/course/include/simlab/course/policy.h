// A course's rules for late work: course.toml, beside the rubric a class is graded with (or named by --course).
//
//     [late]                                   # the course's rules, for every assignment
//     penalty_percent = 10                     # of the score, for each period (or part of one) past the due date
//     per = "day"                              # or "hour"
//     max_percent = 50                         # the most lateness takes (default 100)
//     grace_days = 1                           # lateness forgiven to every student (default 0)
//
//     [apple]                                  # an assignment, by its id: its due date, and any [late] rule it changes
//     due = 2026-10-02T23:59:00-07:00          # a TOML date-time with its offset
//     cutoff = 2026-10-09T23:59:00-07:00       # optional: handed in after it earns nothing
//     extensions = "apple-extensions.csv"      # optional: per student, beside this file
//
// The extensions file is a CSV with a `student` column (simlab's id, or any id the platform gives them: Canvas's ID,
// the SIS User ID, the login, the e-mail, Gradescope's SID; never a name, which a student chooses) and `due` (a new
// due date, as above) or `days` (days added). A row that names no student, a student twice or an id two students
// share is refused in one line naming it.
//
// Who is late is decided on the platform's word where it gives one: Canvas's LATE flag (in its download's file
// names) decides late or not, Gradescope's created_at is the time. How late comes from the best time known: one
// the instructor names (--submitted: Canvas's submitted_at from its API, or a CSV of id and time), the platform's,
// else the file's own time in the download, which nothing vouches for (a copied folder has the copy's) and which
// the run says it used. The penalty is taken from the score the tests and the manual items give.
#pragma once

#include <ctime>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "simlab/grading/record.h"

namespace simlab::engine {

struct LatePolicy {
    bool active = false;  ///< a due date is set for the assignment
    std::string source;   ///< the file it was read from
    std::time_t due = 0;  ///< UTC seconds
    std::optional<std::time_t> cutoff;
    double penaltyPercent = 0;  ///< per period
    double periodHours = 24;
    double maxPercent = 100;
    double graceHours = 0;
    std::map<std::string, std::time_t> dueFor;  ///< extensions, by simlab id
};

/// Who is who: each id the platform vouches for (Canvas's ID, the SIS User ID, the login, the e-mail, Gradescope's
/// SID, simlab's own id) to the student's simlab id. A display name is never one: a student chooses theirs, and may
/// choose another's id. The members of a group share a simlab id.
class StudentIds {
public:
    /// `alias` (ignored when empty) names the student `id`.
    void add(const std::string& alias, const std::string& id);
    /// The simlab id `alias` names; empty when it names none. Throws UsageError, in one line that starts with
    /// `where` and names both students, when it names two.
    std::optional<std::string> find(const std::string& alias, const std::string& where) const;
    /// Every student (simlab id) named.
    std::set<std::string> students() const;
    bool empty() const { return ids_.empty(); }

private:
    std::map<std::string, std::set<std::string>> ids_;
};

/// When a student handed in, and on whose word.
struct HandIn {
    std::string time;                 ///< UTC text ("2026-10-02T23:59:00Z"); empty: not known
    std::string from;                 ///< how simlab knows: "Gradescope's created_at", "Canvas's file time", ...
    bool vouched = false;             ///< a platform vouches for the time (a file's time is no one's word)
    std::optional<bool> flaggedLate;  ///< the platform's own verdict, where it gives one (Canvas's LATE flag)
};

/// Each student's HandIn, by simlab id.
using HandIns = std::map<std::string, HandIn>;

/// Seconds since 1970 (UTC) of "2026-10-02T23:59:00Z", "2026-10-02 23:59:00.123 -07:00", "...+0200"; a time
/// without an offset is UTC. Empty for anything else.
std::optional<std::time_t> parseTime(const std::string& text);
/// "2026-10-03T06:59:00Z"
std::string utcText(std::time_t t);

/// The policy of `assignment` in the course file `path` (none: inactive), its extensions matched to the class's
/// students through `ids` (where `ids` is empty, as on a platform's autograder, an extension keeps the id it names).
/// Throws UsageError in one line naming the file, and the row of the extensions file, and what is wrong.
LatePolicy loadLatePolicy(const std::string& path, const std::string& assignment, const StudentIds& ids);

/// The hand-in times of `path` named by the instructor (--submitted), by simlab id: Canvas's submissions as its API
/// gives them (a JSON list of objects with user_id, submitted_at and late), or a CSV whose first line names the
/// columns student (any id of `ids`) and submitted. Throws UsageError in one line naming the row for a student
/// unknown, given twice or shared, or a time that is not one.
HandIns readSubmittedTimes(const std::string& path, const StudentIds& ids);

/// A column of a roster.csv as intake writes it: (simlab id, the cell) for each row with an id, in its order.
/// Empty when there is no file, no "simlab id" column or no such column.
std::vector<std::pair<std::string, std::string>> rosterColumn(const std::string& rosterPath, const std::string& column);

/// The ids of a roster.csv as intake writes it (and as an instructor may extend it), from its columns of the
/// platform's ids (simlab id, ID, SIS User ID, SIS Login ID, Platform ID, Email), never Student. Empty when there is
/// no file. Throws UsageError in one line naming both rows when one id of a column names two students.
StudentIds rosterIds(const std::string& rosterPath);

/// Each simlab id's hand-in from a roster.csv (its Submitted, Submitted from and Late columns; a Canvas download's
/// row, which has a Canvas file, carries Canvas's late flag). Throws UsageError in one line naming the row for a
/// time that is not one. Members of a group share a folder: the latest of their times.
HandIns rosterHandIns(const std::string& rosterPath);

/// The hand-in of a platform's `from` ("Gradescope's created_at" is vouched for; a file's time is not).
HandIn handInOf(const std::string& time, const std::string& from, std::optional<bool> flaggedLate);

/// Gives `r` its lateness under `policy`: late or not by the platform's flag where `handIn` has one, else by
/// r.submitted against the student's due date; how late by r.submitted. Hours late, the share of the score taken
/// and a line that says so. Nothing without a policy; a student with no known time is not penalized, and the line
/// says that the time is unknown; nor is one the platform flags late whose time says otherwise.
void applyLatePolicy(StudentRecord& r, const LatePolicy& policy, const HandIn& handIn = {});

/// What the run says of the class's hand-in times before any is graded, one line each naming the students: the
/// platform's flags and the times disagree; every time is one (a copied download's: those times are dropped, and
/// say how late no one is); the times are the files' own, which no platform vouches for.
std::vector<std::string> checkHandIns(HandIns& handIns, const LatePolicy& policy);

}  // namespace simlab::engine
