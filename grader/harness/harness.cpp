// The grader's side of every test process: the grading API and the Catch2 listener that reports results.
//
// The report channel. The engine starts each test case as its own process with a pipe only the engine reads
// (descriptor SIMLAB_REPORT_FD) and a second pipe carrying a random token (descriptor SIMLAB_TOKEN_FD). A
// constructor that runs before any other static initializer - before any of the student's code - reads the
// token, closes its pipe, and moves the report pipe to a high close-on-exec descriptor. The harness then writes
// one line per event, "<token> <json>": "start" when a test case begins and "end", with the verdict, when Catch2
// has finished it. Student code shares the process, but nothing it prints reaches the pipe, a file it writes is
// never read, and exiting early - exit(0) inside a student function, say - leaves the test without its "end"
// line, which the engine scores as not finished. (Code that searches the process's memory for the token is a
// deliberate attack, out of reach of any in-process harness; that is what hidden variants and reading the code
// are for.) Run by hand, without the pipes, the test binary is an ordinary Catch2 program.
// Listeners are part of Catch2's "external interfaces", declared only on request.
#define CATCH_CONFIG_EXTERNAL_INTERFACES
#include <catch2/catch.hpp>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "simlab/grading.h"
#include "simlab/rubric.h"

namespace simlab::grading {

namespace {

constexpr std::size_t kMaxReasonLength = 400;

struct Channel {
    int fd = -1;
    std::string token;
    std::string memoryLine;  // prepared in advance: the new-handler may not allocate
};

Channel& channel() {
    static Channel c;
    return c;
}

void writeAll(int fd, const std::string& text) {
    const char* p = text.data();
    std::size_t left = text.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n <= 0) return;
        p += n;
        left -= static_cast<std::size_t>(n);
    }
}

