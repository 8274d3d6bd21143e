// Reports: items graded by hand are listed as pending, outside the score, in the text, results.json and feedback.
#include <catch2/catch.hpp>
#include <string>

#include "simlab/course/batch.h"
#include "simlab/grading/report.h"

namespace report_test {

namespace {

simlab::engine::GradeReport projectReport() {
    simlab::engine::GradeReport r;
    r.assignment = "biosim";
    r.title = "Biosimulation project";
    r.build.ok = true;
    simlab::engine::TestResult t;
    t.name = "the model has exactly the degrees of freedom claimed";
    t.maxScore = 8;
    t.score = 8;
    t.outcome = simlab::engine::Outcome::Passed;
    r.tests.push_back(t);
    r.manual = {{"the schematic is clear", 10, ""}, {"the paragraph describes the system", 5, ""}};
    return r;
}

}  // namespace

TEST_CASE("manual items are pending: listed with their points, never in the score", "[report]") {
    const simlab::engine::GradeReport r = projectReport();
    CHECK(r.score() == 8);
    CHECK(r.maxScore() == 8);
    const std::string text = simlab::engine::renderText(r);
    CHECK_THAT(text, Catch::Contains("Score: 8/8\nGraded by hand, pending: 15 points (the schematic is clear, 10; "
                                     "the paragraph describes the system, 5)."));
    const nlohmann::json results = simlab::engine::toGradescope(r);
    CHECK(results["score"] == 8);
    CHECK(results["tests"].size() == 1);  // Gradescope grades the manual items as questions of their own
    REQUIRE(results["extra_data"]["manual_pending"].size() == 2);
    CHECK(results["extra_data"]["manual_pending"][0]["name"] == "the schematic is clear");
    CHECK(results["extra_data"]["manual_pending"][0]["max_score"] == 10);
    CHECK(results["extra_data"]["manual_pending"][0]["status"] == "pending");
    CHECK(results["extra_data"]["manual_points_pending"] == 15);
}

TEST_CASE("a project's feedback names its drawings and its pending items", "[report]") {
    simlab::engine::Assignment a;
    a.id = "biosim";
    a.title = "Biosimulation project";
    a.source = "Project.cpp";
    simlab::engine::StudentRecord record;
    record.id = "ada";
    record.score = 8;
    record.maxScore = 8;
    const std::string md = simlab::engine::feedbackMarkdown(a, record, projectReport().manual, {"schematic-tree.svg"});
    CHECK_THAT(md, Catch::Contains("Drawn from your model, beside this file: schematic-tree.svg"));
    CHECK_THAT(md, Catch::Contains("Graded by hand, 15 points pending:\n\n- the schematic is clear: pending (10)\n"));
    // With the points given in manual.csv: each item's points and comment, and the score counts them.
    record.manual = {{"the schematic is clear", 10, 7.0, "label the knee"},
                     {"the paragraph describes the system", 5, std::nullopt, ""}};
    const std::string graded = simlab::engine::feedbackMarkdown(a, record, projectReport().manual, {});
    CHECK_THAT(graded, Catch::Contains("**Score: 15/23**"));
    CHECK_THAT(graded, Catch::Contains("Graded by hand, 5 points pending:\n\n- the schematic is clear: 7/10 (label the knee)\n"
                                       "- the paragraph describes the system: pending (5)\n"));
}

}  // namespace report_test
