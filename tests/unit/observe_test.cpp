// Observations: what the judge accepts from the student's process, and how the probe answers. The judge's checks
// run here against a transport that returns whatever answer a test scripts, well formed or hostile.
#include <catch2/catch.hpp>
#include <deque>
#include <map>
#include <string>

#include "simlab/harness/observe.h"
#include "simlab/probe/probe.h"
#include "simlab/todo.h"
#include "transport.h"

namespace observe_test {
namespace {

std::deque<std::string> gScripted;  // the answers the fake probe gives, in order; $ID is the request's number
std::string gExtra;                 // what it sends after its last answer

void replaceAll(std::string& text, const std::string& from, const std::string& to) {
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
        text.replace(at, from.size(), to);
    }
}

}  // namespace
}  // namespace observe_test

namespace simlab::observe::detail {

std::string exchange(const std::string& request, std::size_t limit) {
    if (observe_test::gScripted.empty()) throw ProcessEnded("the student's process ended before it answered");
    std::string answer = observe_test::gScripted.front();
    observe_test::gScripted.pop_front();
    const int id = nlohmann::json::parse(request)["id"];
    observe_test::replaceAll(answer, "$ID", std::to_string(id));
    observe_test::replaceAll(answer, "$OTHER", std::to_string(id + 1));
    if (answer.size() > limit) throw BadReport("an answer longer than the rubric's limit");
    return answer;
}

void beginTest(const std::string&) {}

std::string drain() { return observe_test::gExtra; }

}  // namespace simlab::observe::detail

