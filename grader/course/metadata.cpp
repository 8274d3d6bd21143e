#include "simlab/course/metadata.h"

#include <cctype>

#include "simlab/common/errors.h"
#include "simlab/common/text.h"
#include "simlab/protocol/bounded_json.h"

namespace simlab::engine {

nlohmann::json readSubmissionMetadata(const std::string& text, const std::string& where) {
    nlohmann::json j = wire::parseBounded(text);
    if (j.is_discarded() || !j.is_object()) throw UsageError(printable(where) + " is not JSON");
    return j;
}

std::optional<std::time_t> metadataTime(const nlohmann::json& metadata, const std::vector<std::string>& path) {
    const nlohmann::json* at = &metadata;
    for (const std::string& key : path) {
        if (at->is_array() && key.size() == 1 && std::isdigit(static_cast<unsigned char>(key[0]))) {
            const std::size_t index = static_cast<std::size_t>(key[0] - '0');
            if (index >= at->size()) return std::nullopt;
            at = &(*at)[index];
        } else if (at->is_object() && at->contains(key)) {
            at = &(*at)[key];
        } else {
            return std::nullopt;
        }
    }
    return at->is_string() ? parseTime(at->get<std::string>()) : std::nullopt;
}

std::string studentOfMetadata(const nlohmann::json& metadata) {
    if (!metadata.is_object()) return "";
    const nlohmann::json users = metadata.value("users", nlohmann::json::array());
    if (!users.is_array() || users.empty() || !users[0].is_object()) return "";
    for (const char* key : {"sid", "email"}) {
        const nlohmann::json& value = users[0].value(key, nlohmann::json());
        if (value.is_string() && !value.get<std::string>().empty()) return value.get<std::string>();
        if (value.is_number_integer()) return value.dump();
    }
    return "";
}

LatePolicy metadataLatePolicy(LatePolicy policy, const nlohmann::json& metadata) {
    if (policy.active) return policy;
    const std::optional<std::time_t> own = metadataTime(metadata, {"users", "0", "assignment", "due_date"});
    const std::optional<std::time_t> due = own ? own : metadataTime(metadata, {"assignment", "due_date"});
    if (!due) return policy;
    policy.due = *due;
    policy.cutoff = metadataTime(metadata, {"assignment", "late_due_date"});
    policy.active = true;
    return policy;
}

}  // namespace simlab::engine
