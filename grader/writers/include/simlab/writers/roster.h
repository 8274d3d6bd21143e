// A class roster: who each student of simlab's gradebook (a folder name) is in Canvas.
//
// The roster is a CSV file whose header names its columns, in any order (extra columns are ignored, so Canvas's
// own gradebook export, with a column added, is a roster):
//     simlab id     the student's folder name in the submissions (default: the SIS Login ID column)
//     Student       the name Canvas shows, "Last, First"
//     ID            Canvas's user id
//     SIS User ID   the institution's id
//     SIS Login ID  the login
//     Section       the section(s)
// Student and at least one of ID, SIS User ID and SIS Login ID are required (Canvas matches a row by them). A row
// whose Student is "Points Possible" (a Canvas export's second row) is not a student.
#pragma once

#include <string>
#include <vector>

namespace simlab::engine {

struct RosterEntry {
    std::string folder;  ///< simlab's student id
    std::string student, canvasId, sisUserId, sisLoginId, section;
};

/// The rows of a CSV text (RFC 4180: quoted cells may hold commas, doubled quotes and line breaks; CRLF or LF;
/// a UTF-8 byte order mark is skipped). Throws UsageError, in one line, for an unterminated quote.
std::vector<std::vector<std::string>> readCsv(const std::string& text);

/// The roster `text` holds. A row with an empty simlab id is kept (the student has no grade from simlab); the same
/// simlab id on several rows is a group's folder. Throws UsageError, in one line naming `name` and the row, if a
/// required column is missing, a row has more cells than the header, a row names no student, or an ID, SIS User ID
/// or SIS Login ID is another row's too.
std::vector<RosterEntry> readRoster(const std::string& text, const std::string& name);

}  // namespace simlab::engine
