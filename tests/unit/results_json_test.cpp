// results.json is written whole from a student's record: the scores it has now, the points given by hand, and
// what the build said; record.json keeps all of that, and a record without it is read as from another version.
#include <catch2/catch.hpp>
#include <set>
#include <string>

#include "simlab/grading/report.h"
#include "simlab/writers/writers.h"

namespace results_json_test {

namespace engine = simlab::engine;
using engine::GradeReport;

namespace {

GradeReport classReport() {
    GradeReport r;
    r.assignment = "apple";
    r.status = engine::SubmissionStatus::Graded;
    r.build.ok = true;
    r.build.compileSeconds = 1.25;
    r.build.linkSeconds = 0.5;
    r.sandbox = "bubblewrap";
    r.seconds = 2.2;
    engine::TestResult t;
    t.name = "the apple lands";
    t.maxScore = 20;
    t.score = 20;
    t.credit = 1;
    t.outcome = engine::Outcome::Passed;
    t.reason = "14.8 digits";
    t.figure = 14.8;
    t.unit = "digits";
    r.tests.push_back(t);
    r.manual = {{"the schematic is clear", 10, ""}, {"the paragraph describes the system", 5, ""}};
    return r;
}

}  // namespace

TEST_CASE("results.json from a record says the points given by hand and only the items still pending", "[report]") {
    engine::StudentRecord r = engine::recordOf(classReport());
    r.manual[0].points = 7.0;
    r.manual[0].comment = "label the knee";
    const nlohmann::json doc = nlohmann::json::parse(engine::resultsJson(r));
    CHECK(doc["score"] == 20);
    CHECK(doc["execution_time"] == 3);
    CHECK_THAT(doc["output"].get<std::string>(),
               Catch::Contains("compiled in 1.2 s, linked in 0.5 s\nsandbox: bubblewrap\n"
                               "Graded by hand: 7/10 points (the schematic is clear, 7/10 (label the knee)).\n"
                               "Graded by hand, pending: 5 points (the paragraph describes the system, 5)."));
    const nlohmann::json& extra = doc["extra_data"];
    CHECK(extra["assignment"] == "apple");
    REQUIRE(extra["manual_graded"].size() == 1);
    CHECK(extra["manual_graded"][0]["score"] == 7);
    CHECK(extra["manual_graded"][0]["comment"] == "label the knee");
    REQUIRE(extra["manual_pending"].size() == 1);
    CHECK(extra["manual_points_pending"] == 5);
    CHECK(extra["total_with_manual"] == 27);
    CHECK(extra["max_with_manual"] == 35);
    CHECK(doc["tests"][0]["extra_data"]["figure"] == 14.8);
}

TEST_CASE("results.json with every item given says none pending, and flags points given to an earlier file",
          "[report]") {
    engine::StudentRecord r = engine::recordOf(classReport());
    r.manual[0].points = 7.5;
    r.manual[1].points = 5;
    r.manual[1].earlierFile = true;
    const nlohmann::json doc = nlohmann::json::parse(engine::resultsJson(r));
    const std::string output = doc["output"];
    CHECK_THAT(output, Catch::Contains("Graded by hand: 12.5/15 points (the schematic is clear, 7.5/10; the paragraph "
                                       "describes the system, 5/5, given to an earlier file)."));
    CHECK_THAT(output, !Catch::Contains("pending"));
    CHECK(doc["extra_data"]["manual_graded"][0]["earlier_file"] == false);
    CHECK(doc["extra_data"]["manual_graded"][1]["earlier_file"] == true);
    CHECK(doc["extra_data"]["total_with_manual"] == 32.5);  // counted all the same
}

TEST_CASE("results.json has a leaderboard only where a test gave entries, and record.json keeps them", "[report]") {
    engine::StudentRecord r = engine::recordOf(classReport());
    CHECK_FALSE(nlohmann::json::parse(engine::resultsJson(r)).contains("leaderboard"));
    r.tests[0].leaderboard = {{"trade: evaluations", 29, "asc"}, {"trade: digits kept", 12, "desc"}};
    const nlohmann::json doc = nlohmann::json::parse(engine::resultsJson(r));
    REQUIRE(doc["leaderboard"].size() == 2);
    CHECK(doc["leaderboard"][0] == nlohmann::json({{"name", "trade: evaluations"}, {"value", 29}, {"order", "asc"}}));
    CHECK(doc["leaderboard"][1]["order"] == "desc");
    r.id = "ada";
    r.key = "k";
    const std::optional<engine::StudentRecord> back = engine::readRecordJson(engine::recordJson(r));
    REQUIRE(back);
    REQUIRE(back->tests[0].leaderboard.size() == 2);
    CHECK(back->tests[0].leaderboard[1].value == 12);
}

TEST_CASE("results.json from a re-scored record has its new points", "[report]") {
    engine::StudentRecord r = engine::recordOf(classReport());
    r.tests[0].maxScore = r.tests[0].score = 30;
    r.score = r.maxScore = 30;
    const nlohmann::json doc = nlohmann::json::parse(engine::resultsJson(r));
    CHECK(doc["score"] == 30);
    CHECK(doc["tests"][0]["score"] == 30);
    CHECK(doc["extra_data"]["max_score"] == 30);
}

TEST_CASE("record.json keeps what results.json shows, and an older record is read as none", "[report]") {
    engine::StudentRecord r = engine::recordOf(classReport());
    r.id = "ada";
    r.key = "k";
    r.notRunCount = 2;
    r.notRunPoints = 15;
    r.content = "0123456789ab";
    const std::string text = engine::recordJson(r);
    const std::optional<engine::StudentRecord> back = engine::readRecordJson(text);
    REQUIRE(back);
    CHECK(back->assignment == "apple");
    CHECK(back->built);
    CHECK(back->build == r.build);
    CHECK(back->notRunCount == 2);
    CHECK(back->notRunPoints == 15);
    CHECK(back->content == "0123456789ab");
    nlohmann::json older = nlohmann::json::parse(text);
    older.erase("build");
    CHECK_FALSE(engine::readRecordJson(older.dump()));
}

TEST_CASE("a record whose credit is out of 0 to 1, or that names a test twice, is read as damaged", "[report]") {
    engine::StudentRecord r = engine::recordOf(classReport());
    r.id = "ada";
    r.key = "k";
    const nlohmann::json good = nlohmann::json::parse(engine::recordJson(r));
    REQUIRE(engine::readRecordJson(good.dump()));
    REQUIRE_FALSE(good["tests"].empty());
    for (const double credit : {5.0, -0.5}) {
        nlohmann::json edited = good;
        edited["tests"][0]["credit"] = credit;
        CHECK_FALSE(engine::readRecordJson(edited.dump()));
    }
    nlohmann::json twice = good;
    twice["tests"].push_back(good["tests"][0]);
    CHECK_FALSE(engine::readRecordJson(twice.dump()));
}

TEST_CASE("every status has one name, read back as itself; record.json with another is read as damaged", "[report]") {
    using engine::SubmissionStatus;
    std::set<std::string> names;
    for (const SubmissionStatus status :
         {SubmissionStatus::Graded, SubmissionStatus::MisnamedFile, SubmissionStatus::MissingFile,
          SubmissionStatus::UnsafeFile, SubmissionStatus::FileTooLarge, SubmissionStatus::DidNotCompile,
          SubmissionStatus::DidNotLink, SubmissionStatus::ForbiddenCode, SubmissionStatus::GraderError}) {
        const std::string& name = engine::statusName(status);
        CHECK(names.insert(name).second);
        CHECK(engine::statusNamed(name) == status);
    }
    CHECK(names.count("did not compile"));
    CHECK(names.count("grader error"));
    CHECK_FALSE(engine::statusNamed("Graded"));
    CHECK_FALSE(engine::statusNamed(""));

    engine::StudentRecord r = engine::recordOf(classReport());
    r.id = "ada";
    r.key = "k";
    r.status = SubmissionStatus::FileTooLarge;
    nlohmann::json record = nlohmann::json::parse(engine::recordJson(r));
    CHECK(record["status"] == "file too large");
    const std::optional<engine::StudentRecord> back = engine::readRecordJson(record.dump());
    REQUIRE(back);
    CHECK(back->status == SubmissionStatus::FileTooLarge);
    CHECK(nlohmann::json::parse(engine::resultsJson(r))["extra_data"]["status"] == "file too large");
    record["status"] = "nearly graded";
    CHECK_FALSE(engine::readRecordJson(record.dump()));
}

}  // namespace results_json_test
