// The HTML pages of a graded class: feedback.html and report.html show every test, and every text from a student
// (ids, reasons, compiler messages) is escaped, in valid UTF-8, so that nothing of it becomes markup.
#include <catch2/catch.hpp>
#include <initializer_list>
#include <string>

#include "simlab/common/text.h"
#include "simlab/writers/html.h"
#include "simlab/writers/writers.h"
#include "../../grader/writers/common.h"

namespace report_pages_test {

namespace {

using simlab::engine::Outcome;
using simlab::engine::StudentRecord;
using simlab::engine::TestResult;

const std::string kInvalidUtf8 = "\xff\xfe\xc0\x80";  // bytes that are not UTF-8

simlab::engine::Assignment apple() {
    simlab::engine::Assignment a;
    a.id = "apple";
    a.title = "Newton's apple";
    a.source = "NewtonsApple.cpp";
    return a;
}

TestResult test(const std::string& name, Outcome outcome, double score, double max, const std::string& reason) {
    TestResult t;
    t.name = name;
    t.visibility = "visible";
    t.outcome = outcome;
    t.score = score;
    t.maxScore = max;
    t.reason = reason;
    return t;
}

// A student whose id and messages are hostile: markup, quotes, ampersands, bytes that are not UTF-8, a terminal
// escape and a right-to-left override.
StudentRecord hostileStudent() {
    StudentRecord r;
    r.id = "<script>alert(1)</script>";
    r.status = simlab::engine::SubmissionStatus::Graded;
    r.note = "graded <b>x</b>.cpp; \"quoted\" & 'single'";
    r.file = "NewtonsApple.cpp";
    r.score = 12.5;
    r.maxScore = 30;
    r.seconds = 3.25;
    r.compiler = "warning: <unused> \"x\" & y " + kInvalidUtf8 + "\nsecond line \x1b[2J";
    TestResult digits = test("y at the final time has the target accuracy digits", Outcome::Passed, 10, 10,
                             "14.8 digits, need 10");
    digits.figure = 14.8;
    digits.unit = "digits";
    r.tests.push_back(digits);
    TestResult hostile = test("the energy <stays> & \"holds\"", Outcome::Failed, 2.5, 10,
                              "drift \"&<>\" " + kInvalidUtf8 + " \xe2\x80\xae" "reversed");
    hostile.feedback = {"<img src=x onerror=alert(1)>"};
    r.tests.push_back(hostile);
    TestResult hidden = test("hidden: other heights", Outcome::Crashed, 0, 10, "the secret height is 42 m");
    hidden.visibility = "hidden";
    hidden.figure = 42;
    hidden.unit = "m";
    r.tests.push_back(hidden);
    return r;
}

simlab::Rubric rubricOf(const StudentRecord& r) {
    simlab::Rubric rubric;
    rubric.assignment = "apple";
    for (const TestResult& t : r.tests) {
        simlab::RubricTest test;
        test.name = t.name;
        test.points = t.maxScore;
        test.visibility = t.visibility;
        rubric.tests.push_back(test);
    }
    return rubric;
}

// Every part is in the page.
void checkHolds(const std::string& page, std::initializer_list<std::string> parts) {
    for (const std::string& part : parts) CHECK_THAT(page, Catch::Contains(part));
}

// Nothing a student wrote became markup, and the page is text a browser reads as UTF-8.
void checkSafe(const std::string& page) {
    CHECK(simlab::engine::isValidUtf8(page));
    CHECK_THAT(page, Catch::Contains("<meta charset=\"utf-8\">"));
    CHECK_THAT(page, !Catch::Contains("<script", Catch::CaseSensitive::No));
    // No markup a student wrote, no terminal escape, no right-to-left override (it shows as "\u202e"), nothing
    // fetched.
    for (const char* absent : {"<img", "<b>", "<unused>", "\x1b", "\xe2\x80\xae", "src=\""}) {
        CHECK_THAT(page, !Catch::Contains(absent));
    }
}

}  // namespace

TEST_CASE("feedback.html escapes a hostile id, reason and compiler message", "[report][html]") {
    const std::string page = simlab::engine::feedbackHtml(apple(), hostileStudent());
    checkSafe(page);
    checkHolds(page, {"&lt;script&gt;alert(1)&lt;/script&gt;",
                      "drift &quot;&amp;&lt;&gt;&quot; \xEF\xBF\xBD",
                      "\\u202ereversed",
                      "&lt;img src=x onerror=alert(1)&gt;",
                      "graded &lt;b&gt;x&lt;/b&gt;.cpp; &quot;quoted&quot; &amp; &apos;single&apos;",
                      "warning: &lt;unused&gt; &quot;x&quot; &amp; y \xEF\xBF\xBD",
                      "second line \\x1b[2J"});
}

TEST_CASE("feedback.html has each test's line: its points, outcome and figure", "[report][html]") {
    const std::string page = simlab::engine::feedbackHtml(apple(), hostileStudent());
    checkHolds(page, {"Score: <strong>12.5/30</strong>",
                      "<td class=\"num\">10/10</td><td><span class=\"badge pass\"><span aria-hidden=\"true\">\u2713</span> "
                      "passed</span></td>",
                      "y at the final time has the target accuracy digits</a></td><td class=\"figure\">14.8 digits</td>",
                      "<td class=\"num\">2.5/10</td><td><span class=\"badge fail\"><span aria-hidden=\"true\">\u2717</span> "
                      "failed</span></td>",
                      "the energy &lt;stays&gt; &amp; &quot;holds&quot;",
                      "<td class=\"num\">0/10</td><td><span class=\"badge error\"><span aria-hidden=\"true\">\u26A0</span> "
                      "crashed</span></td>",
                      "Reproduce: <code>simlab check apple NewtonsApple.cpp --test &quot;the energy &lt;stays&gt; &amp; "
                      "&quot;holds&quot;&quot;</code>"});
    // A hidden test: its points and outcome, never its reason or figure.
    checkHolds(page, {"hidden: other heights", "A hidden test: your instructor has the details."});
    CHECK_THAT(page, !Catch::Contains("secret"));
    CHECK_THAT(page, !Catch::Contains("42 m"));
}

TEST_CASE("feedback.html shows the runs the tests drew in the page, and links every file drawn", "[report][html]") {
    const std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M0 0L1 1\"/></svg>";
    const std::string page = simlab::engine::feedbackHtml(
        apple(), hostileStudent(), {}, {{"your-run.svg", svg}, {"schematic-tree.dot", "digraph { a -> b }"}});
    checkHolds(page, {"<h2 id=\"runs\">Your runs, drawn</h2>",
                      "<img src=\"" + simlab::engine::writers::dataUri("image/svg+xml", svg) + "\" alt=\"your-run.svg\"",
                      "<a href=\"your-run.svg\">your-run.svg</a>", "<a href=\"schematic-tree.dot\">"});
    CHECK_THAT(page, !Catch::Contains("<path"));        // the picture's markup is never the page's own
    CHECK_THAT(page, !Catch::Contains("digraph"));      // a file that is not a picture is linked, not shown
    CHECK_THAT(simlab::engine::feedbackHtml(apple(), hostileStudent()), !Catch::Contains("Your runs, drawn"));
}

TEST_CASE("a plot's text alternative: its title as the alt, its description beside it, its points as tables",
          "[report][html]") {
    // A plot as drawPlot writes it (simlab/plot.h): a title and a description that are markup, and two curves drawn
    // at the same x, which share a table.
    const std::string svg =
        "<svg xmlns=\"http://www.w3.org/2000/svg\">\n<title>a &lt;b&gt; run</title>\n<desc>height &amp; more</desc>\n"
        "<metadata id=\"simlab-plot-data\">{&quot;title&quot;:&quot;a &lt;b&gt; run&quot;,&quot;panels&quot;:[{"
        "&quot;x&quot;:&quot;t (s)&quot;,&quot;y&quot;:&quot;y (m)&quot;,&quot;marks&quot;:[{&quot;label&quot;:"
        "&quot;hit&quot;,&quot;x&quot;:2,&quot;y&quot;:0}],&quot;curves&quot;:[{&quot;title&quot;:&quot;exact&quot;,"
        "&quot;samples&quot;:false,&quot;points&quot;:200,&quot;x&quot;:[0,1],&quot;y&quot;:[10,5.1]},{&quot;title"
        "&quot;:&quot;simulated&quot;,&quot;samples&quot;:true,&quot;points&quot;:2,&quot;x&quot;:[0,1],&quot;y"
        "&quot;:[10,5.100000001]}]}]}</metadata>\n<path d=\"M0 0L1 1\"/></svg>";
    const std::string figure = simlab::engine::writers::figureHtml("p1", "your-run.svg", svg, "your-run.svg", "your-run.svg");
    CHECK_THAT(figure, !Catch::Contains("<b>"));
    checkHolds(figure, {"<img src=\"your-run.svg\" alt=\"Plot: a &lt;b&gt; run\" aria-describedby=\"p1-about\"",
                        "<p id=\"p1-about\">height &amp; more</p>", "<a href=\"#p1-data\">Its points as tables</a>",
                        "<details class=\"data\" id=\"p1-data\">",
                        "<caption>exact and simulated: y (m) against t (s), points of the line, 2 of 200 evenly spread"
                        "</caption>",
                        "<th scope=\"col\">t (s)</th><th scope=\"col\">exact</th><th scope=\"col\">simulated</th>",
                        "<tr><th scope=\"row\" class=\"num\">1</th><td class=\"num\">5.1</td><td class=\"num\">"
                        "5.100000001</td></tr>",
                        "<tr><th scope=\"row\">hit</th><td class=\"num\">2</td><td class=\"num\">0</td></tr>"});
    CHECK_THAT(figure, !Catch::Contains("<path"));
    // A picture that carries nothing of its own keeps the alt it is given; broken points are no table.
    const std::string plain = simlab::engine::writers::figureHtml("p2", "a.png", "", "a.png");
    checkHolds(plain, {"alt=\"a.png\""});
    CHECK_THAT(plain, !Catch::Contains("<details"));
    const std::string broken = simlab::engine::writers::figureHtml(
        "p3", "b.svg", "<svg><metadata id=\"simlab-plot-data\">{not json</metadata></svg>", "b.svg");
    CHECK_THAT(broken, !Catch::Contains("<details"));
    checkHolds(broken, {"alt=\"b.svg\""});
}

TEST_CASE("report.html escapes hostile ids and links each student's feedback by a URL-encoded path",
          "[report][html]") {
    simlab::engine::ClassResult result;
    StudentRecord hostile = hostileStudent();
    hostile.status = simlab::engine::SubmissionStatus::DidNotLink;
    StudentRecord spaced = hostileStudent();
    spaced.id = "ada lovelace " + kInvalidUtf8;
    spaced.score = 30;
    result.records = {hostile, spaced};
    result.skipped = {{"<iframe>.txt", "a file, not a student's folder"}};
    const std::string page = simlab::engine::classReportHtml(apple(), rubricOf(hostile), result);
    checkSafe(page);
    CHECK_THAT(page, !Catch::Contains("<iframe"));
    checkHolds(page, {"<a href=\"students/%3Cscript%3Ealert%281%29%3C%2Fscript%3E/feedback.html\">"
                      "&lt;script&gt;alert(1)&lt;/script&gt;</a>",
                      "<a href=\"students/ada%20lovelace%20%FF%FE%C0%80/feedback.html\">ada lovelace \xEF\xBF\xBD",
                      "2 students: median <strong>21.2</strong>",
                      "did not link",
                      "&lt;iframe&gt;.txt"});
    // Each test with its pass rate; the one with a figure with its spread.
    checkHolds(page, {"y at the final time has the target accuracy digits</td><td class=\"num\">10</td>"
                      "<td class=\"num\">2/2 (100%)",
                      "the energy &lt;stays&gt; &amp; &quot;holds&quot;",
                      "0/2 (0%)",
                      "14.8 [14.8, 14.8] digits"});
}

TEST_CASE("report.html: needs a look lists every test that crashed or timed out, whatever the score; the pass "
          "rate counts the files built and run", "[report][html]") {
    simlab::engine::ClassResult result;
    // Eleven students lower than the two below fill the "lowest scores" list.
    for (int i = 0; i < 11; ++i) {
        StudentRecord r;
        r.id = "low" + std::to_string(i);
        r.status = simlab::engine::SubmissionStatus::Graded;
        r.score = 10 + i;
        r.maxScore = 100;
        r.tests = {test("the fall", Outcome::Failed, r.score, 100, "")};
        result.records.push_back(r);
    }
    StudentRecord crashed;
    crashed.id = "crashed-at-95";
    crashed.status = simlab::engine::SubmissionStatus::Graded;
    crashed.score = 95;
    crashed.maxScore = 100;
    crashed.tests = {test("the fall", Outcome::Passed, 95, 95, ""), test("the trade", Outcome::Crashed, 0, 5, "SIGSEGV")};
    StudentRecord slow = crashed;
    slow.id = "timed-out-at-89";
    slow.score = 89;
    slow.tests[1] = test("the trade", Outcome::TimedOut, 0, 11, "");
    StudentRecord unbuilt;
    unbuilt.id = "unbuilt";
    unbuilt.status = simlab::engine::SubmissionStatus::DidNotCompile;
    unbuilt.maxScore = 100;
    unbuilt.tests = {test("the fall", Outcome::DidNotCompile, 0, 95, ""), test("the trade", Outcome::DidNotCompile, 0, 5, "")};
    result.records.push_back(crashed);
    result.records.push_back(slow);
    result.records.push_back(unbuilt);
    simlab::Rubric rubric = rubricOf(crashed);
    const std::string page = simlab::engine::classReportHtml(apple(), rubric, result);
    const std::string attention = page.substr(page.find("<section id=\"attention\">"));
    checkHolds(attention, {"A test crashed, ran out of time or memory, or was refused",
                           "crashed-at-95</a></td><td class=\"num\">95/100</td><td class=\"name\">the trade (crashed)",
                           "timed-out-at-89</a></td><td class=\"num\">89/100</td><td class=\"name\">the trade (timed out)"});
    // The pass rate is over the 13 files built and run, not the 14 students.
    checkHolds(page, {"the trade</td><td class=\"num\">5</td><td class=\"num\">0/2 (0%)",
                      "the fall</td><td class=\"num\">95</td><td class=\"num\">2/13 (15%)"});
}

TEST_CASE("report.html draws figures that span many orders of magnitude on log axes", "[report][html]") {
    simlab::engine::ClassResult result;
    for (double drift : {0.0, 1.9e-14, 2e-14, 3e-10, 2.0}) {
        StudentRecord r;
        r.id = "s" + std::to_string(result.records.size());
        r.status = simlab::engine::SubmissionStatus::Graded;
        r.maxScore = 10;
        TestResult t = test("the energy stays", Outcome::Passed, 10, 10, "");
        t.figure = drift;
        t.unit = "relative energy drift";
        r.tests.push_back(t);
        result.records.push_back(r);
    }
    const std::string page = simlab::engine::classReportHtml(apple(), rubricOf(result.records[0]), result);
    CHECK(simlab::engine::isValidUtf8(page));
    CHECK_THAT(page, Catch::Contains("from 0 to 2 relative energy drift, log scale"));
    CHECK_THAT(page, Catch::Contains("2e-14 [0, 2] relative energy drift"));
}

TEST_CASE("pictures go inside a page as base64 data URIs", "[report][html]") {
    using simlab::engine::writers::base64;
    // RFC 4648, section 10.
    CHECK(base64("") == "");
    CHECK(base64("f") == "Zg==");
    CHECK(base64("fo") == "Zm8=");
    CHECK(base64("foo") == "Zm9v");
    CHECK(base64("foob") == "Zm9vYg==");
    CHECK(base64("fooba") == "Zm9vYmE=");
    CHECK(base64("foobar") == "Zm9vYmFy");
    CHECK(base64(std::string("\xff\xfe\x00", 3)) == "//4A");  // every bit of a byte, a NUL included
    CHECK(simlab::engine::writers::dataUri("image/svg+xml", "<svg/>") == "data:image/svg+xml;base64,PHN2Zy8+");
    CHECK(simlab::engine::writers::pictureType("run.svg") == "image/svg+xml");
    CHECK(simlab::engine::writers::pictureType("run.png") == "image/png");
    CHECK(simlab::engine::writers::pictureType("tree.dot").empty());
}

}  // namespace report_pages_test