void send(const nlohmann::json& record) {
    const Channel& c = channel();
    if (c.fd < 0) return;
    writeAll(c.fd, c.token + " " + record.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

// Out of memory: say so on the channel, then stop. Reporting must not allocate, hence the prepared line.
void onOutOfMemory() {
    const Channel& c = channel();
    if (c.fd >= 0) writeAll(c.fd, c.memoryLine);
    std::_Exit(137);
}

std::string readToken(int fd) {
    std::string token;
    char c = 0;
    while (token.size() < 128 && ::read(fd, &c, 1) == 1 && c != '\n') token += c;
    ::close(fd);
    return token;
}

// Runs before the default-priority static initializers of every translation unit, the student's included.
__attribute__((constructor(101))) void openChannel() {
    const char* reportFd = std::getenv("SIMLAB_REPORT_FD");
    const char* tokenFd = std::getenv("SIMLAB_TOKEN_FD");
    if (!reportFd || !tokenFd) return;
    const int inherited = std::atoi(reportFd);
    Channel& c = channel();
    c.token = readToken(std::atoi(tokenFd));
    c.fd = ::fcntl(inherited, F_DUPFD_CLOEXEC, 200);
    if (inherited != c.fd) ::close(inherited);
    c.memoryLine = c.token + " {\"event\":\"memory\"}\n";
    ::unsetenv("SIMLAB_REPORT_FD");
    ::unsetenv("SIMLAB_TOKEN_FD");
    std::set_new_handler(onOutOfMemory);
}

// What the running test case has said about itself.
struct Verdict {
    std::string test;
    std::optional<double> figure;
    std::string unit;
    std::string text;
    std::optional<double> credit;
    std::vector<std::string> feedback;
    std::string firstFailure;  // reason taken from the first failed assertion
    bool failureIsException = false;
    bool failureHasInfo = false;
};

Verdict& verdict() {
    static Verdict v;
    return v;
}

std::string oneLine(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    std::replace(text.begin(), text.end(), '\t', ' ');
    text.erase(std::unique(text.begin(), text.end(), [](char a, char b) { return a == ' ' && b == ' '; }),
               text.end());
    while (!text.empty() && text.back() == ' ') text.pop_back();
    if (text.size() > kMaxReasonLength) text = text.substr(0, kMaxReasonLength - 3) + "...";
    return text;
}

}  // namespace

double param(const std::string& key) {
    static std::optional<Rubric> rubric;
    if (!rubric) {
        const char* path = std::getenv("SIMLAB_RUBRIC");
        if (!path) throw std::runtime_error("SIMLAB_RUBRIC is not set: run this test through simlab check");
        rubric = loadRubric(path);
    }
    const RubricTest* test = rubric->find(verdict().test);
    if (!test) throw std::runtime_error("the rubric " + rubric->path + " has no test '" + verdict().test + "'");
    const auto found = test->params.find(key);
    if (found == test->params.end()) {
        throw std::runtime_error("the rubric " + rubric->path + " gives test '" + verdict().test + "' no '" + key + "'");
    }
    return found->second;
}

std::string submissionFile(const std::string& name) {
    const char* dir = std::getenv("SIMLAB_SUBMISSION_DIR");
    const std::string path = std::string(dir ? dir : ".") + "/" + name;
    if (::access(path.c_str(), R_OK) != 0) {
        throw std::runtime_error("the submission has no " + name + " (it goes beside your source file)");
    }
    return path;
}

std::string show(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

void measured(double value, const std::string& unit, const std::string& text) {
    verdict().figure = value;
    verdict().unit = unit;
    verdict().text = text;
}

void partialCredit(double fraction) {
    verdict().credit = std::isfinite(fraction) ? std::clamp(fraction, 0.0, 1.0) : 0.0;
}

void feedback(const std::string& line) { verdict().feedback.push_back(oneLine(line)); }

bool atLeast(double value, double floor, double target, const std::string& unit) {
    char text[96];
    std::snprintf(text, sizeof text, "%.1f %s, need %g", value, unit.c_str(), target);
    measured(value, unit, text);
    partialCredit(target > floor ? (value - floor) / (target - floor) : 0.0);
    return value >= target;
}

bool atMost(double value, double allowed, const std::string& what) {
    measured(value, what, what + " " + show(value) + ", allowed " + show(allowed));
    return value <= allowed;
}

namespace {

struct Listener : Catch::TestEventListenerBase {
    using TestEventListenerBase::TestEventListenerBase;

    void testCaseStarting(const Catch::TestCaseInfo& info) override {
        verdict() = Verdict{};
        verdict().test = info.name;
        send({{"event", "start"}, {"test", info.name}});
        TestEventListenerBase::testCaseStarting(info);
    }

    bool assertionEnded(const Catch::AssertionStats& stats) override {
        const Catch::AssertionResult& result = stats.assertionResult;
        Verdict& v = verdict();
        if (result.isOk() || !v.firstFailure.empty()) return true;
        const auto kind = result.getResultType();
        std::string info;
        for (const Catch::MessageInfo& m : stats.infoMessages) {
            if (m.type == Catch::ResultWas::Info) info += (info.empty() ? "" : "; ") + m.message;
        }
        if (kind == Catch::ResultWas::ThrewException || kind == Catch::ResultWas::FatalErrorCondition) {
            v.failureIsException = true;
            v.firstFailure = kind == Catch::ResultWas::ThrewException ? result.getMessage()
                                                                       : "fatal error: " + result.getMessage();
        } else if (!info.empty()) {
            v.failureHasInfo = true;
            v.firstFailure = info;
        } else if (result.hasExpression()) {
            v.firstFailure = "expected " + result.getExpressionInMacro() + ", got " + result.getExpandedExpression();
        } else {
            v.firstFailure = result.getMessage();
        }
        v.firstFailure = oneLine(v.firstFailure);
        return true;
    }

    void testCaseEnded(const Catch::TestCaseStats& stats) override {
        const Verdict& v = verdict();
        const bool passed = stats.totals.assertions.failed == 0 && !stats.aborting;
        std::string reason = v.text;
        if (!passed && (v.failureIsException || v.failureHasInfo || v.text.empty())) reason = v.firstFailure;
        nlohmann::json record = {{"event", "end"},
                                 {"test", v.test},
                                 {"passed", passed},
                                 {"credit", passed ? 1.0 : v.credit.value_or(0.0)},
                                 {"reason", reason},
                                 {"feedback", v.feedback}};
        if (v.figure) record["figure"] = {{"value", std::isfinite(*v.figure) ? *v.figure : 0.0}, {"unit", v.unit}};
        send(record);
        TestEventListenerBase::testCaseEnded(stats);
    }
};

CATCH_REGISTER_LISTENER(Listener)

}  // namespace

}  // namespace simlab::grading
