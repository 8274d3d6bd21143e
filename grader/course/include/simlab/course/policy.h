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
// The extensions file is a CSV with a `student` column (simlab's id, or any id the roster gives them: Canvas's ID,
// the SIS User ID, the e-mail, the platform's login) and `due` (a new due date, as above) or `days` (days added).
//
// When a student handed in comes from the platform (roster.csv's Submitted column, which intake fills from Canvas's
// and Moodle's file times, Gradescope's created_at and Classroom's commit time) or, for a plain class folder, from
// the file's own time. The penalty is taken from the score the tests and the manual items give.
#pragma once

#include <ctime>
#include <map>
#include <optional>
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
    std::vector<std::string> unknownStudents;   ///< extension rows that name no student (a typo)
};

/// Seconds since 1970 (UTC) of "2026-10-02T23:59:00Z", "2026-10-02 23:59:00.123 -07:00", "...+0200"; a time
/// without an offset is UTC. Empty for anything else.
std::optional<std::time_t> parseTime(const std::string& text);
/// "2026-10-03T06:59:00Z"
std::string utcText(std::time_t t);

/// The policy of `assignment` in the course file `path` (none: inactive), its extensions matched to the class's
/// students: `aliases` maps every id the roster gives a student (Canvas's ID, SIS User ID, e-mail, login, name) to
/// simlab's. Throws UsageError in one line naming the file and what is wrong.
LatePolicy loadLatePolicy(const std::string& path, const std::string& assignment,
                          const std::map<std::string, std::string>& aliases);

/// A column of a roster.csv as intake writes it: (simlab id, the cell) for each row with an id, in its order.
/// Empty when there is no file, no "simlab id" column or no such column.
std::vector<std::pair<std::string, std::string>> rosterColumn(const std::string& rosterPath, const std::string& column);

/// The aliases of a roster.csv as intake writes it (and as an instructor may extend it): each of its ids of a
/// student, to that student's simlab id. Empty when there is no file.
std::map<std::string, std::string> rosterAliases(const std::string& rosterPath);

/// Each simlab id's submission time (UTC text) from a roster.csv's Submitted column.
std::map<std::string, std::string> rosterTimes(const std::string& rosterPath);

/// Gives `r` its lateness under `policy` (r.submitted against the student's due date): hours late, the share of
/// the score taken and a line that says so. Nothing without a policy; a student with no known time is not
/// penalized, and the line says that the time is unknown.
void applyLatePolicy(StudentRecord& r, const LatePolicy& policy);

}  // namespace simlab::engine
