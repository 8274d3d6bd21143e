// Rubrics: the apple's as shipped, and the one-line errors a malformed rubric gets.
#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <string>

#include "simlab/rubric.h"

namespace {

// Writes `text` to a rubric file and loads it.
simlab::Rubric loadText(const std::string& text) {
    const std::string path = "rubric-test.toml";
    {
        std::ofstream out(path);
        out << text;
    }
    struct Remove {
        std::string path;
        ~Remove() { std::remove(path.c_str()); }
    } remove{path};
    return simlab::loadRubric(path);
}

const std::string kHeader = "assignment = \"apple\"\nsubmission = \"NewtonsApple.cpp\"\n";

}  // namespace

TEST_CASE("the apple's rubric totals 100 points, 20 of them hidden", "[rubric]") {
    const simlab::Rubric rubric = simlab::loadRubric(SIMLAB_SOURCE_DIR "/assignments/apple/rubric.toml");
    CHECK(rubric.assignment == "apple");
    CHECK(rubric.submission == "NewtonsApple.cpp");
    CHECK(rubric.totalPoints() == 100);
    double hidden = 0;
    for (const simlab::RubricTest& t : rubric.tests) hidden += t.visible() ? 0 : t.points;
    CHECK(hidden == 20);
    const simlab::RubricTest* digits = rubric.find("y at the final time has the target accuracy digits");
    REQUIRE(digits);
    CHECK(digits->params.at("target") == 10);
    CHECK(rubric.limits.wallSeconds == 5);
}

TEST_CASE("a rubric's thresholds and limits are read as written", "[rubric]") {
    const simlab::Rubric r = loadText(kHeader + "[limits]\nwall_seconds = 2.5\n[[test]]\nname = \"a test\"\n"
                                                "points = 7\nvisibility = \"after_due_date\"\nfloor = 3\n");
    CHECK(r.limits.wallSeconds == 2.5);
    REQUIRE(r.tests.size() == 1);
    CHECK(r.tests[0].points == 7);
    CHECK_FALSE(r.tests[0].visible());
    CHECK(r.tests[0].params.at("floor") == 3);
}

TEST_CASE("malformed rubrics are refused with the file, line and what is wrong", "[rubric]") {
    using Catch::Contains;
    CHECK_THROWS_WITH(loadText(kHeader + "[[test]]\nname = \"x\"\npoints = \n"),
                      Contains("rubric-test.toml:5:"));
    CHECK_THROWS_WITH(loadText(kHeader + "[[test]]\nname = \"x\"\n"), Contains("test 'x' has no points"));
    CHECK_THROWS_WITH(loadText(kHeader + "[[test]]\nname = \"x\"\npoints = -1\n"), Contains("must not be negative"));
    CHECK_THROWS_WITH(loadText(kHeader + "[[test]]\nname = \"x\"\npoints = 1\nvisibility = \"secret\"\n"),
                      Contains("visibility 'secret' is not one of"));
    CHECK_THROWS_WITH(loadText(kHeader + "[[test]]\nname = \"x\"\npoints = 1\n[[test]]\nname = \"x\"\npoints = 2\n"),
                      Contains("two tests are named 'x'"));
    CHECK_THROWS_WITH(loadText(kHeader + "[[test]]\nname = \"a, b\"\npoints = 1\n"), Contains("test-spec syntax"));
    CHECK_THROWS_WITH(loadText(kHeader + "pionts = 3\n[[test]]\nname = \"x\"\npoints = 1\n"),
                      Contains("unknown key 'pionts'"));
    CHECK_THROWS_WITH(loadText(kHeader + "[limits]\nwall = 3\n[[test]]\nname = \"x\"\npoints = 1\n"),
                      Contains("unknown limit 'wall'"));
    CHECK_THROWS_WITH(loadText(kHeader), Contains("the rubric has no [[test]]"));
    CHECK_THROWS_WITH(loadText("[[test]]\nname = \"x\"\npoints = 1\n"), Contains("'assignment' is missing"));
    CHECK_THROWS_WITH(simlab::loadRubric("no-such-rubric.toml"), Contains("no-such-rubric.toml"));
}
