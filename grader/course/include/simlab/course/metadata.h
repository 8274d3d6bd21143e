// Gradescope's submission_metadata.json, beside the submission an autograder grades: who handed it in, when, and the
// assignment's due dates (a student's own, where Gradescope gave them an extension). Its bytes come from the
// platform and are read as data: a value of another type than Gradescope writes is no value.
#pragma once

#include <ctime>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "simlab/course/policy.h"

namespace simlab::engine {

/// The metadata `text` as a JSON object. Throws UsageError "<where> is not JSON" for anything else (text nested
/// deeper than any metadata is, too).
nlohmann::json readSubmissionMetadata(const std::string& text, const std::string& where);

/// A date-time text of the metadata at `path` ({"assignment", "due_date"}; a list's item by a one-digit index, as
/// in {"users", "0", "assignment", "due_date"}), as UTC seconds; empty where absent or not a time.
std::optional<std::time_t> metadataTime(const nlohmann::json& metadata, const std::vector<std::string>& path);

/// The student the metadata names: users[0]'s sid, else their e-mail; empty where it names nobody (or null).
std::string studentOfMetadata(const nlohmann::json& metadata);

/// `policy` (course.toml's) where it is active; else the metadata's due dates: the first user's own, else the
/// assignment's, with its late due date as the cutoff. Inactive where the metadata gives neither.
LatePolicy metadataLatePolicy(LatePolicy policy, const nlohmann::json& metadata);

}  // namespace simlab::engine
