#include "simlab/common/status.h"

#include <array>
#include <utility>

namespace simlab::engine {

namespace {

// The one table of the statuses' names.
const std::array<std::pair<SubmissionStatus, std::string>, 9>& statusNames() {
    static const std::array<std::pair<SubmissionStatus, std::string>, 9> names = {{
        {SubmissionStatus::Graded, "graded"},
        {SubmissionStatus::MisnamedFile, "misnamed file"},
        {SubmissionStatus::MissingFile, "missing file"},
        {SubmissionStatus::UnsafeFile, "unsafe file"},
        {SubmissionStatus::FileTooLarge, "file too large"},
        {SubmissionStatus::DidNotCompile, "did not compile"},
        {SubmissionStatus::DidNotLink, "did not link"},
        {SubmissionStatus::ForbiddenCode, "forbidden code"},
        {SubmissionStatus::GraderError, "grader error"},
    }};
    return names;
}

}  // namespace

const std::string& statusName(SubmissionStatus status) {
    for (const auto& [value, name] : statusNames()) {
        if (value == status) return name;
    }
    return statusNames().front().second;  // not reached: every status is in the table
}

std::optional<SubmissionStatus> statusNamed(const std::string& name) {
    for (const auto& [value, named] : statusNames()) {
        if (named == name) return value;
    }
    return std::nullopt;
}

}  // namespace simlab::engine
