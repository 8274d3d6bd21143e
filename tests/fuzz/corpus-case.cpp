// A case of a corpus (course/corpus.cpp): the course's tests/corpus, and a lab of one's own's corpus/, which
// `simlab assignment verify` grades wherever the lab came from. Every case that reads names its student's folder
// and files with one plain name each (nothing written outside the class), and is written into a folder of its own.
#include "fuzz.h"
#include "simlab/course/corpus.h"

namespace {

using namespace simlab::engine;

// The apple, as the build's manifest describes it, from this tree.
const Assignment& apple() {
    static const Assignment a = [] {
        Assignment x;
        x.id = "apple";
        x.source = "NewtonsApple.cpp";
        x.solution = SIMLAB_SOURCE_DIR "/solutions/apple/NewtonsApple.cpp";
        x.starter = SIMLAB_SOURCE_DIR "/starter/apple/NewtonsApple.cpp";
        x.rubric = SIMLAB_SOURCE_DIR "/assignments/apple/grading/rubric.toml";
        return x;
    }();
    return a;
}

const simlab::Rubric& rubric() {
    static const simlab::Rubric r = simlab::loadRubric(apple().rubric);
    return r;
}

bool plainName(const std::string& name) {
    return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos &&
           name.find('\0') == std::string::npos;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string& folder = simlab::fuzz::scratch().fresh();
    simlab::fuzz::write(folder + "/case.toml", simlab::fuzz::text(data, size));
    CorpusCase c;
    try {
        c = loadCorpusCase(apple(), rubric(), folder + "/case.toml", {{"{source_dir}", SIMLAB_SOURCE_DIR}});
    } catch (const std::runtime_error&) {
        return 0;
    }
    simlab::fuzz::require(plainName(c.folder), "a student's folder that is no plain name: " + c.folder);
    for (const auto& [name, file] : c.files) {
        simlab::fuzz::require(plainName(name), "a student's file that is no plain name: " + name);
    }
    std::vector<TestResult> tests;
    for (const simlab::RubricTest& t : rubric().tests) {
        TestResult r;
        r.name = t.name;
        r.outcome = Outcome::Passed;
        tests.push_back(r);
    }
    compareWithCase(c, tests, 100.0, SubmissionStatus::Graded, "report", true);
    try {
        writeCorpusCase(c, folder + "/class/" + c.folder, folder + "/class");
    } catch (const std::runtime_error&) {
    }
    return 0;
}
