// The judge's side of every grader test: the grading API and the Catch2 listener that reports each verdict.
//
// The judge is a process that never loads student code. The engine starts it once per submission, for the test
// cases it names, with two descriptors: 3 takes this listener's records to the engine, and 6 is a socket on which
// each test case, at its first question, receives a new probe of its own (the process that holds the student's
// code, see simlab/probe.h and observe_remote.cpp). The listener writes one line per event: "start" when a test
// case begins and "end", with the verdict, when Catch2 has finished it. Nothing the student's code does can reach
// descriptor 3: it runs in other processes. Run by hand, without the engine, the judge is an ordinary Catch2 program whose tests fail,
// saying that they ask a student's process that only simlab check starts.
// Listeners are part of Catch2's "external interfaces", declared only on request.
#define CATCH_CONFIG_EXTERNAL_INTERFACES
#include <catch2/catch.hpp>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "simlab/protocol/attachments.h"
#include "simlab/harness/grading.h"
#include "simlab/harness/observe.h"
#include "simlab/plot.h"
#include "simlab/rubric/rubric.h"
#include "simlab/protocol/verdict.h"

namespace simlab::grading {

namespace {

constexpr std::size_t kMaxReasonLength = 400;

// Descriptor 3 when the engine runs this judge (SIMLAB_REPORT_FD says so), else nowhere.
int reportFd() {
    static const int fd = [] {
        const char* value = std::getenv("SIMLAB_REPORT_FD");
        if (!value) return -1;
        const int inherited = std::atoi(value);
        // Out of the way of the observation channel, and kept from anything the judge might execute.
        const int moved = ::fcntl(inherited, F_DUPFD_CLOEXEC, 200);
        if (moved >= 0) ::close(inherited);
        return moved;
    }();
    return fd;
}

void writeAll(int fd, const std::string& text) {
    const char* p = text.data();
    std::size_t left = text.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return;
        p += n;
        left -= static_cast<std::size_t>(n);
    }
}

void send(const nlohmann::json& record) {
    const int fd = reportFd();
    if (fd < 0) return;
    writeAll(fd, record.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

// What the running test case has said about itself.
struct Running {
    std::string test;
    std::optional<double> figure;
    std::string unit;
    std::string text;
    std::optional<double> credit;
    std::vector<std::string> feedback;
    std::vector<wire::Attachment> attachments;
    std::vector<wire::BoardEntry> leaderboard;
    std::string worstPoint;    // shown after `text` when the test fails (grading::worstPoint)
    std::string firstFailure;  // reason taken from the first failed assertion
    bool failureIsException = false;
    bool failureHasInfo = false;
    std::chrono::steady_clock::time_point started;
};

Running& verdict() {
    static Running v;
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

namespace {

const Rubric& rubric() {
    static std::optional<Rubric> rubric;
    if (!rubric) {
        const char* path = std::getenv("SIMLAB_RUBRIC");
        if (!path) throw std::runtime_error("SIMLAB_RUBRIC is not set: run this test through simlab check");
        rubric = loadRubric(path);
    }
    return *rubric;
}

}  // namespace

StudentVariant studentVariant() {
    StudentVariant v;
    const char* student = std::getenv("SIMLAB_STUDENT");
    v.student = student ? student : "";
    v.seed = rubric().variants.seed;
    v.on = rubric().variants.perStudent && !v.student.empty();
    return v;
}

void leaderboard(const std::string& name, double value, const std::string& order) {
    if (order != "asc" && order != "desc") throw std::invalid_argument("leaderboard: order is asc or desc");
    if (!std::isfinite(value) || verdict().leaderboard.size() >= wire::kMaxBoardEntries) return;
    verdict().leaderboard.push_back({name, value, order});
}

double param(const std::string& key) {
    const Rubric* rubric = &grading::rubric();
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
    // The engine copies each file handed in, with care; one it would not read has a note saying why instead.
    if (std::FILE* refused = std::fopen((path + ".refused").c_str(), "r")) {
        char why[512] = {0};
        const std::size_t n = std::fread(why, 1, sizeof why - 1, refused);
        std::fclose(refused);
        throw std::runtime_error(std::string(why, n));
    }
    if (::access(path.c_str(), R_OK) != 0) {
        throw std::runtime_error("the submission has no " + name + " (it goes beside your source file)");
    }
    return path;
}

void worstPoint(const std::string& text) { verdict().worstPoint = oneLine(text); }

void measured(double value, const std::string& unit, const std::string& text) {
    verdict().figure = value;
    verdict().unit = unit;
    verdict().text = text;
}

void partialCredit(double fraction) {
    verdict().credit = std::isfinite(fraction) ? std::clamp(fraction, 0.0, 1.0) : 0.0;
}

void feedback(const std::string& line) { verdict().feedback.push_back(oneLine(line)); }

void attach(const std::string& name, const std::string& text) {
    using wire::isAttachmentName;
    using wire::kMaxAttachmentBytes;
    if (verdict().attachments.size() >= wire::kMaxAttachments) throw std::invalid_argument("attach: too many files");
    if (!isAttachmentName(name)) throw std::invalid_argument("attach: '" + name + "' is not a plain file name");
    if (text.size() > kMaxAttachmentBytes) throw std::invalid_argument("attach: " + name + " is over 256 KiB");
    verdict().attachments.push_back({name, text});
}

void attachPlot(const std::string& name, const Plot& plot) {
    try {
        if (name.size() < 4 || name.compare(name.size() - 4, 4, ".svg") != 0) {
            throw std::invalid_argument("'" + name + "' does not end in .svg");
        }
        const char* tmp = std::getenv("TMPDIR");
        std::string dir = std::string(tmp && *tmp ? tmp : "/tmp") + "/simlab-plot-XXXXXX";
        if (!::mkdtemp(dir.data())) {
            throw std::runtime_error(std::string("no temporary folder: ") + std::strerror(errno));
        }
        const std::string path = dir + "/" + name;
        std::string text;
        try {
            drawPlot(plot, path);
            std::ifstream in(path, std::ios::binary);
            text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        } catch (...) {
            std::remove(path.c_str());
            ::rmdir(dir.c_str());
            throw;
        }
        std::remove(path.c_str());
        ::rmdir(dir.c_str());
        attach(name, text);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "simlab: no %s for the feedback: %s\n", name.c_str(), e.what());
    }
}

bool atLeast(double value, double floor, double target, const std::string& unit) {
    if (!std::isfinite(value)) {
        measured(0, unit, unit + ": not a finite number, need " + show(target));
        partialCredit(0);
        return false;
    }
    char text[96];
    std::snprintf(text, sizeof text, "%.1f %s, need %g", value, unit.c_str(), target);
    measured(value, unit, text);
    partialCredit(target > floor ? (value - floor) / (target - floor) : 0.0);
    return value >= target;
}

bool atMost(double value, double allowed, const std::string& what) {
    if (std::isnan(value)) {
        measured(0, what, what + ": not a number, allowed " + show(allowed));
        return false;
    }
    measured(value, what, what + " " + show(value) + ", allowed " + show(allowed));
    return value <= allowed;
}

namespace {

struct Listener : Catch::TestEventListenerBase {
    using TestEventListenerBase::TestEventListenerBase;

    void testCaseStarting(const Catch::TestCaseInfo& info) override {
        verdict() = Running{};
        verdict().test = info.name;
        verdict().started = std::chrono::steady_clock::now();
        observe::startTest(info.name);
        send(wire::startRecord(info.name));
        TestEventListenerBase::testCaseStarting(info);
    }

    bool assertionEnded(const Catch::AssertionStats& stats) override {
        const Catch::AssertionResult& result = stats.assertionResult;
        Running& v = verdict();
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
        const Running& v = verdict();
        // Whatever the test concluded, the channel must have carried exactly the answers it asked for.
        const bool failedBefore = observe::lastFailure() != observe::ChannelFailure::None;
        const std::string extra = observe::finishTest();
        const observe::ChannelFailure channel = observe::lastFailure();
        const bool passed =
            stats.totals.assertions.failed == 0 && !stats.aborting && channel == observe::ChannelFailure::None;
        std::string reason = v.text;
        if (!passed && !v.worstPoint.empty()) reason += ": " + v.worstPoint;
        if (!passed && (v.failureIsException || v.failureHasInfo || v.text.empty())) reason = v.firstFailure;
        if (!extra.empty() && !failedBefore) reason = extra;
        wire::Verdict end;
        end.test = v.test;
        end.passed = passed;
        end.credit = passed ? 1.0 : v.credit.value_or(0.0);
        end.reason = reason;
        end.feedback = v.feedback;
        end.attachments = v.attachments;
        end.leaderboard = v.leaderboard;
        if (v.figure) end.figure = wire::Figure{std::isfinite(*v.figure) ? *v.figure : 0.0, v.unit};
        if (channel == observe::ChannelFailure::BadReport) end.channel = wire::ChannelFailure::BadReport;
        if (channel == observe::ChannelFailure::ProcessEnded) end.channel = wire::ChannelFailure::ProcessEnded;
        // how long the test took here, the student's process included, and the shared questions it used: what
        // the next self-check shares the tests out by
        end.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - v.started).count();
        end.shared = observe::sharedUsed();
        send(wire::endRecord(end));
        TestEventListenerBase::testCaseEnded(stats);
    }
};

CATCH_REGISTER_LISTENER(Listener)

}  // namespace

}  // namespace simlab::grading
