// How a self-check shares its tests out over judges: from last time's costs, so that the judges end together and
// tests that ask the same shared questions meet in one judge, where the answer is computed once; and the pool that
// runs the judges (and a class's students, and a study's runs) at once.
#include <catch2/catch.hpp>
#include <atomic>
#include <chrono>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "simlab/common/parallel.h"
#include "simlab/grading/grade.h"

namespace share_tests_test {

using simlab::engine::readTestCost;
using simlab::engine::shareTests;
using simlab::engine::TestCost;

namespace {

// The judge given to each of `tests`.
std::map<std::string, std::size_t> judgesOf(const std::vector<std::string>& tests,
                                            const std::map<std::string, TestCost>& expected, int judges) {
    const std::vector<std::size_t> placed = shareTests(tests, expected, judges);
    REQUIRE(placed.size() == tests.size());
    std::map<std::string, std::size_t> byName;
    for (std::size_t i = 0; i < tests.size(); ++i) byName[tests[i]] = placed[i];
    return byName;
}

// The time each judge would take, counting a shared answer once per judge.
std::vector<double> loads(const std::map<std::string, std::size_t>& judgeOf,
                          const std::map<std::string, TestCost>& expected, std::size_t judges) {
    std::map<std::string, double> answer;
    for (const auto& [name, cost] : expected) {
        for (const auto& [digest, seconds] : cost.shared) answer[digest] = std::max(answer[digest], seconds);
    }
    std::vector<double> load(judges, 0.0);
    std::vector<std::map<std::string, bool>> has(judges);
    for (const auto& [name, k] : judgeOf) {
        const TestCost& cost = expected.at(name);
        double computed = 0;
        for (const auto& [digest, seconds] : cost.shared) computed += seconds;
        load[k] += cost.seconds - computed;
        for (const auto& [digest, seconds] : cost.shared) {
            if (!has[k][digest]) load[k] += answer[digest];
            has[k][digest] = true;
        }
    }
    return load;
}

}  // namespace

TEST_CASE("without last time's costs the tests go round-robin in the rubric's order", "[share]") {
    const std::vector<std::size_t> placed = shareTests({"a", "b", "c", "d", "e"}, {}, 2);
    CHECK(placed == std::vector<std::size_t>{0, 1, 0, 1, 0});
    CHECK(shareTests({"a", "b"}, {}, 1) == std::vector<std::size_t>{0, 0});
    CHECK(shareTests({"a", "b"}, {}, 8) == std::vector<std::size_t>{0, 1});  // no judge without a test
}

TEST_CASE("tests that ask the same shared runs meet in one judge, and the judges end together", "[share]") {
    // The book's shape: three spins run once (0.1 s each) by the first test that asks, read by three more tests;
    // one of them also draws for 0.13 s. Two tests of their own take 0.32 and 0.19 s.
    const std::map<std::string, TestCost> expected = {
        {"accuracy", {0.32, {{"min", 0.1}, {"mid", 0.1}, {"max", 0.1}}}},
        {"conserved", {0.01, {{"min", 0}, {"mid", 0}, {"max", 0}}}},
        {"stability", {0.13, {{"min", 0}, {"mid", 0}, {"max", 0}}}},
        {"answers", {0.01, {{"min", 0}, {"mid", 0}, {"max", 0}}}},
        {"trade", {0.32, {}}},
        {"start", {0.19, {}}},
    };
    const std::vector<std::string> tests = {"accuracy", "conserved", "stability", "answers", "trade", "start"};
    const auto judgeOf = judgesOf(tests, expected, 2);
    CHECK(judgeOf.at("conserved") == judgeOf.at("accuracy"));
    CHECK(judgeOf.at("stability") == judgeOf.at("accuracy"));
    CHECK(judgeOf.at("answers") == judgeOf.at("accuracy"));
    CHECK(judgeOf.at("trade") != judgeOf.at("accuracy"));
    CHECK(judgeOf.at("start") != judgeOf.at("accuracy"));
    const std::vector<double> load = loads(judgeOf, expected, 2);
    CHECK(std::max(load[0], load[1]) == Approx(0.51));  // 0.47 and 0.51: the spins are run once, in one judge
}

TEST_CASE("a test that draws joins the tests whose runs it reads, when that ends the judges sooner", "[share]") {
    // As the book's tests were measured: the first to ask runs the three spins (0.16, 0.1 and 0.1 s); the
    // stability test also draws for 0.14 s, so a group of all the spins' readers would be past an even share.
    const std::map<std::string, TestCost> expected = {
        {"conserved", {0.364, {{"min", 0.16}, {"mid", 0.1}, {"max", 0.1}}}},
        {"accuracy", {0.01, {{"min", 0}, {"mid", 0}, {"max", 0}}}},
        {"stability", {0.14, {{"min", 0}, {"mid", 0}, {"max", 0}}}},
        {"answers", {0.004, {{"min", 0}, {"mid", 0}, {"max", 0}}}},
        {"start", {0.003, {{"min", 0}}}},
        {"trade", {0.347, {}}},
        {"integrator", {0.102, {}}},
        {"samples", {0.037, {}}},
    };
    std::vector<std::string> tests;
    for (const auto& [name, cost] : expected) tests.push_back(name);
    const auto judgeOf = judgesOf(tests, expected, 2);
    for (const std::string reader : {"accuracy", "stability", "answers", "start"}) {
        CHECK(judgeOf.at(reader) == judgeOf.at("conserved"));
    }
    const std::vector<double> load = loads(judgeOf, expected, 2);
    CHECK(std::max(load[0], load[1]) == Approx(0.521));  // the spins' readers; the rest take 0.486
}

TEST_CASE("a cheap answer every test reads does not put every test in one judge", "[share]") {
    // The declaration, asked by every test and computed by the first (0.01 s), and four runs of their own of
    // 0.5 s each.
    std::map<std::string, TestCost> expected;
    std::vector<std::string> tests;
    for (const std::string name : {"a", "b", "c", "d"}) {
        expected[name] = name == "a" ? TestCost{0.51, {{"declaration", 0.01}}} : TestCost{0.5, {{"declaration", 0.0}}};
        tests.push_back(name);
    }
    const auto judgeOf = judgesOf(tests, expected, 2);
    const std::vector<double> load = loads(judgeOf, expected, 2);
    CHECK(load[0] == Approx(1.01));
    CHECK(load[1] == Approx(1.01));
}

TEST_CASE("a test not seen last time counts as long as the longest", "[share]") {
    const std::map<std::string, TestCost> expected = {{"long", {1.0, {}}}, {"short", {0.1, {}}}};
    const auto judgeOf = judgesOf({"long", "short", "new"}, expected, 2);
    CHECK(judgeOf.at("new") != judgeOf.at("long"));
    CHECK(judgeOf.at("short") == judgeOf.at("long"));
}

TEST_CASE("a cost is read only where its numbers are finite and not negative", "[share]") {
    const auto cost = readTestCost(nlohmann::json::parse(
        R"({"seconds": 0.5, "shared": {"0123456789abcdef": 0.25, "a": -1, "b": "soon", "0123456789abcdef0": 1}})"));
    REQUIRE(cost);
    CHECK(cost->seconds == 0.5);
    CHECK(cost->shared == std::map<std::string, double>{{"0123456789abcdef", 0.25}});
    CHECK_FALSE(readTestCost(nlohmann::json::parse(R"({"seconds": -1})")));
    CHECK_FALSE(readTestCost(nlohmann::json::parse(R"({"shared": {}})")));
    CHECK_FALSE(readTestCost(nlohmann::json::parse("5")));
    CHECK_FALSE(readTestCost(nlohmann::json::parse(R"({"seconds": 1e999})", nullptr, false)));
}

TEST_CASE("the pool calls each index once, on at most its threads, and none for no work", "[share]") {
    std::vector<std::atomic<int>> calls(200);
    std::atomic<int> running{0}, most{0};
    simlab::engine::forEachInParallel(calls.size(), 4, [&](std::size_t i) {
        const int now = ++running;
        for (int seen = most; now > seen && !most.compare_exchange_weak(seen, now);) {}
        ++calls[i];
        std::this_thread::sleep_for(std::chrono::microseconds(200));
        --running;
    });
    for (const std::atomic<int>& c : calls) CHECK(c == 1);
    CHECK(most <= 4);
    CHECK(most >= 1);
    int none = 0, one = 0;
    simlab::engine::forEachInParallel(0, 4, [&](std::size_t) { ++none; });
    simlab::engine::forEachInParallel(1, 0, [&](std::size_t) { ++one; });  // at least one thread
    CHECK(none == 0);
    CHECK(one == 1);
}

TEST_CASE("the pool throws a call's exception once every thread has ended", "[share]") {
    std::atomic<bool> slowEnded{false};
    std::atomic<int> calls{0};
    auto work = [&](std::size_t i) {
        ++calls;
        if (i == 0) {
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
            slowEnded = true;
        }
        if (i == 1) throw std::runtime_error("index 1 failed");
    };
    CHECK_THROWS_WITH(simlab::engine::forEachInParallel(2, 2, work), "index 1 failed");
    CHECK(slowEnded);
    CHECK(calls == 2);
}

}  // namespace share_tests_test
