// Files a grader test attaches to the student's feedback (a drawing of their model, say): what the judge may send
// and what the engine will write. Shared so that both refuse the same names and sizes.
#pragma once

#include <cctype>
#include <cstddef>
#include <string>

namespace simlab::wire {

/// The largest attachment, in bytes (the judge's whole report channel holds 1 MiB).
constexpr std::size_t kMaxAttachmentBytes = 256u << 10;
/// Attachments per test.
constexpr std::size_t kMaxAttachments = 3;

/// A plain file name: 1 to 64 letters, digits, '.', '-' or '_', not starting with a dot, and not one of the
/// report's own files.
inline bool isAttachmentName(const std::string& name) {
    if (name.empty() || name.size() > 64 || name[0] == '.') return false;
    for (const char c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '_') return false;
    }
    for (const char* own : {"feedback.md", "results.json", "record.json", "output.txt"}) {
        if (name == own) return false;
    }
    return true;
}

}  // namespace simlab::wire