namespace observe_test {
namespace {

using namespace simlab::observe;

struct Sample {
    double time = 0, y = 0;
};
SIMLAB_WIRE(Sample, time, y)

nlohmann::json ask1(const std::string& reply) {
    gScripted = {reply};
    gExtra.clear();
    clearFailure();
    return ask("run", {});
}

}  // namespace

TEST_CASE("a well-formed answer to the request made is returned as it came", "[observe]") {
    const nlohmann::json first = ask1(R"({"id": $ID, "answer": {"samples": [{"time": 0, "y": 10}]}})");
    CHECK(first["samples"][0]["y"] == 10);
    CHECK(lastFailure() == ChannelFailure::None);
    CHECK(ask1(R"({"id": $ID, "answer": 3})") == 3);
}

TEST_CASE("an answer that breaks the protocol is a bad report, never data", "[observe]") {
    using Catch::Contains;
    CHECK_THROWS_AS(ask1("garbage"), BadReport);
    CHECK_THROWS_WITH(ask1("garbage"), Catch::Matches("the answer to request [0-9]+ \\('run'\\) is not a JSON object"));
    CHECK(lastFailure() == ChannelFailure::BadReport);
    // An answer to another request: a duplicate, or a forgery written ahead of the real one.
    CHECK_THROWS_WITH(ask1(R"({"id": $OTHER, "answer": 0})"), Contains("an answer out of turn, twice or unasked"));
    CHECK_THROWS_WITH(ask1(R"({"answer": 0})"), Contains("carries no request number"));
    CHECK_THROWS_WITH(ask1(R"({"id": $ID, "answer": 0, "threw": {"type": "x", "message": "y"}})"),
                      Contains("one answer or exception"));
    CHECK_THROWS_WITH(ask1(R"({"id": $ID, "answer": 0, "passed": true})"), Contains("one answer or exception"));
    CHECK_THROWS_WITH(ask1(R"({"id": $ID, "threw": "boom"})"), Contains("an exception in the wrong shape"));
    CHECK(lastFailure() == ChannelFailure::BadReport);
}

TEST_CASE("a malformed observation names the field that is wrong", "[observe]") {
    const nlohmann::json answer = ask1(R"({"id": $ID, "answer": {"samples": [{"time": 0}]}})");
    CHECK_THROWS_MATCHES(decode<std::vector<Sample>>(answer["samples"], "run"), BadReport,
                         Catch::Message("the answer to 'run' is malformed: [0].y is missing"));
    CHECK_THROWS_WITH(decode<Sample>(nlohmann::json::parse(R"({"time": "soon", "y": 1})"), "run"),
                      Catch::Contains("time is not a number"));
}

TEST_CASE("a non-finite number fails the test that observed it, saying where", "[observe]") {
    // JSON has no NaN: the probe writes null, and the judge names the value and its sample's time.
    CHECK_THROWS_MATCHES(ask1(R"({"id": $ID, "answer": {"samples": [{"time": 0, "y": 1}, {"time": 0.25, "y": null}]}})"),
                         NonFinite,
                         Catch::Message("the student's run produced a value that is not a finite number (NaN or "
                                        "infinity): samples[1].y at t = 0.25 s"));
    CHECK(lastFailure() == ChannelFailure::None);  // a failure of the simulation, not of the channel
}

TEST_CASE("the student's exception is the test's reason", "[observe]") {
    CHECK_THROWS_MATCHES(
        ask1(R"({"id": $ID, "threw": {"type": "simlab::NotDoneYet", "message": "not done yet (A.cpp:3): build it"}})"),
        StudentError, Catch::Message("not done yet (A.cpp:3): build it"));
    CHECK_THROWS_MATCHES(ask1(R"({"id": $ID, "threw": {"type": "std::runtime_error", "message": "mine"}})"),
                         StudentError, Catch::Message("threw std::runtime_error: mine"));
}

TEST_CASE("a process that ends before answering, or sends what nobody asked for, is named", "[observe]") {
    gScripted.clear();
    clearFailure();
    CHECK_THROWS_AS(ask("run", {}), ProcessEnded);
    CHECK(lastFailure() == ChannelFailure::ProcessEnded);
    clearFailure();
    gExtra = R"({"id": 99, "answer": "an extra, unasked"})";
    CHECK(finishTest() == "the student's process sent " + std::to_string(gExtra.size()) +
                              " bytes after its last answer, which nobody asked for");
    CHECK(lastFailure() == ChannelFailure::BadReport);
    gExtra.clear();
    clearFailure();
    CHECK(finishTest().empty());
}

TEST_CASE("a shared answer serves later tests, and each test says which it used and which it computed", "[observe]") {
    gExtra.clear();
    clearFailure();
    startTest("first");
    gScripted = {R"({"id": $ID, "answer": {"samples": [{"time": 0, "y": 10}]}})"};
    CHECK(askShared("run", {{"scene", 1}})["samples"][0]["y"] == 10);
    const std::map<std::string, double> first = sharedUsed();
    REQUIRE(first.size() == 1);
    const std::string digest = first.begin()->first;
    CHECK(digest.size() == 16);
    CHECK(first.begin()->second >= 0);
    CHECK(finishTest().empty());

    // The next test asks the same (no process answers: the answer kept is read) and another question.
    startTest("second");
    CHECK(sharedUsed().empty());
    CHECK(askShared("run", {{"scene", 1}})["samples"][0]["y"] == 10);
    gScripted = {R"({"id": $ID, "answer": 4})"};
    CHECK(askShared("run", {{"scene", 2}}) == 4);
    const std::map<std::string, double> second = sharedUsed();
    REQUIRE(second.size() == 2);
    CHECK(second.at(digest) == 0);  // served by the first test's answer
    CHECK(finishTest().empty());
}

TEST_CASE("the probe answers with data, or with the exception and its type", "[probe]") {
    simlab::probe::add("test-ok", [](const nlohmann::json& a) { return nlohmann::json{{"twice", 2 * a.value("x", 0)}}; });
    simlab::probe::add("test-todo", [](const nlohmann::json&) -> nlohmann::json { SIMLAB_TODO("write it"); });
    simlab::probe::add("test-throw", [](const nlohmann::json&) -> nlohmann::json { throw std::out_of_range("far"); });
    simlab::probe::add("test-int", [](const nlohmann::json&) -> nlohmann::json { throw 42; });
    auto answer = [](const std::string& kind) {
        return nlohmann::json::parse(simlab::probe::answer(R"({"id": 5, "kind": ")" + kind + R"(", "arguments": {"x": 4}})"));
    };
    CHECK(answer("test-ok") == nlohmann::json::parse(R"({"id": 5, "answer": {"twice": 8}})"));
    CHECK(answer("test-todo")["threw"]["type"] == "simlab::NotDoneYet");
    CHECK(answer("test-throw")["threw"] == nlohmann::json::parse(R"({"type": "std::out_of_range", "message": "far"})"));
    CHECK(answer("test-int")["threw"]["type"] == "something that is not a std::exception");
    CHECK(answer("no-such")["threw"]["message"] == "the probe has no observation 'no-such'");
    // A message that is not UTF-8 is replaced, never a reason to fail.
    simlab::probe::add("test-bytes", [](const nlohmann::json&) -> nlohmann::json { throw std::runtime_error("\xff\xfe"); });
    CHECK(nlohmann::json::parse(simlab::probe::answer(R"({"id": 6, "kind": "test-bytes"})"))["threw"]["message"] ==
          "\xEF\xBF\xBD\xEF\xBF\xBD");
}

}  // namespace observe_test
