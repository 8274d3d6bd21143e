// What became of a submission: its record's status. Each status has one name, given here and nowhere else, and every
// file and report says it in those words (results.json, record.json, gradebook.csv, the JUnit XML, the feedback
// and the class report), for instructors' tools read them.
#pragma once

#include <optional>
#include <string>

namespace simlab::engine {

enum class SubmissionStatus {
    Graded,         ///< the file named by the rubric, built and tested
    MisnamedFile,   ///< the one C++ file there, under another name, built and tested
    MissingFile,    ///< no file to grade
    UnsafeFile,     ///< refused unread: a link, a folder, a file that changed while it was read ...
    FileTooLarge,   ///< refused unread: over the size limit
    DidNotCompile,
    DidNotLink,
    ForbiddenCode,  ///< the object check refused it before the link
    GraderError     ///< simlab could not grade it (a disk full, say): retried on the next run
};

/// "graded", "misnamed file", "missing file", "unsafe file", "file too large", "did not compile", "did not link",
/// "forbidden code", "grader error".
const std::string& statusName(SubmissionStatus status);
/// The status of that name; none for another.
std::optional<SubmissionStatus> statusNamed(const std::string& name);

}  // namespace simlab::engine
