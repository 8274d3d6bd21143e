// The platforms' writers: PrairieLearn's results.json, GitHub Classroom's runner result, Canvas's gradebook CSV
// and the roster it is made with. Each takes a student's bytes as they come and says them safely.
#include <catch2/catch.hpp>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/course/intake.h"
#include "simlab/course/manual.h"
#include "simlab/grading/report.h"
#include "simlab/writers/roster.h"
#include "simlab/course/similarity.h"
#include "simlab/common/text.h"
#include "simlab/writers/writers.h"

namespace platforms_test {

using namespace simlab::engine;
using nlohmann::json;

namespace {

TestResult test(const std::string& name, double score, double max, Outcome outcome, const std::string& visibility) {
    TestResult t;
    t.name = name;
    t.score = score;
    t.maxScore = max;
    t.outcome = outcome;
    t.visibility = visibility;
    return t;
}

GradeReport report() {
    GradeReport r;
    r.assignment = "apple";
    r.title = "Newton's apple";
    r.source = "NewtonsApple.cpp";
    r.build.ok = true;
    TestResult drawn = test("the fall", 10, 10, Outcome::Passed, "visible");
    drawn.reason = "14.8 digits";
    drawn.attachments = {{"apple-run.svg", "<svg xmlns='http://www.w3.org/2000/svg'/>"}, {"apple-run.txt", "t y"}};
    r.tests.push_back(drawn);
    TestResult lost = test("the energy \x1b[2J\xff", 0, 5, Outcome::Failed, "visible");
    lost.reason = "drift \xc0\x80 1e-3";
    lost.feedback = {"look at \x1b]0;title\x07 the step"};
    r.tests.push_back(lost);
    TestResult hidden = test("hidden: other heights", 5, 5, Outcome::Passed, "hidden");
    hidden.reason = "13 digits at h = 7";
    hidden.attachments = {{"secret.svg", "<svg/>"}};
    r.tests.push_back(hidden);
    return r;
}

}  // namespace

TEST_CASE("PrairieLearn: score in [0, 1], the tests' points, visible pictures as data URIs", "[platforms]") {
    const std::string text = prairieLearnJson(report());
    CHECK(isValidUtf8(text));
    const json doc = json::parse(text);
    CHECK(doc["gradable"] == true);
    CHECK(doc["score"].get<double>() == Approx(0.75));
    REQUIRE(doc["tests"].size() == 3);
    CHECK(doc["tests"][0]["points"] == 10);
    CHECK(doc["tests"][0]["max_points"] == 10);
    CHECK(doc["tests"][0]["message"] == "passed: 14.8 digits");
    REQUIRE(doc["tests"][0]["images"].size() == 1);  // the .txt is not a picture
    CHECK(doc["tests"][0]["images"][0]["label"] == "apple-run.svg");
    CHECK(doc["tests"][0]["images"][0]["url"] ==
          "data:image/svg+xml;base64,PHN2ZyB4bWxucz0naHR0cDovL3d3dy53My5vcmcvMjAwMC9zdmcnLz4=");
    // A student's bytes: no control character and no invalid UTF-8 reaches the page.
    const std::string name = doc["tests"][1]["name"], message = doc["tests"][1]["message"], output = doc["tests"][1]["output"];
    CHECK(isValidUtf8(name));
    CHECK(message.find('\x1b') == std::string::npos);
    CHECK(output.find('\x1b') == std::string::npos);
    CHECK(output.find('\x07') == std::string::npos);
    // A hidden test: its points and outcome, nothing of what it measured or drew.
    CHECK(doc["tests"][2]["points"] == 5);
    CHECK(doc["tests"][2]["message"] == "passed (a hidden test: the details are your instructor's)");
    CHECK_FALSE(doc["tests"][2].contains("images"));
    CHECK(text.find("h = 7") == std::string::npos);
}

TEST_CASE("PrairieLearn: no file is not gradable; a grader error neither", "[platforms]") {
    GradeReport r = report();
    r.status = SubmissionStatus::MissingFile;
    r.note = "no NewtonsApple.cpp";
    const json doc = json::parse(prairieLearnJson(r));
    CHECK(doc["gradable"] == false);
    CHECK(doc["format_errors"] == json::array({"no NewtonsApple.cpp"}));
    const json failed = json::parse(prairieLearnErrorJson("no manifest \x1b[2J"));
    CHECK(failed["gradable"] == false);
    CHECK(failed["format_errors"][0].get<std::string>().find('\x1b') == std::string::npos);
}

TEST_CASE("PrairieLearn: under the limit, pictures go first, then the texts are cut", "[platforms]") {
    GradeReport r = report();
    r.tests[0].attachments = {{"big.svg", std::string(30000, 'x')}, {"small.png", std::string(600, 'y')}};
    r.tests[1].feedback = {std::string(5000, 'z')};
    const std::string whole = prairieLearnJson(r);
    CHECK(json::parse(whole)["tests"][0]["images"].size() == 2);

    const std::string noBig = prairieLearnJson(r, 20000);
    CHECK(noBig.size() <= 20000);
    const json a = json::parse(noBig);
    REQUIRE(a["tests"][0]["images"].size() == 1);  // the largest left out first
    CHECK(a["tests"][0]["images"][0]["label"] == "small.png");
    CHECK_THAT(a["message"].get<std::string>(), Catch::Contains("Pictures were left out"));
    CHECK(a["tests"][1]["output"].get<std::string>().size() > 5000);  // the texts whole

    const std::string cut = prairieLearnJson(r, 3000);
    CHECK(cut.size() <= 3000);
    const json b = json::parse(cut);
    CHECK_FALSE(b["tests"][0].contains("images"));
    CHECK_THAT(b["tests"][1]["output"].get<std::string>(), Catch::Contains("cut short"));
    CHECK(b["score"].get<double>() == Approx(0.75));  // the score is never cut

    // Multi-byte characters are cut whole.
    r.tests[1].feedback = {std::string(3000, 'a') + std::string(2000, '\xc3') };
    for (std::string& line : r.tests[1].feedback) line = validUtf8(line);
    CHECK(isValidUtf8(prairieLearnJson(r, 3000)));
}

namespace {
// The two runner results classroomJson writes, one a line.
std::pair<json, json> runners(const GradeReport& r) {
    const std::string text = classroomJson(r);
    const std::size_t line = text.find('\n');
    REQUIRE(line != std::string::npos);
    REQUIRE(text.back() == '\n');
    return {json::parse(text.substr(0, line)), json::parse(text.substr(line + 1))};
}
// The reporter's console table (autograding-grading-reporter@v1): per runner, tests passed / tests x max_score.
double tableTotal(const std::pair<json, json>& both) {
    double total = 0;
    for (const json& r : {both.first, both.second}) {
        int passed = 0;
        for (const json& t : r["tests"]) passed += t["status"] == "pass";
        total += static_cast<double>(passed) / static_cast<double>(r["tests"].size()) * r["max_score"].get<double>();
    }
    return total;
}
// The points it records for Classroom: the tests' scores of the runners with a max_score.
double recorded(const std::pair<json, json>& both) {
    double total = 0;
    for (const json& r : {both.first, both.second}) {
        if (r["max_score"].get<double>() == 0) continue;
        for (const json& t : r["tests"]) total += t["score"].get<double>();
    }
    return total;
}
}  // namespace

TEST_CASE("Classroom: two runners, so that the reporter's table and the points it records agree", "[platforms]") {
    const auto [earned, missed] = runners(report());
    CHECK(earned["version"] == 1);
    CHECK(earned["status"] == "pass");
    CHECK(earned["max_score"] == 15);
    CHECK(missed["status"] == "fail");
    CHECK(missed["max_score"] == 5);
    REQUIRE(earned["tests"].size() == 2);
    CHECK(earned["tests"][0]["name"] == "the fall (10 of 10 points)");
    CHECK(earned["tests"][0]["status"] == "pass");
    CHECK(earned["tests"][0]["score"] == 10);
    CHECK(earned["tests"][0]["line_no"] == 0);
    CHECK(earned["tests"][0]["test_code"] == "build/bin/simlab check apple NewtonsApple.cpp --test \"the fall\"");
    REQUIRE(missed["tests"].size() == 1);
    CHECK(missed["tests"][0]["status"] == "fail");
    CHECK(missed["tests"][0]["score"] == 0);
    CHECK(missed["tests"][0]["message"].get<std::string>().find('\x1b') == std::string::npos);
    CHECK(tableTotal({earned, missed}) == Approx(15));
    CHECK(recorded({earned, missed}) == Approx(15));

    // Partial credit: one runner would show 10 (2 of 3 passed x 15) and record 12.81; these two agree.
    GradeReport partial = report();
    partial.tests[1].score = 2.81;
    const auto both = runners(partial);
    CHECK(both.first["max_score"].get<double>() == Approx(17.81));
    CHECK(both.second["max_score"].get<double>() == Approx(2.19));
    CHECK(tableTotal(both) == Approx(17.81));
    CHECK(recorded(both) == Approx(17.81));
    const std::string name = both.second["tests"][0]["name"];
    CHECK(name.find('\x1b') == std::string::npos);
    CHECK(name.find(" (2.19 of 5 points missed)") != std::string::npos);

    // Full marks and none: neither runner is ever empty (the reporter divides by its number of tests).
    GradeReport full = report();
    full.tests[1].score = 5;
    const auto all = runners(full);
    CHECK(all.second["status"] == "pass");
    CHECK(all.second["max_score"] == 0);
    CHECK(all.second["tests"].size() == 1);
    CHECK(tableTotal(all) == Approx(20));
    CHECK(recorded(all) == Approx(20));

    GradeReport broken = report();
    broken.build.ok = false;
    for (TestResult& t : broken.tests) t.outcome = Outcome::DidNotCompile, t.score = 0;
    const auto error = runners(broken);
    CHECK(error.first["status"] == "error");
    CHECK(error.second["status"] == "error");
    CHECK(error.second["tests"][0]["status"] == "error");
    CHECK(tableTotal(error) == 0);
    CHECK(recorded(error) == 0);
    CHECK(error.second["max_score"] == 20);
}

TEST_CASE("Gradescope: a test with points is never hidden, so the student always sees the total", "[platforms]") {
    GradeReport r = report();
    r.tests.push_back(test("hidden: a note worth nothing", 0, 0, Outcome::Passed, "hidden"));
    r.tests.push_back(test("shown when published", 2, 2, Outcome::Passed, "after_published"));
    const json doc = toGradescope(r);
    CHECK(doc["tests"][0]["visibility"] == "visible");
    CHECK(doc["tests"][2]["visibility"] == "after_due_date");  // hidden in the rubric, 5 points
    CHECK(doc["tests"][3]["visibility"] == "hidden");          // no points: it may stay hidden
    CHECK(doc["tests"][4]["visibility"] == "after_published");
}

TEST_CASE("Similarity: C++ read as tokens, identifiers, numbers and literals by kind, on their lines", "[platforms]") {
    const std::vector<CppToken> t = cppTokens(
        "#include <cmath>\nauto s = u8R\"x(a\")x\" + 'c'; // a comment\n/* two\nlines */ x.y->z >>= 1.5e-3;\n\"open");
    std::vector<std::string> kinds;
    for (const CppToken& k : t) kinds.push_back(k.kind);
    CHECK(kinds == std::vector<std::string>{"auto", "ID", "=", "STR", "+", "CHR", ";", "ID", ".", "ID", "->", "ID",
                                            ">>=", "NUM", ";", "STR"});
    CHECK(t[3].text == "u8R\"x(a\")x\"");
    CHECK((t[0].line == 2 && t[7].line == 4 && t[12].text == ">>=" && t[13].text == "1.5e-3" && t[15].line == 5));
}

TEST_CASE("Similarity: a file spelt another way the compiler reads alike is the same tokens, on its own lines",
          "[platforms]") {
    // The compiler joins a line that ends in a backslash to the next, and reads a digraph or an alternative token
    // as the punctuator it stands for: a copy written so must tokenize as the file it copies.
    const std::string plain =
        "int f(int a[2], bool b) {\n    if (a[0] != 1 && !b || ~a[1]) { a[0] &= 3; a[1] ^= a[0] | 1; }\n"
        "    return a[0];\n}\n";
    const std::string spelt =
        "int f(int a<:2:>, bool b) <%\n    if (a<:0:> not_eq 1 and not b or compl a<:1:>) <% a<:0:> and_eq 3; "
        "a<:1:> xor_eq a<:0:> bitor 1; %>\n    ret\\\nurn a<:0:>;\n%>\n";
    const std::vector<CppToken> p = cppTokens(plain), s = cppTokens(spelt);
    REQUIRE(p.size() == s.size());
    for (std::size_t k = 0; k < p.size(); ++k) {
        INFO("token " << k << ": " << p[k].text << " and " << s[k].text);
        CHECK(p[k].kind == s[k].kind);
        CHECK(p[k].text == s[k].text);
    }
    // A splice keeps each token on the line where it starts, and what follows on the lines after the splice.
    CHECK((s[s.size() - 7].kind == "return" && s[s.size() - 7].line == 3));  // cut over lines 3 and 4
    CHECK(s[s.size() - 6].line == 4);                                        // a
    CHECK(s.back().line == 5);                                               // }
    // <:: not followed by : or > is < and ::, as in std::vector<::T>; a digraph opens a directive too.
    std::vector<std::string> kinds;
    for (const CppToken& t : cppTokens("std::vector<::T> v;\n%:include <x>\n%:define N 1\n")) kinds.push_back(t.kind);
    CHECK(kinds == std::vector<std::string>{"ID", "::", "ID", "<", "::", "ID", ">", "ID", ";", "#", "ID", "ID", "NUM"});
}

TEST_CASE(
    "Similarity: the starter's code removed by its tokens, renamed or not; flagged above the class by three "
    "spreads, 50 to 100 %",
    "[platforms]") {
    const std::string starter =
        "void f(const Model& model, State& state) {\n    model.system.realize(state, Stage::Dynamics);\n}\n";
    // The starter's function with its names changed is still the starter's; the student's own line stays, on its line.
    CHECK(withoutStarter("void f(const Model& m, State& s) {\n    m.system.realize(s, Stage::Dynamics);\n"
                         "    double p_GA = \"a\";\n}\n",
                         starter) == "\n\ndouble p_GA = \"\" ;\n}\n");
    // A short piece like the starter's is the student's own: runs of fewer than 8 tokens are not removed.
    CHECK(withoutStarter("int g() { m.realize(s); }\n", starter) == "int g ( ) { m . realize ( s ) ; }\n");
    CHECK(similarityThreshold(10, 5) == 50);    // a class of distinct files: 50 %
    CHECK(similarityThreshold(40, 10) == 70);   // one that shares more: above its median by three spreads
    CHECK(similarityThreshold(88, 10) == 100);  // a class made from one file: its identical copies still show
}

TEST_CASE("Similarity: sim_c++'s runs read by file, the lower first; the rule that flagged a pair named",
          "[platforms]") {
    const std::string output =
        "File 0.cpp: 490 tokens, 81 lines\n\n"
        "2.cpp: line 44-81                      |0.cpp: line 43-80                 [248]\n\n"
        "0.cpp: line 14-43                      |2.cpp: line 14-42                 [237]\n"
        "0.cpp: line 1-2 |0.cpp: line 5-6 [30]\n";
    const auto runs = parseSimRuns(output);
    REQUIRE(runs.size() == 1);
    const std::vector<SharedRun>& r = runs.at({0, 2});
    REQUIRE(r.size() == 2);
    CHECK((r[0].aFirst == 43 && r[0].aLast == 80 && r[0].bFirst == 44 && r[0].bLast == 81 && r[0].tokens == 248));
    CHECK((r[1].aFirst == 14 && r[1].aLast == 43 && r[1].bFirst == 14 && r[1].bLast == 42 && r[1].tokens == 237));
    SimilarPair p;
    CHECK(flaggedBy(p).empty());
    p.overFloor = true;
    CHECK(flaggedBy(p) == "floor");
    p.overClass = true;
    CHECK(flaggedBy(p) == "floor, class");
    p.overFloor = false;
    CHECK(flaggedBy(p) == "class");
}

TEST_CASE("CSV: quoted cells, doubled quotes, line breaks inside, CRLF, a byte order mark", "[platforms]") {
    const auto rows = readCsv("\xEF\xBB\xBFStudent,ID\r\n\"Lovelace, Ada\",\"1\"\"2\"\r\n\"two\nlines\",3");
    REQUIRE(rows.size() == 3);
    CHECK(rows[0] == std::vector<std::string>{"Student", "ID"});
    CHECK(rows[1] == std::vector<std::string>{"Lovelace, Ada", "1\"2"});
    CHECK(rows[2] == std::vector<std::string>{"two\nlines", "3"});
    CHECK_THROWS_AS(readCsv("a,\"b\nc"), UsageError);
}

TEST_CASE("Roster: Canvas's columns, the simlab id or the SIS login, one-line errors", "[platforms]") {
    const auto roster = readRoster("Student,ID,SIS User ID,SIS Login ID,Section,simlab id,Lab 1\n"
                                   "Points Possible,,,,,,10\n"
                                   "\"Lovelace, Ada\",101,s1,ada,A,ada-folder,9\n\n"
                                   "\"Babbage, Charles\",102,s2,cb,A,charles\n",
                                   "r.csv");
    REQUIRE(roster.size() == 2);
    CHECK(roster[0].folder == "ada-folder");
    CHECK(roster[0].student == "Lovelace, Ada");
    CHECK(roster[1].canvasId == "102");
    CHECK(readRoster("Student,SIS Login ID\nAda,ada\n", "r.csv")[0].folder == "ada");

    auto error = [](const std::string& text) {
        try {
            readRoster(text, "r.csv");
        } catch (const UsageError& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    CHECK_THAT(error("Name,ID\nAda,1\n"), Catch::Contains("no Student column"));
    CHECK_THAT(error("Student,Section\nAda,A\n"), Catch::Contains("none of the columns ID, SIS User ID"));
    CHECK_THAT(error("Student,ID\nAda,1\n"), Catch::Contains("no 'simlab id' column"));
    // A group's folder on each member's row; a student simlab has no id for.
    CHECK(error("Student,ID,simlab id\nAda,1,team\nBob,2,team\n") == "(no error)");
    CHECK(readRoster("Student,ID,simlab id\nAda,1,\n", "r.csv")[0].folder.empty());
    CHECK_THAT(error("Student,ID,simlab id\nAda,1,a,extra\n"), Catch::Contains("row 2 has 4 cells"));
    CHECK_THAT(error("Student,ID,simlab id\n,,a\n"), Catch::Contains("row 2 names no student"));
    CHECK_THAT(error("Student,ID,simlab id\n\"Ada,1,a\n"), Catch::Contains("never closed"));
    CHECK_THAT(error(""), Catch::Contains("is empty"));
    for (const std::string& e : {error("Name\n"), error("Student,ID,simlab id\n\"Ada,1,a\n")}) {
        CHECK(e.find('\n') == std::string::npos);
    }
}

TEST_CASE("Canvas: one column, formula-safe cells, groups, blanks for what has no grade, who is missing", "[platforms]") {
    const auto roster = readRoster("Student,ID,SIS User ID,SIS Login ID,Section,simlab id\n"
                                   "\"Lovelace, Ada\",101,s1,ada,A,ada\n"
                                   "=HYPERLINK(\"x\"),102,s2,eve,\"A,B\",eve\n"
                                   "Carol,103,s3,carol,B,carol\n"
                                   "Dan,104,s4,dan,B,\n"
                                   "Fay,105,s5,fay,B,team\n"
                                   "Gus,106,s6,gus,B,team\n"
                                   "Hal,107,s7,hal,B,hal\n",
                                   "r.csv");
    StudentRecord ada, eve, zed, broken, team, hal;
    ada.id = "ada", ada.score = 67.5, ada.maxScore = 75, ada.status = SubmissionStatus::Graded;
    ada.manual = {{"the schematic", 25, 20.0, "clear"}};
    eve.id = "eve", eve.score = 0, eve.status = SubmissionStatus::MissingFile;
    zed.id = "=zed", zed.score = 50, zed.status = SubmissionStatus::Graded;
    broken.id = "carol", broken.status = SubmissionStatus::GraderError;
    team.id = "team", team.score = 70, team.maxScore = 75, team.status = SubmissionStatus::Graded;
    team.manual = {{"the schematic", 25, 25.0, ""}};
    hal.id = "hal", hal.score = 75, hal.maxScore = 75, hal.status = SubmissionStatus::Graded;
    hal.manual = {{"the schematic", 25, std::nullopt, ""}};
    const CanvasExport made = canvasCsv("Biosimulation project (1234)", 100, roster, {ada, eve, zed, broken, team, hal});
    CHECK(made.csv == "Student,ID,SIS User ID,SIS Login ID,Section,Biosimulation project (1234)\n"
                      "Points Possible,,,,,100\n"
                      "\"Lovelace, Ada\",101,s1,ada,A,87.5\n"      // 67.5 of the tests, 20 by hand
                      "\"'=HYPERLINK(\"\"x\"\")\",102,s2,eve,\"A,B\",\n"  // no file: blank, never 0
                      "Carol,103,s3,carol,B,\n"
                      "Dan,104,s4,dan,B,\n"
                      "Fay,105,s5,fay,B,95\n"                       // the group's grade, each member
                      "Gus,106,s6,gus,B,95\n"
                      "Hal,107,s7,hal,B,\n");                       // its manual item pending
    CHECK(made.scored == 3);
    CHECK(made.notGraded == std::vector<std::string>{"carol"});
    CHECK(made.noId == std::vector<std::string>{"Dan"});
    CHECK(made.missingFile == std::vector<std::string>{"eve"});
    CHECK(made.manualPending == std::vector<std::string>{"hal"});
    CHECK(made.notOnRoster == std::vector<std::string>{"=zed"});
}

TEST_CASE("manual.csv: rows for every student and item, what a person typed kept, one-line errors", "[platforms]") {
    simlab::Rubric rubric;
    rubric.manual = {{"the schematic", 10, ""}, {"=the paragraph", 5, ""}};
    // Written for a class: a row per student and item, pending.
    const std::string fresh = manualCsv({}, {"ada", "bob"}, rubric);
    CHECK(fresh == "student,item,points,comment,file\n"
                   "ada,the schematic,,,\n"
                   "ada,\"'=the paragraph\",,,\n"
                   "bob,the schematic,,,\n"
                   "bob,\"'=the paragraph\",,,\n");
    // Filled in, read back; a new student gets rows, a student who left keeps theirs.
    const std::string filled = "student,item,points,comment\n"
                               "ada,the schematic,8,\"no axis, no joint\"\n"
                               "ada,\"'=the paragraph\",5,\n"
                               "bob,the schematic,,\n"
                               "gone,the schematic,3,kept\n";
    const ManualSheet sheet = readManualCsv(filled, "manual.csv", rubric);
    CHECK(*sheet.entries.at({"ada", "the schematic"}).points == 8);
    CHECK(sheet.entries.at({"ada", "the schematic"}).comment == "no axis, no joint");
    CHECK(*sheet.entries.at({"ada", "=the paragraph"}).points == 5);
    CHECK_FALSE(sheet.entries.at({"bob", "the schematic"}).points);
    const std::string merged = manualCsv(sheet, {"ada", "bob", "cy"}, rubric);
    CHECK_THAT(merged, Catch::Contains("ada,the schematic,8,\"no axis, no joint\",\n"));
    CHECK_THAT(merged, Catch::Contains("gone,the schematic,3,kept,\n"));
    // Points as typed, to the last digit (found by fuzz-manual: 0.125 was kept as 0.13, 9.999 as 10).
    const ManualSheet fine = readManualCsv("student,item,points\nada,the schematic,0.125\nbob,the schematic,9.999\n"
                                           "gone,gone,123456789012345678901234567890\n",
                                           "manual.csv", rubric);
    const ManualSheet kept = readManualCsv(manualCsv(fine, {}, rubric), "manual.csv", rubric);
    CHECK(*kept.entries.at({"ada", "the schematic"}).points == 0.125);
    CHECK(*kept.entries.at({"bob", "the schematic"}).points == 9.999);
    CHECK(*kept.entries.at({"gone", "gone"}).points == 123456789012345678901234567890.0);
    CHECK_THAT(merged, Catch::Contains("cy,the schematic,,,\ncy,\"'=the paragraph\",,,\n"));
    // A student's grade from the sheet.
    StudentRecord ada;
    ada.id = "ada", ada.score = 50, ada.maxScore = 75;
    applyManual(ada, sheet, rubric);
    CHECK(ada.total() == 63);
    CHECK(ada.maxTotal() == 90);
    CHECK(ada.pendingPoints() == 0);
    StudentRecord bob;
    bob.id = "bob", bob.score = 70, bob.maxScore = 75;
    applyManual(bob, sheet, rubric);
    CHECK(bob.total() == 70);
    CHECK(bob.pendingPoints() == 15);

    auto error = [&](const std::string& text) {
        try {
            readManualCsv(text, "manual.csv", rubric);
        } catch (const UsageError& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    CHECK_THAT(error("name,item,points\n"), Catch::Contains("the first line must be student,item,points,comment,file"));
    CHECK_THAT(error("student,item,points,file\n"), Catch::Contains("the first line must be"));
    CHECK_THAT(error("student,item,points,comment,file\nada,the schematic,5,,my-guess\n"),
               Catch::Contains("row 2: the file 'my-guess' is not one simlab wrote"));
    CHECK_THAT(error("student,item,points\nada,the schematic,eight\n"), Catch::Contains("row 2: the points 'eight' are not a decimal number"));
    CHECK_THAT(error("student,item,points\nada,the schematic,11\n"), Catch::Contains("worth 0 to 10"));
    CHECK_THAT(error("student,item,points\nada,the schematic,-1\n"), Catch::Contains("not a decimal number"));
    CHECK_THAT(error("student,item,points\nada,the schematic,1\nada,the schematic,2\n"), Catch::Contains("row 3"));
    for (const char* notDecimal : {"0x10", "1e1", "+5", ".5", "5.", "inf", "nan", "5 points"}) {
        CHECK_THAT(error(std::string("student,item,points\nada,the schematic,") + notDecimal + "\n"),
                   Catch::Contains("are not a decimal number"));
    }
    CHECK_THAT(error("student,item,points,comment\nada,the schematic,5,tr\xe8s bien\n"), Catch::Contains("not UTF-8"));
    // An id with spaces at its end, or that looks like a formula, reads back as the same student.
    StudentRecord spaced;
    spaced.id = "bob ";
    const std::string written = manualCsv({}, {"bob ", "'=x"}, rubric);
    ManualSheet back = readManualCsv(written, "manual.csv", rubric);
    back.entries.at({manualKey("bob "), "the schematic"}).points = 4;
    applyManual(spaced, back, rubric);
    CHECK(spaced.total() == 4);
    CHECK(manualCsv(back, {"bob ", "'=x"}, rubric).size() == written.size() + 1);  // the 4, and no second row
    CHECK(strayManualRows(sheet, {"ada", "bob", "cy"}, rubric) == std::vector<std::string>{"gone / the schematic"});
    CHECK(error("") == "(no error)");
}

TEST_CASE("manual.csv: points are tied to the file they were given to, and flagged when it changes", "[platforms]") {
    simlab::Rubric rubric;
    rubric.manual = {{"the schematic", 10, ""}, {"the paragraph", 5, ""}};
    ManualSheet sheet = readManualCsv("student,item,points,comment\n"
                                      "ada,the schematic,8,\n"
                                      "ada,the paragraph,,\n"
                                      "bob,the schematic,6,\n",
                                      "manual.csv", rubric);
    // Each row with points gets its student's file; a pending row, or a student with none known, gets none.
    stampManual(sheet, {{"ada", "aaaa11112222"}, {"bob", ""}});
    CHECK(sheet.entries.at({"ada", "the schematic"}).file == "aaaa11112222");
    CHECK(sheet.entries.at({"ada", "the paragraph"}).file.empty());
    CHECK(sheet.entries.at({"bob", "the schematic"}).file.empty());
    // A cell already filled in is kept.
    stampManual(sheet, {{"ada", "bbbb33334444"}});
    CHECK(sheet.entries.at({"ada", "the schematic"}).file == "aaaa11112222");
    const std::string written = manualCsv(sheet, {"ada", "bob"}, rubric);
    CHECK_THAT(written, Catch::Contains("ada,the schematic,8,,aaaa11112222\n"));
    CHECK(readManualCsv(written, "manual.csv", rubric).entries.at({"ada", "the schematic"}).file == "aaaa11112222");

    StudentRecord same, changed, older;
    same.id = changed.id = older.id = "ada";
    same.content = "aaaa11112222";
    changed.content = "bbbb33334444";
    applyManual(same, sheet, rubric);
    applyManual(changed, sheet, rubric);
    applyManual(older, sheet, rubric);  // a record that does not say what it graded
    CHECK_FALSE(same.manual[0].earlierFile);
    CHECK(changed.manual[0].earlierFile);
    CHECK_FALSE(changed.manual[1].earlierFile);  // pending: nothing was given
    CHECK_FALSE(older.manual[0].earlierFile);
    CHECK(changed.total() == same.total());  // kept and counted
}

TEST_CASE("Gradescope: every submission keeps a folder of its own, whatever SIDs the students typed", "[platforms]") {
    namespace fs = std::filesystem;
    // A SID that is literally what a clash would be renamed to, before or after the two submissions that clash.
    for (const bool literalFirst : {true, false}) {
        TempDir dir("simlab-intake-test-");
        const std::string download = dir.path() + "/download";
        const std::vector<std::pair<std::string, std::string>> submissions =
            literalFirst ? std::vector<std::pair<std::string, std::string>>{{"submission_101", "s42-submission_103"},
                                                                            {"submission_102", "s42"},
                                                                            {"submission_103", "s42"}}
                         : std::vector<std::pair<std::string, std::string>>{{"submission_102", "s42"},
                                                                            {"submission_103", "s42"},
                                                                            {"submission_201", "s42-submission_103"}};
        std::string metadata;
        for (const auto& [submission, sid] : submissions) {
            fs::create_directories(download + "/" + submission);
            writeFileAtomically(download + "/" + submission + "/NewtonsApple.cpp", "// handed in as " + submission + "\n");
            metadata += submission + ":\n  :submitters:\n  - {\":sid\": \"" + sid + "\"}\n";
        }
        writeFileAtomically(download + "/submission_metadata.yml", metadata);
        const std::vector<IntakeStudent> students =
            takeIn("gradescope", download, dir.path() + "/class", {"NewtonsApple.cpp"}, 1 << 20);
        REQUIRE(students.size() == 3);
        std::set<std::string> ids;
        for (std::size_t i = 0; i < students.size(); ++i) {
            ids.insert(students[i].id);
            // Each folder holds its own submission's file: none was dropped or overwritten.
            CHECK(readFile(dir.path() + "/class/" + students[i].id + "/NewtonsApple.cpp") ==
                  "// handed in as " + submissions[i].first + "\n");
        }
        CHECK(ids.size() == 3);
        CHECK(ids.count("s42"));
        CHECK(ids.count("s42-submission_103"));
        // The student whose SID it is keeps it, whichever order the download lists them in.
        for (const IntakeStudent& s : students) {
            if (s.sid == "s42-submission_103") CHECK(s.id == "s42-submission_103");
        }
    }
}

TEST_CASE("Classroom: two repositories whose names make one folder name keep a folder each", "[platforms]") {
    // Found by fuzz-intake: "lab-a b" and "lab-a-b" (or a name led by a byte safeId drops) were both "a-b", and the
    // second repository's file was never taken. The login that has an id as its own keeps it.
    namespace fs = std::filesystem;
    const TempDir dir("simlab-classroom-test-");
    const std::string download = dir.path() + "/lab-submissions";
    const std::vector<std::string> repos = {"lab-a b", "lab-a-b", "lab-a-b-2"};
    for (const std::string& repo : repos) {
        fs::create_directories(download + "/" + repo + "/.git");
        writeFileAtomically(download + "/" + repo + "/NewtonsApple.cpp", "// " + repo + "\n");
    }
    const std::vector<IntakeStudent> students =
        takeIn("classroom", download, dir.path() + "/class", {"NewtonsApple.cpp"}, 1 << 20);
    REQUIRE(students.size() == 3);
    std::set<std::string> ids;
    for (std::size_t i = 0; i < students.size(); ++i) {
        ids.insert(students[i].id);
        CHECK(readFile(dir.path() + "/class/" + students[i].id + "/NewtonsApple.cpp") == "// " + repos[i] + "\n");
    }
    CHECK(ids.size() == 3);
    CHECK(students[0].id == "a-b");
    CHECK(students[1].id == "a-b-3");
    CHECK_THAT(students[1].note, Catch::Contains("the id a-b is another repository's too: this one is a-b-3"));
    CHECK(students[2].id == "a-b-2");
}

TEST_CASE("Gradescope: an id longer than a folder name can be is cut, and told apart by a digest", "[platforms]") {
    // Found by fuzz-gradescope-yaml: an SID (or a group's SIDs joined, or an id told apart by its submission's
    // name) past the 255 bytes a file system's name holds stopped the download with "File name too long".
    namespace fs = std::filesystem;
    const TempDir dir("simlab-gradescope-test-");
    const std::string download = dir.path() + "/download", sid(300, 's');
    std::string metadata;
    for (const char* submission : {"submission_1", "submission_2"}) {
        fs::create_directories(download + "/" + submission);
        writeFileAtomically(download + "/" + submission + "/NewtonsApple.cpp", std::string("// ") + submission + "\n");
        metadata += std::string(submission) + ":\n  :submitters:\n  - {\":sid\": \"" + sid + "\"}\n";
    }
    writeFileAtomically(download + "/submission_metadata.yml", metadata);
    const std::vector<IntakeStudent> students =
        takeIn("gradescope", download, dir.path() + "/class", {"NewtonsApple.cpp"}, 1 << 20);
    REQUIRE(students.size() == 2);
    CHECK(students[0].id != students[1].id);
    for (const IntakeStudent& s : students) {
        CHECK(s.id.size() <= 200);
        CHECK(s.id.rfind(std::string(150, 's'), 0) == 0);
        CHECK(s.sid == sid);  // the roster keeps the SID whole
    }
    CHECK(readFile(dir.path() + "/class/" + students[1].id + "/NewtonsApple.cpp") == "// submission_2\n");
}

}  // namespace platforms_test
