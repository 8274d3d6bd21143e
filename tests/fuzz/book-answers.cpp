// The book's answers file, BookAnswers.toml, handed in beside the student's code: parsed by toml++ as the tests
// parse it, and read by answers.h.
#include "book/grading/answers.h"
#include "fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    toml::table file;
    try {
        file = toml::parse(std::string_view(reinterpret_cast<const char*>(data), size), std::string_view("BookAnswers.toml"));
    } catch (const toml::parse_error&) {
        return 0;  // the test fails, saying the file is not TOML
    }
    book::testing::answersOf(file);
    return 0;
}
