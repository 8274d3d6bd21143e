// The student's answers file, BookAnswers.toml, read as data: each section's values as written. Its bytes are the
// student's; the tests judge what this reads (book_testing.h's readAnswers), and tests/fuzz reads it as they do.
#pragma once

#include <map>
#include <string>
#include <toml++/toml.h>
#include <utility>

namespace book::testing {

struct Answers {
    std::map<std::string, std::string> conserved;  // quantity -> "yes" / "no"
    std::map<std::string, std::string> stability;  // minimum, intermediate, maximum -> "stable" / ...
};

/// The answers a parsed BookAnswers.toml gives: [conserved] and [stability], each key's text ("(not text)" for a
/// value that is none); anything else in the file is left alone.
inline Answers answersOf(const toml::table& file) {
    Answers answers;
    for (const auto& [section, into] : {std::pair<const char*, std::map<std::string, std::string>*>{"conserved", &answers.conserved},
                                        {"stability", &answers.stability}}) {
        if (const toml::table* table = file[section].as_table()) {
            for (auto&& [key, value] : *table) (*into)[std::string(key.str())] = value.value_or(std::string("(not text)"));
        }
    }
    return answers;
}

}  // namespace book::testing
