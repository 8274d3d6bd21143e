// Untrusted JSON, read without recursion it does not need: how deeply a text nests, counted before it is parsed.
// The judge reads the student's answers this way, and the engine the student's process's events.
#pragma once

#include <algorithm>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

namespace simlab::wire {

/// How deeply arrays and objects nest in the JSON text `text` (0 for a plain value), counted without parsing it:
/// a reader of untrusted JSON checks this before anything recursive touches it.
inline std::size_t nestingDepth(const std::string& text) {
    std::size_t depth = 0, deepest = 0;
    bool inString = false, escaped = false;
    for (const char c : text) {
        if (inString) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}

/// The deepest nesting an observation needs is a handful of levels; past this, an answer is refused unread.
constexpr std::size_t kMaxNesting = 32;

/// `text` parsed as JSON if it nests no deeper than kMaxNesting; a discarded value otherwise, or if it is not JSON.
inline nlohmann::json parseBounded(const std::string& text) {
    if (nestingDepth(text) > kMaxNesting) return nlohmann::json(nlohmann::json::value_t::discarded);
    return nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
}

}  // namespace simlab::wire
