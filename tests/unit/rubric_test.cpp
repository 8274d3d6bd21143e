// Rubrics: the apple's as shipped, and the one-line errors a malformed rubric gets.
#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <string>

#include "simlab/common/files.h"
#include "simlab/rubric/rubric.h"

namespace rubric_test {

namespace {

// Writes `text` to a rubric file of a folder of its own (tests run side by side) and loads it.
simlab::Rubric loadText(const std::string& text) {
    const simlab::engine::TempDir dir("simlab-rubric-test-");
    const std::string path = dir.path() + "/rubric-test.toml";
    {
        std::ofstream out(path);
        out << text;
    }
    return simlab::loadRubric(path);
}

const std::string kHeader = "assignment = \"apple\"\nsubmission = \"NewtonsApple.cpp\"\n";

}  // namespace

TEST_CASE("the apple's rubric totals 100 points, 24 of them hidden", "[rubric]") {
    const simlab::Rubric rubric = simlab::loadRubric(SIMLAB_SOURCE_DIR "/assignments/apple/grading/rubric.toml");
    CHECK(rubric.assignment == "apple");
    CHECK(rubric.submission == "NewtonsApple.cpp");
    CHECK(rubric.totalPoints() == 100);
    double hidden = 0;
    for (const simlab::RubricTest& t : rubric.tests) hidden += t.visible() ? 0 : t.points;
    CHECK(hidden == 24);
    const simlab::RubricTest* digits = rubric.find("y at the final time has the target accuracy digits");
    REQUIRE(digits);
    CHECK(digits->params.at("target") == 10);
    CHECK(rubric.limits.cpuSeconds == 5);
    CHECK(rubric.limits.wallSeconds == 30);  // a net for sleeping code, far above the CPU time
    CHECK(rubric.limits.submissionKiB == 1024);
}

TEST_CASE("a rubric's thresholds and limits are read as written", "[rubric]") {
    const simlab::Rubric r = loadText(kHeader + "[limits]\ncpu_seconds = 2.5\nwall_seconds = 9\n[[test]]\n"
                                                "name = \"a test\"\npoints = 7\nvisibility = \"after_due_date\"\nfloor = 3\n");
    CHECK(r.limits.cpuSeconds == 2.5);
    CHECK(r.limits.wallSeconds == 9);
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
    // Every limit has a range: a timeout of 1e10 s or 1e30 MiB of memory would silently zero every test.
    const std::string test = "[[test]]\nname = \"x\"\npoints = 1\n";
    CHECK_THROWS_WITH(loadText(kHeader + "[limits]\ncpu_seconds = 1e10\n" + test),
                      Contains("cpu_seconds must be between 0.1 and 3600 s, got 1e+10"));
    CHECK_THROWS_WITH(loadText(kHeader + "[limits]\nmemory_mib = 1e30\n" + test),
                      Contains("memory_mib must be between 64 and 65536 MiB"));
    CHECK_THROWS_WITH(loadText(kHeader + "[limits]\nprocesses = 0\n" + test), Contains("processes must be between"));
    CHECK_THROWS_WITH(loadText(kHeader + "[limits]\ncpu_seconds = 20\nwall_seconds = 10\n" + test),
                      Contains("wall_seconds (the net for sleeping code) must be at least cpu_seconds"));
    CHECK_THROWS_WITH(loadText("[[test]]\nname = \"x\"\npoints = 1\n"), Contains("'assignment' is missing"));
    CHECK_THROWS_WITH(simlab::loadRubric("no-such-rubric.toml"), Contains("no-such-rubric.toml"));
}

TEST_CASE("TOML that toml++ 3.3.0 mishandles in its checks is a one-line error naming the line", "[rubric]") {
    // Found by the fuzz targets of simlab's TOML readers: a table header broken by a line break stops toml++ at an
    // assertion where it is built with them, and a non-ASCII letter where whitespace may be reaches code the
    // library marks unreachable. The library simlab links (Debian's) reports both as the parse errors they are.
    using Catch::Contains;
    CHECK_THROWS_WITH(loadText(kHeader + "[\ntest]\n"), Contains("rubric-test.toml:3:"));
    CHECK_THROWS_WITH(loadText(kHeader + "\xcf\x87 = 1\n"), Contains("rubric-test.toml:3:"));
    CHECK_THROWS_WITH(loadText(kHeader + "[limits\xc8\xb9 ]\n"), Contains("rubric-test.toml:3:"));
}

TEST_CASE("the project's rubric grades 75 points and leaves 25 to be graded by hand", "[rubric]") {
    const simlab::Rubric rubric = simlab::loadRubric(SIMLAB_SOURCE_DIR "/assignments/biosim/grading/rubric.toml");
    CHECK(rubric.totalPoints() == 75);
    CHECK(rubric.manualPoints() == 25);
    REQUIRE(rubric.manual.size() == 3);
    CHECK(rubric.manual[0].name == "the schematic shows the points, bodies and joints clearly");
    CHECK(rubric.manual[0].points == 10);
    CHECK(rubric.extraFiles == std::vector<std::string>{"project.toml"});
}

TEST_CASE("a manual item needs a name and points, and nothing else unknown", "[rubric]") {
    const std::string test = "[[test]]\nname = \"a test\"\npoints = 1\n";
    CHECK_THROWS_WITH(loadText(kHeader + test + "[[manual]]\npoints = 5\n"), Catch::Contains("has no name"));
    CHECK_THROWS_WITH(loadText(kHeader + test + "[[manual]]\nname = \"clarity\"\n"), Catch::Contains("has no points"));
    CHECK_THROWS_WITH(loadText(kHeader + test + "[[manual]]\nname = \"clarity\"\npoints = 5\nfloor = 2\n"),
                      Catch::Contains("unknown key 'floor' in a [[manual]] item"));
    CHECK_THROWS_WITH(loadText(kHeader + test + "[[manual]]\nname = \"a\"\npoints = 5\n[[manual]]\nname = \"a\"\npoints = 1\n"),
                      Catch::Contains("two manual items are named 'a'"));
    CHECK_THROWS_WITH(loadText(kHeader + test + "[[manual]]\nname = \"a\"\npoints = -1\n"),
                      Catch::Contains("'points' must be between 0 and 1e6"));
    const simlab::Rubric r = loadText(kHeader + test + "[[manual]]\nname = \"clarity\"\npoints = 5\n");
    CHECK(r.totalPoints() == 1);
    CHECK(r.manualPoints() == 5);
}

TEST_CASE("[variants] turns on each student's own trade scene, with the course's seed", "[rubric]") {
    using Catch::Contains;
    const std::string test = "[[test]]\nname = \"x\"\npoints = 1\n";
    CHECK_FALSE(loadText(kHeader + test).variants.perStudent);
    const simlab::Rubric r = loadText(kHeader + "[variants]\nper_student = true\nseed = \"fall 2026\"\n" + test);
    CHECK(r.variants.perStudent);
    CHECK(r.variants.seed == "fall 2026");
    CHECK_THROWS_WITH(loadText(kHeader + "[variants]\nper_student = true\n" + test), Contains("needs a seed"));
    CHECK_THROWS_WITH(loadText(kHeader + "[variants]\nper_student = 1\nseed = \"s\"\n" + test),
                      Contains("'per_student' must be true or false"));
    CHECK_THROWS_WITH(loadText(kHeader + "[variants]\nshuffle = true\n" + test),
                      Contains("unknown key 'shuffle' in [variants]"));
    CHECK_THROWS_WITH(loadText(kHeader + "variants = 3\n" + test), Contains("'variants' must be a table"));
}

}  // namespace rubric_test
