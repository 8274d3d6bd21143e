// A corpus case read (course/corpus.h): the student's folder and files it names are each one plain name, so that
// writing the case never writes outside its folder, wherever the case came from (a lab of one's own's corpus).
#include <catch2/catch.hpp>
#include <fstream>
#include <string>

#include "simlab/common/files.h"
#include "simlab/course/corpus.h"

namespace corpus_test {

using namespace simlab::engine;

namespace {

// The case `text` read for the apple, from a file of a folder of its own; its error, or "" if it reads.
std::string refusal(const std::string& text) {
    const TempDir dir("simlab-corpus-test-");
    {
        std::ofstream out(dir.path() + "/case.toml");
        out << "base = \"solution\"\nscore = 100\n" << text;
    }
    Assignment apple;
    apple.id = "apple";
    apple.source = "NewtonsApple.cpp";
    apple.solution = SIMLAB_SOURCE_DIR "/solutions/apple/NewtonsApple.cpp";
    apple.rubric = SIMLAB_SOURCE_DIR "/assignments/apple/grading/rubric.toml";
    try {
        loadCorpusCase(apple, simlab::loadRubric(apple.rubric), dir.path() + "/case.toml", {});
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("a corpus case names its student's folder and files by one plain name each", "[corpus]") {
    using Catch::Contains;
    CHECK(refusal("folder = \"%1B]0;pwned%07\"\n") == "");
    CHECK(refusal("[[file]]\nname = \"BookAnswers.toml\"\ntext = \"x\"\n") == "");
    // Found by fuzz-corpus-case: a folder or a file named with '/' (percent escapes too) lay outside the case's folder.
    CHECK_THAT(refusal("folder = \"..%2F..%2Fetc\"\n"), Contains("the folder '../../etc' is not one plain name"));
    CHECK_THAT(refusal("folder = \"..\"\n"), Contains("is not one plain name"));
    CHECK_THAT(refusal("[[file]]\nname = \"../x\"\ntext = \"y\"\n"), Contains("a file's name '../x' is not one plain name"));
    CHECK_THAT(refusal("[[file]]\nname = \"/etc/passwd\"\ntext = \"y\"\n"), Contains("is not one plain name"));
    CHECK_THAT(refusal("[[file]]\nname = \"NewtonsApple.cpp\"\nrename = \"a/b\"\n"),
               Contains("a file's new name 'a/b' is not one plain name"));
}

}  // namespace corpus_test
