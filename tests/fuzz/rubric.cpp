// A rubric, rubric.toml: an author's own lab's, or one an instructor edits (simlab grade --rubric), read as
// loadRubric reads it. Every rubric that reads names tests Catch2 can select, in limits simlab can set.
#include "fuzz.h"
#include "simlab/rubric/rubric.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    simlab::Rubric rubric;
    try {
        rubric = simlab::readRubric(simlab::fuzz::text(data, size), "rubric.toml");
    } catch (const simlab::RubricError&) {
        return 0;
    }
    for (const simlab::RubricTest& t : rubric.tests) {
        simlab::fuzz::require(simlab::isValidTestName(t.name), "a test name Catch2 would misread: " + t.name);
        simlab::fuzz::require(t.points >= 0, "a test of negative points");
    }
    try {
        rubric.limits.check();
    } catch (const std::invalid_argument& e) {
        simlab::fuzz::broken(std::string("limits that read but do not check: ") + e.what());
    }
    rubric.totalPoints();
    rubric.manualPoints();
    return 0;
}
