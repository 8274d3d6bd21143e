// A class as a platform hands it over: the download of Gradescope ("Export Submissions"), Canvas ("Download
// Submissions"), Moodle ("Download all submissions") or GitHub Classroom (`gh classroom clone student-repos`),
// taken in as a class folder simlab grades (a folder per student holding the file) and a roster of who is who.
//
//   canvas      flat files  lovelaceada_101_9001_NewtonsApple.cpp, with "late" after the name for a late one and
//               "-N" before the extension for the Nth resubmission; the id is the name and Canvas's user id; the
//               submission time is the file's (a download's zip keeps it)
//   gradescope  submission_metadata.yml beside submission_<id>/ folders; each submission's submitters (name, sid,
//               email): one member, or a group whose members share its id
//   moodle      "Full Name_123456_assignsubmission_file_/" folders (and "..._onlinetext_/", the same student),
//               or, downloaded "not in folders", files "Full Name_123456_assignsubmission_file_NewtonsApple.cpp";
//               the id is the name and Moodle's participant number; the time is the newest file's
//   classroom   one git repository per student, "<assignment>-<login>/"; the file wherever the repository has it;
//               the time is the last commit's (the student's clock: Classroom's own deadline is the stronger)
#pragma once

#include <string>
#include <vector>

namespace simlab::engine {

/// One student (or a group's member) of a download, as the roster beside the gradebook lists them.
struct IntakeStudent {
    std::string id;       ///< simlab's id: the folder graded (shared by a group's members)
    std::string name;     ///< as the platform spells it
    std::string canvasId; ///< Canvas's user id (a Canvas download)
    std::string sid;      ///< Gradescope's SID (most schools' student number: Canvas's SIS User ID)
    std::string platformId;  ///< Moodle's participant number, the GitHub login: no id Canvas knows
    std::string email;
    bool late = false;    ///< the platform marked the submission late
    std::string submitted;      ///< when it was handed in (UTC, "2026-10-02T23:59:00Z"); empty if unknown
    std::string submittedFrom;  ///< how simlab knows: "Canvas's file time", "Gradescope's created_at", ...
    std::string canvasFile;     ///< a Canvas download's name for the submission ("lovelaceada_101_9001"), for
                                ///< files uploaded back to it (Canvas's Re-Upload Submissions)
    std::string group;    ///< the members' names, for a group submission
    std::string note;     ///< what intake saw: "no NewtonsApple.cpp in the submission", "resubmitted 2 times", ...
};

/// The platforms whose downloads simlab reads: "gradescope", "canvas", "moodle", "classroom".
const std::vector<std::string>& downloadLayouts();

/// The platform a folder's layout looks like ("canvas", ...), "loose files" for a folder of files that is no
/// platform's layout, or "" for a class folder (a folder per student).
std::string layoutOf(const std::string& folder);

/// Takes the download `folder` of platform `layout` into `classDir` (remade: simlab marks it as its own beside it,
/// and refuses a folder of that name it did not make, or one inside the download): a folder per id holding the
/// student's files, read as untrusted data (regular files only, at most `limitBytes` each). `handedIn` is the
/// file graded, then the rubric's extra files. Returns every student, in the download's order. Throws UsageError,
/// in one line, if `folder` is not such a download.
std::vector<IntakeStudent> takeIn(const std::string& layout, const std::string& folder, const std::string& classDir,
                                  const std::vector<std::string>& handedIn, std::size_t limitBytes);

/// The roster of a download: Canvas's columns (Student, ID, SIS User ID, SIS Login ID, Section), simlab id, then
/// Platform ID, Email, Late, Submitted (with Submitted from), Group, Note and Canvas file, as CSV (what
/// `simlab export canvas` matches Canvas's own gradebook export with, and the late policy reads the times of).
std::string intakeRosterCsv(const std::vector<IntakeStudent>& students);

}  // namespace simlab::engine
