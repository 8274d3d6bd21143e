#include "simlab/grading/grade.h"

#include <fcntl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <numeric>
#include <optional>
#include <set>
#include <thread>

#include "simlab/protocol/bounded_json.h"
#include "simlab/common/errors.h"
#include "simlab/common/parallel.h"
#include "simlab/build/lab.h"
#include "simlab/build/lock.h"
#include "simlab/isolation/process.h"
#include "simlab/protocol/verdict.h"
#include "simlab/grading/failure_sites.h"
#include "simlab/grading/record.h"
#include "simlab/common/text.h"

namespace fs = std::filesystem;

namespace simlab::engine {

namespace {

std::string seconds(double s) {
    char text[32];
    std::snprintf(text, sizeof text, "%g s", s);
    return text;
}

// The judge waits on each test's probe in turn, so its wall-clock net is theirs added up and then some; its own
// work is small.
Limits judgeLimits(const Limits& probe, std::size_t tests) {
    Limits l;
    l.wallSeconds = (probe.wallSeconds + 5) * static_cast<double>(tests) + 60;
    l.cpuSeconds = 10.0 * static_cast<double>(tests) + 60;
    l.memoryMiB = 4096;
    l.outputKiB = 1024;
    l.fileMiB = 16;
    l.processes = 16;
    l.observationMiB = probe.observationMiB;
    return l;
}

// A probe's server holds each test's probe in its process tree while it runs (two at once, as one ends and the next
// starts): its limits are its tests' together, and each test is still held to its own.
Limits serverLimits(const Limits& probe, std::size_t tests) {
    Limits l = probe;
    l.wallSeconds = (probe.wallSeconds + 5) * static_cast<double>(tests) + 60;
    l.cpuSeconds = (probe.cpuSeconds + 3) * static_cast<double>(tests) + 60;
    l.memoryMiB = 2 * probe.memoryMiB + 256;
    // The tests' folders share the server's space (bubblewrap's memory folder): each of those running at once may
    // take what a test may (three times its file-size limit), and each test's folder goes when it ends.
    l.fileMiB = probe.fileMiB * (1 + 3 * std::min<std::size_t>(tests, 4));
    return l;
}

// A submission's stalls, shared by its judges. A test whose student process passes the wall-clock net has stalled:
// sleeping, or blocked on something that never comes. Code every test runs first (building the model, say) would
// make each test wait the whole net, so once one test of a submission has stalled, every other test - later, or
// running beside it - is stopped as stalled as soon as neither its student process nor its judge has used CPU time
// for kIdleSeconds. A judge waits on nothing but the student's process, so when both are idle, nothing but the
// student's code is waiting, and on nothing the test will give it. A test that computes (a long one, one on a busy
// machine, one that never reaches the code that stalled) is never stopped by this rule: it keeps the rubric's
// limits. The grader measures both CPU times; nothing the student's process says counts.
struct Stalls {
    std::mutex lock;
    std::string first;              // the test that stalled first, having waited the whole net
    std::set<std::string> stopped;  // tests stopped early because of it
};

constexpr double kIdleSeconds = 1;         // no progress for this long ends a test, once the submission has stalled
constexpr double kProgressSeconds = 0.02;  // CPU time that counts as progress (the kernel counts in 10 ms ticks)

// The probe's `stalled` check for `test` (ProcessRequest::stalled): its CPU time and its judge's, as the judge's
// supervisor last saw it (`judgeCpu`).
std::function<bool(double)> idleWatch(Stalls& stalls, const std::atomic<double>& judgeCpu, const std::string& test) {
    double base = -1;
    std::chrono::steady_clock::time_point since;
    return [&stalls, &judgeCpu, test, base, since](double cpu) mutable {
        const double both = cpu + judgeCpu.load();
        const auto now = std::chrono::steady_clock::now();
        if (both >= base + kProgressSeconds) {
            base = both;
            since = now;
            return false;
        }
        if (now - since < std::chrono::duration<double>(kIdleSeconds)) return false;
        std::lock_guard<std::mutex> guard(stalls.lock);
        if (stalls.first.empty() || stalls.first == test) return false;
        stalls.stopped.insert(test);
        return true;
    };
}

// What the probe said about itself on its event channel. Student code shares that process and can write there
// too; the events only ever name a failure, so a forged one costs its writer.
struct ProbeEvents {
    bool memory = false;
    bool terminated = false;  // std::terminate ran
    std::string type, what;   // the exception in flight then, if there was one
    std::string refused;      // the system call the students' filter refused (the host names it), if one was
    // Where the student's code was (simlab/isolation/failure_sites.h): as a signal was about to end the process (and
    // the signal), at the last sample of its CPU time, and where the exception the course's code caught was thrown
    // (and its type). Addresses in the probe, looked up only beside the outcome the kernel gave. A place is kept only
    // where it is the one the process told: two crash lines or two exceptions that differ (a child's and its own, a
    // test that asked twice), or a channel past what is kept, leave it unknown.
    int crashSignal = 0;
    std::vector<std::uint64_t> crashAt, sampleAt, threwAt;
    std::vector<std::uint64_t> terminateAt;  // where the exception std::terminate ended was thrown
    double sampleCpu = 0;  // the process's CPU time at its last sample
    std::string threwType;
};

// The report channel keeps 1 MiB of lines (supervise): past that, later lines are lost, and the last sample kept is
// not the last one made.
constexpr std::size_t kReportsKept = 1 << 20;

ProbeEvents probeEvents(const std::vector<std::string>& lines) {
    ProbeEvents e;
    std::size_t bytes = 0;
    for (const std::string& line : lines) bytes += line.size() + 1;
    bool placesKnown = bytes + 4096 < kReportsKept, crashTold = false, throwTold = false;
    for (const std::string& line : lines) {
        const nlohmann::json record = wire::parseBounded(line);
        if (!record.is_object() || !record.contains("event") || !record["event"].is_string()) continue;
        const std::string event = record["event"];
        const std::vector<std::uint64_t> at = readFailureFrames(record.value("at", nlohmann::json()));
        if (event == "crash" && record.contains("signal") && record["signal"].is_number_integer()) {
            const int signal = record["signal"].get<int>();
            placesKnown = placesKnown && (!crashTold || (signal == e.crashSignal && at == e.crashAt));
            crashTold = true;
            e.crashSignal = signal;
            e.crashAt = at;
        }
        if (event == "sample" && record.contains("cpu") && record["cpu"].is_number_unsigned()) {
            e.sampleAt = at;
            e.sampleCpu = 1e-6 * static_cast<double>(record["cpu"].get<std::uint64_t>());
        }
        if (event == "threw" && record.contains("type") && record["type"].is_string()) {
            placesKnown = placesKnown && (!throwTold || (record["type"] == e.threwType && at == e.threwAt));
            throwTold = true;
            e.threwType = record["type"];
            e.threwAt = at;
        }
        if (event == "memory") e.memory = true;
        if (event == "refused" && record.contains("call") && record["call"].is_string()) {
            e.refused = record["call"].get<std::string>().substr(0, 64);
        }
        if (event == "terminate") {
            e.terminated = true;
            e.type = record.contains("type") && record["type"].is_string() ? record["type"].get<std::string>() : "";
            e.what = record.contains("what") && record["what"].is_string() ? record["what"].get<std::string>() : "";
            e.terminateAt = readFailureFrames(record.value("at", nlohmann::json()));
        }
    }
    if (!placesKnown) e.crashAt = e.sampleAt = e.threwAt = e.terminateAt = {};
    return e;
}

// The judge's verdict on `test`, if it wrote one; a malformed one leaves `malformed` saying what is wrong.
std::optional<wire::Verdict> judgeVerdict(const std::vector<std::string>& lines, const std::string& test,
                                          std::string* malformed) {
    std::optional<nlohmann::json> end;
    for (const std::string& line : lines) {
        nlohmann::json record = wire::parseBounded(line);
        if (wire::isEndRecord(record, test)) end = std::move(record);
    }
    if (!end) return std::nullopt;
    try {
        return wire::readVerdict(*end);
    } catch (const wire::WireError& e) {
        *malformed = e.what();
        return std::nullopt;
    }
}

// Why a probe that died of a signal died, as far as simlab can tell, and where in the student's file (`site`: " in
// simulate() (NewtonsApple.cpp:52)", or nothing).
std::string crashReason(const isolation::ProcessResult& probe, const ProbeEvents& events, const std::string& site) {
    std::string reason = "crashed (" + isolation::signalName(probe.signal) + ")" + site;
    if (probe.signal == SIGABRT && events.terminated) {
        if (events.type.empty()) return reason + ": std::terminate was called with no exception in flight";
        return reason + ": " + events.type + (events.what.empty() ? "" : " \"" + events.what + "\"") +
               " escaped: nothing caught it, or it left a destructor or a noexcept function";
    }
    if (probe.signal == SIGABRT) {
        const std::size_t at = probe.output.find("Assertion `");
        if (at != std::string::npos) {
            const std::size_t start = probe.output.rfind('\n', at);
            const std::size_t end = probe.output.find('\n', at);
            const std::size_t from = start == std::string::npos ? 0 : start + 1;
            return reason + ": " + probe.output.substr(from, std::min<std::size_t>(end - from, 300));
        }
        return reason + ": abort() was called";
    }
    if (probe.signal == SIGSYS) {
        if (events.refused.empty()) return reason + ": the sandbox refused a system call a simulation does not make";
        return reason + ": the sandbox refuses the system call " + events.refused +
               ", which a simulation does not make (simlab's system-call filter)";
    }
    if (probe.signal == SIGSEGV) return reason + ": a bad pointer, or a stack overflowed by endless recursion";
    if (probe.signal == SIGFPE) return reason + ": an arithmetic fault, such as an integer division by zero";
    return reason;
}

// The last sample of a test stopped for its CPU time, if it says where the student's code was as it was stopped:
// taken when the sampled process had used nearly all the CPU time the test's processes used together (a sample is
// made every tenth of a second, and the engine looks every tenth), not before a process of its own spun the rest.
constexpr double kSampleBefore = 0.5;  // seconds of CPU time
const std::vector<std::uint64_t>& whereStopped(const isolation::ProcessResult& probe, const ProbeEvents& events) {
    static const std::vector<std::uint64_t> none;
    return probe.cpuTimeout && events.sampleCpu >= probe.cpuSeconds - kSampleBefore ? events.sampleAt : none;
}

// Where the student's code was, for a reason: each frame list of `events` the test's outcome may need.
std::vector<std::vector<std::uint64_t>> framesToLookUp(const isolation::ProcessResult& probe,
                                                       const ProbeEvents& events) {
    std::vector<std::vector<std::uint64_t>> frames;
    if (probe.signal != 0 && events.crashSignal == probe.signal) frames.push_back(events.crashAt);
    if (probe.signal == SIGABRT && events.terminated) frames.push_back(events.terminateAt);
    frames.push_back(whereStopped(probe, events));
    frames.push_back(events.threwAt);
    return frames;
}

// "threw T in f() (F.cpp:12): message" for the judge's "threw T: message", when T is the type the probe's event says
// was thrown at that site; the reason as it was otherwise.
std::string withThrowSite(const std::string& reason, const ProbeEvents& events, const FailureSites& sites) {
    const std::string head = "threw " + events.threwType;
    if (events.threwType.empty() || reason.rfind(head + ": ", 0) != 0) return reason;
    const std::string site = sites.site(events.threwAt).inReason();
    return site.empty() ? reason : head + site + reason.substr(head.size());
}

// `stalledFirst` names the test whose stall had this one stopped early (see Stalls), if it was; `events` are what
// its probe said, and `sites` where in the student's file their frames are.
TestResult interpret(const RubricTest& test, const isolation::ProcessResult& probe,
                     const isolation::ProcessResult& judge, const Limits& limits, const std::string& stalledFirst,
                     const ProbeEvents& events, const FailureSites& sites) {
    TestResult t;
    t.name = test.name;
    t.visibility = test.visibility;
    t.maxScore = test.points;
    t.seconds = probe.wallSeconds;
    t.cpuSeconds = probe.cpuSeconds;
    t.output = probe.output;
    std::string malformed;
    const std::optional<wire::Verdict> verdict = judgeVerdict(judge.reports, test.name, &malformed);
    double credit = 0;

    if (!probe.started) {
        t.outcome = Outcome::DidNotFinish;
        t.reason = "could not run the student's code: " + probe.error;
    } else if (!judge.started) {
        t.outcome = Outcome::DidNotFinish;
        t.reason = "could not run the grader's tests: " + judge.error;
    } else if (!verdict && (judge.cpuTimeout || judge.wallTimeout || judge.signal != 0)) {
        t.outcome = Outcome::DidNotFinish;
        t.reason = "the grader's judge stopped (" +
                   std::string(judge.signal ? isolation::signalName(judge.signal) : judge.cpuTimeout ? "its CPU time ran out" : "its time ran out") +
                   ") before this test: a fault in simlab, not in the submission";
    } else if (probe.memoryLimit) {
        t.outcome = Outcome::OutOfMemory;
        t.reason = "its processes together held more than " + std::to_string(limits.memoryMiB) + " MiB";
    } else if (events.memory && (probe.exitCode == 137 || probe.signal != 0)) {
        t.outcome = Outcome::OutOfMemory;
        t.reason = "it needed more than " + std::to_string(limits.memoryMiB) + " MiB";
    } else if (probe.outputLimit) {
        t.outcome = Outcome::OutputTruncated;
        t.reason = "it printed more than " + std::to_string(limits.outputKiB) + " KiB, and was stopped";
    } else if (probe.diskLimit) {
        t.outcome = Outcome::OutOfDisk;
        t.reason = "its files together took more than " + std::to_string(3 * limits.fileMiB) +
                   " MiB, the space a test has, and it was stopped";
    } else if (probe.cpuTimeout) {
        t.outcome = Outcome::TimedOut;
        // Where it was at the last sample of its CPU time, a tenth of a second or so before it was stopped.
        const std::string site = sites.site(whereStopped(probe, events)).inReason();
        t.reason = (site.empty() ? "" : "stopped" + site + ": ") + "no end within " +
                   seconds(std::ceil(limits.cpuSeconds)) + " of CPU time";
    } else if (probe.wallTimeout && !stalledFirst.empty()) {
        t.outcome = Outcome::Stalled;
        t.reason = "no progress for " + seconds(kIdleSeconds) + ": \"" + stalledFirst +
                   "\" had already waited the full " + seconds(limits.wallSeconds) +
                   " of wall-clock time, which a submission is given once";
    } else if (probe.wallTimeout) {
        char text[160];
        std::snprintf(text, sizeof text,
                      "no end after %g s of wall-clock time, having used %.1f s of CPU "
                      "time (sleeping, or waiting for something?)",
                      limits.wallSeconds, probe.cpuSeconds);
        t.outcome = Outcome::Stalled;
        t.reason = text;
    } else if (probe.signal != 0) {
        t.outcome = Outcome::Crashed;
        // An exception nothing caught is where it was thrown (std::terminate's own frames may not unwind: clang's
        // call of it from a noexcept function has no unwind table); any other crash where the signal came.
        std::string site;
        if (probe.signal == SIGABRT && events.terminated) site = sites.site(events.terminateAt).inReason();
        if (site.empty() && events.crashSignal == probe.signal) site = sites.site(events.crashAt).inReason();
        t.reason = crashReason(probe, events, site);
    } else if (!verdict) {
        t.outcome = Outcome::DidNotFinish;
        if (!malformed.empty()) {
            t.reason = "the grader's judge sent a malformed verdict (" + malformed +
                       "): a fault in simlab, not in the submission";
        } else if (judge.output.find("No test cases matched") != std::string::npos) {
            t.reason = "the grader has no test of this name: the rubric and the tests disagree";
        } else {
            t.reason = "the grader's judge ended without a verdict (" +
                       (judge.signal ? isolation::signalName(judge.signal) : "status " + std::to_string(judge.exitCode)) +
                       "): a fault in simlab, not in the submission";
        }
    } else if (verdict->channel == wire::ChannelFailure::ProcessEnded) {
        t.outcome = Outcome::DidNotFinish;
        t.reason = "did not finish: the student's code ended its process (exit status " +
                   std::to_string(probe.exitCode) + ") before it answered";
    } else if (verdict->channel == wire::ChannelFailure::BadReport) {
        t.outcome = Outcome::BadReport;
        t.reason = verdict->reason;
    } else {
        t.outcome = verdict->passed ? Outcome::Passed : Outcome::Failed;
        credit = verdict->passed ? 1.0 : verdict->credit;
        t.reason = verdict->passed ? verdict->reason : withThrowSite(verdict->reason, events, sites);
        t.feedback = verdict->feedback;
        t.attachments = verdict->attachments;
        if (verdict->figure) {
            t.figure = verdict->figure->value;
            t.unit = verdict->figure->unit;
        }
        t.leaderboard = verdict->leaderboard;
    }
    // The judge's account of the test's time (the student's process's, and the judge's own: drawing, say) and of
    // the shared questions it used: hints for sharing the next self-check's tests out, nothing scored.
    if (verdict) {
        t.seconds = std::max(t.seconds, verdict->seconds);
        t.shared = verdict->shared;
    }
    t.credit = credit;
    t.score = roundScore(test.points * credit);
    return t;
}

// Where one submission's grading happens: the probe (a shared object) and the host it runs in, the judges' files,
// a folder per process.
struct Workspace {
    std::string root, build, probe, host;
    std::string student;             ///< GradeOptions::student, for the judge
    FailureSites* sites = nullptr;  ///< where in the student's file the tests' failures were, the judges' together
};

// A judge's files: the rubric, and the files handed in beside the source (or why each was refused).
void writeJudgeFiles(const std::string& dir, const Rubric& rubric, const SubmissionFiles& files) {
    createPrivateFolder(dir);
    createPrivateFolder(dir + "/submission");
    writeFileAtomically(dir + "/rubric.toml", readFile(rubric.path));
    for (const HandedIn& extra : files.extras) {
        if (extra.ok) writeFileAtomically(dir + "/submission/" + extra.name, extra.text);
        else writeFileAtomically(dir + "/submission/" + extra.name + ".refused", extra.refusal);
    }
}

// Where the sandbox's users reach their folders by the host's own paths (as root, without bubblewrap: Landlock, or
// limits only), a folder they pass through to what they are handed, without seeing what else is there; else
// simlab's alone, like everything of a grading (bubblewrap binds each process's folders for it).
void makePassable(const std::string& path) {
    const isolation::SandboxSupport& sandbox = isolation::sandboxSupport();
    if (!sandbox.ownUser || sandbox.bubblewrap) return;
    std::error_code ignored;
    fs::permissions(path, fs::perms::owner_all | fs::perms::group_exec | fs::perms::others_exec, ignored);
}

// What every probe and the probes' server run with.
const std::vector<std::string> kProbeEnvironment = {"PATH=/usr/bin:/bin", "TMPDIR=/tmp", "LC_ALL=C"};

// Where the sandbox allows, the tests' probes are forked from one host started for them (TestServer): each is still
// a process of its own, as a user of its own, and loads the probe only once it is. None where it does not.
std::unique_ptr<isolation::TestServer> startProbeServer(const Workspace& w, const std::string& tag,
                                                        const Limits& limits, std::size_t tests) {
    if (!isolation::testServers()) return nullptr;
    const std::string program = w.root + "/" + tag + "server";
    const std::string home = w.root + "/" + tag + "probes";
    createPrivateFolder(program);
    createPrivateFolder(home);
    // The server's alone (0600 in a folder of 0700): each test's child copies it into its own folder, as its own
    // user, before it loads it (probe_host.cpp).
    writeFileAtomically(program + "/probe.so", readFile(w.probe + "/probe.so"));
    fs::permissions(program + "/probe.so", fs::perms::owner_read | fs::perms::owner_write);
    // Each test's child makes its folder there, through root's group (probe_host.cpp): nothing else of it is
    // any test's to write or list. (bubblewrap puts a folder in memory there, with those modes, for the server.)
    if (!isolation::sandboxSupport().bubblewrap) {
        fs::permissions(home,
                        fs::perms::owner_all | fs::perms::group_write | fs::perms::group_exec | fs::perms::others_exec);
    }
    isolation::ProcessRequest server;
    server.argv = {w.host, "--serve", program + "/probe.so"};
    server.env = kProbeEnvironment;
    server.env.push_back("HOME=" + home);
    server.workDir = home;
    server.limits = serverLimits(limits, tests);
    server.readOnlyPaths = {program, w.host};
    server.scratchWorkDir = true;
    return std::make_unique<isolation::TestServer>(server);
}

// One test's probe (number `number` of its judge), forked from `server` where there is one.
isolation::ProcessResult runProbe(isolation::ProcessRequest probe, isolation::TestServer* server, const Workspace& w,
                                  const std::string& tag, int number) {
    std::optional<isolation::ProcessResult> result;
    if (server) result = server->run(probe);
    if (result) return std::move(*result);
    // A host of its own, run as a user of its own, loading a copy of the probe that user owns while it runs (a
    // test's user never touches another's files, even as one test ends and the next begins).
    const std::string dir = w.root + "/" + tag + "test" + std::to_string(number);
    const std::string program = w.root + "/" + tag + "program" + std::to_string(number);
    createPrivateFolder(dir);
    createPrivateFolder(program);
    writeFileAtomically(program + "/probe.so", readFile(w.probe + "/probe.so"));
    fs::permissions(program + "/probe.so", fs::perms::owner_read);
    probe.argv = {w.host, program + "/probe.so"};
    probe.env = kProbeEnvironment;
    probe.env.push_back("HOME=" + dir);
    probe.workDir = dir;
    probe.readOnlyPaths = {program, w.host};
    probe.handOver = {program};
    return isolation::runProcess(probe);
}

// The probes a judge's tests asked for, each run in a thread of its own; their results by test name.
struct ProbeRuns {
    std::mutex lock;
    std::map<std::string, isolation::ProcessResult> results;
    std::vector<std::thread> running;
    int started = 0;
    std::atomic<double> judgeCpu{0};  // the judge's CPU time so far, for idleWatch
};

// Answers the judge on `socket` until it is done: each message is "probe <test>"; each reply carries the judge's
// ends of two new pipes, whose other ends are the new probe's descriptors 4 (requests) and 5 (answers).
void serveProbes(int socket, ProbeRuns& runs, Stalls& stalls, isolation::TestServer* server, const Workspace& w,
                 const std::string& tag, const Limits& limits,
                 const std::function<void(const std::string&)>& progress) {
    char message[1024];
    for (;;) {
        const ssize_t n = ::recv(socket, message, sizeof message, 0);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 6 || std::string(message, 6) != "probe ") break;  // the judge is done (or confused)
        const std::string test(message + 6, static_cast<std::size_t>(n) - 6);
        if (progress) progress(test);
        int requests[2] = {-1, -1}, answers[2] = {-1, -1};
        if (::pipe2(requests, O_CLOEXEC) != 0 || ::pipe2(answers, O_CLOEXEC) != 0) {
            for (int fd : {requests[0], requests[1], answers[0], answers[1]}) {
                if (fd >= 0) ::close(fd);
            }
            break;  // the judge reads the socket's end: its tests say the process could not start
        }
        isolation::ProcessRequest probe;
        probe.limits = limits;
        probe.reportChannel = true;
        probe.passFds = {{4, requests[0]}, {5, answers[1]}};
        probe.isolate = true;
        probe.scratchWorkDir = true;
        probe.stalled = idleWatch(stalls, runs.judgeCpu, test);
        runs.running.emplace_back([&runs, &stalls, server, &w, &tag, probe, test, number = ++runs.started] {
            isolation::ProcessResult result = runProbe(probe, server, w, tag, number);
            if (result.wallTimeout) {
                std::lock_guard<std::mutex> guard(stalls.lock);
                if (stalls.first.empty()) stalls.first = test;
            }
            std::lock_guard<std::mutex> guard(runs.lock);
            runs.results[test] = std::move(result);
        });
        // The judge's ends: sent, then closed here, so that each pipe ends when its last holder does.
        const int ends[2] = {requests[1], answers[0]};
        const char byte = 'p';
        const bool sent = isolation::sendWithDescriptors(socket, &byte, 1, {ends[0], ends[1]});
        ::close(ends[0]);
        ::close(ends[1]);
        if (!sent) break;
    }
}

// The judge of `tests`, asking for probes on the socket `probes` at its descriptor 6. It runs from a copy of its
// own, in the folder its user owns for the run: the course's judge may be (and, graded without bubblewrap or
// Landlock, must be) unreadable to every other user.
isolation::ProcessResult runJudge(const Assignment& assignment, const std::vector<const RubricTest*>& tests,
                                  const Workspace& w, const std::string& judgeFiles, const std::string& tag,
                                  const Limits& limits, int probes, std::atomic<double>& cpu) {
    const std::string judgeProgram = judgeFiles + "/judge";
    writeFileAtomically(judgeProgram, readFile(assignment.judge));
    fs::permissions(judgeProgram, fs::perms::owner_all);
    isolation::ProcessRequest judge;
    // The tests' names in a file of the judge's own (Catch2's --input-file, a name a line), not on its command
    // line, which every user may read in /proc where no namespace hides the judge's process (limits only).
    std::string names;
    for (const RubricTest* test : tests) names += test->name + "\n";
    writeFileAtomically(judgeFiles + "/tests.txt", names);
    judge.argv = {judgeProgram, "--use-colour", "no", "--input-file", judgeFiles + "/tests.txt"};
    judge.env = {"PATH=/usr/bin:/bin", "HOME=" + w.root + "/" + tag + "judge-home", "TMPDIR=/tmp", "LC_ALL=C",
                 "SIMLAB_RUBRIC=" + judgeFiles + "/rubric.toml", "SIMLAB_SUBMISSION_DIR=" + judgeFiles + "/submission",
                 "SIMLAB_ANSWER_LIMIT=" + std::to_string(static_cast<unsigned long long>(limits.observationMiB) << 20)};
    if (!w.student.empty()) judge.env.push_back("SIMLAB_STUDENT=" + w.student);
    judge.workDir = w.root + "/" + tag + "judge-home";
    createPrivateFolder(judge.workDir);
    judge.limits = judgeLimits(limits, tests.size());
    judge.reportChannel = true;
    judge.passFds = {{6, probes}};
    judge.isolate = true;
    judge.readOnlyPaths = {judgeProgram, judgeFiles};
    judge.handOver = {judgeFiles};  // its user's alone: no probe can read the judge, the rubric or the files
    judge.scratchWorkDir = true;
    judge.stalled = [&cpu](double used) {
        cpu = used;
        return false;
    };
    return isolation::runProcess(judge);
}

// The tests of one submission: one judge runs them all, in turn, and at each test's first question asks for a
// probe of that test's own on the socket at its descriptor 6 (serveProbes). `judgeFiles` is this judge's own copy
// of the rubric and the files handed in (its user owns it for the run), and `tag` sets its processes' folders apart
// from those of judges running beside it.
std::vector<TestResult> runTests(const Assignment& assignment, const std::vector<const RubricTest*>& tests,
                                 const Workspace& w, const std::string& judgeFiles, const std::string& tag,
                                 const Limits& limits, Stalls& stalls, std::string* graderOutput,
                                 const std::function<void(const std::string&)>& progress) {
    int socket[2];
    if (::socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, socket) != 0) {
        throw std::runtime_error(std::string("cannot create a socket: ") + std::strerror(errno));
    }
    ProbeRuns probes;
    // The server starts while the judge does.
    std::unique_ptr<isolation::TestServer> probeServer = startProbeServer(w, tag, limits, tests.size());
    std::thread server([&] { serveProbes(socket[0], probes, stalls, probeServer.get(), w, tag, limits, progress); });
    // Ends the server's wait (should the judge have left a copy behind) and its probes: after the judge, or when
    // the judge could not be started at all (its error then goes on, never a std::terminate of a running thread).
    auto endServer = [&] {
        ::shutdown(socket[0], SHUT_RDWR);
        server.join();
        for (std::thread& t : probes.running) t.join();
        probeServer.reset();
        ::close(socket[0]);
    };
    isolation::ProcessResult judged;
    try {
        judged = runJudge(assignment, tests, w, judgeFiles, tag, limits, socket[1], probes.judgeCpu);
    } catch (...) {
        endServer();
        throw;
    }
    endServer();
    *graderOutput = judged.output;

    bool interrupted = judged.interrupted;
    for (const auto& [test, probe] : probes.results) interrupted = interrupted || probe.interrupted;
    if (interrupted) throw Interrupted();
    std::vector<isolation::ProcessResult> ran;
    std::vector<ProbeEvents> events;
    std::vector<std::vector<std::uint64_t>> lookUp;
    for (const RubricTest* test : tests) {
        isolation::ProcessResult probe;  // a test that asked nothing had no probe: as if one had started and ended cleanly
        probe.started = true;
        probe.exitCode = 0;
        if (const auto found = probes.results.find(test->name); found != probes.results.end()) probe = found->second;
        events.push_back(probeEvents(probe.reports));
        for (auto& frames : framesToLookUp(probe, events.back())) lookUp.push_back(std::move(frames));
        ran.push_back(std::move(probe));
    }
    // Where the failures were, every test's at once.
    w.sites->lookUp(lookUp);
    std::vector<TestResult> results;
    for (std::size_t i = 0; i < tests.size(); ++i) {
        std::string stalledFirst;
        {
            std::lock_guard<std::mutex> guard(stalls.lock);
            if (stalls.stopped.count(tests[i]->name)) stalledFirst = stalls.first;
        }
        results.push_back(interpret(*tests[i], ran[i], judged, limits, stalledFirst, events[i], *w.sites));
    }
    return results;
}

// The selected tests, over `options.judges` judges at once (shareTests), each with files of its own; the results
// come back in the rubric's order.
std::vector<TestResult> runJudges(const Assignment& assignment, const Rubric& rubric, const SubmissionFiles& files,
                                  const std::vector<const RubricTest*>& selected, const Workspace& w,
                                  const Limits& limits, const GradeOptions& options, std::string* graderOutput) {
    if (selected.empty()) return {};
    std::vector<std::string> names;
    for (const RubricTest* test : selected) names.push_back(test->name);
    std::vector<std::size_t> judgeOf = shareTests(names, options.expected, options.judges);
    std::map<std::size_t, std::size_t> used;  // the judges given work, numbered from 0 in order
    for (std::size_t k : judgeOf) used.emplace(k, 0);
    std::size_t judges = 0;
    for (auto& [k, number] : used) number = judges++;
    std::vector<std::vector<const RubricTest*>> shares(judges);
    std::vector<std::pair<std::size_t, std::size_t>> placed(selected.size());  // test i: judge, place in its share
    for (std::size_t i = 0; i < selected.size(); ++i) {
        const std::size_t k = used.at(judgeOf[i]);
        placed[i] = {k, shares[k].size()};
        shares[k].push_back(selected[i]);
    }
    std::vector<std::vector<TestResult>> results(judges);
    std::vector<std::string> outputs(judges);
    std::mutex told;
    Stalls stalls;
    auto progress = [&](const std::string& test) {
        if (!options.progress) return;
        std::lock_guard<std::mutex> guard(told);
        options.progress(test);
    };
    forEachInParallel(judges, static_cast<int>(judges), [&](std::size_t k) {
        const std::string dir = w.root + "/judge" + std::to_string(k + 1);
        writeJudgeFiles(dir, rubric, files);
        results[k] = runTests(assignment, shares[k], w, dir, "j" + std::to_string(k + 1) + "-", limits, stalls,
                              &outputs[k], progress);
    });
    std::vector<TestResult> ordered;
    for (std::size_t i = 0; i < selected.size(); ++i) ordered.push_back(results[placed[i].first][placed[i].second]);
    for (const std::string& output : outputs) *graderOutput += output;
    return ordered;
}

}  // namespace

std::string outcomeName(Outcome outcome) {
    switch (outcome) {
        case Outcome::Passed: return "passed";
        case Outcome::Failed: return "failed";
        case Outcome::TimedOut: return "timed out";
        case Outcome::Stalled: return "stalled";
        case Outcome::OutOfMemory: return "killed for memory";
        case Outcome::OutOfDisk: return "killed for disk";
        case Outcome::Crashed: return "crashed";
        case Outcome::OutputTruncated: return "output truncated";
        case Outcome::BadReport: return "bad report";
        case Outcome::DidNotFinish: return "did not finish";
        case Outcome::DidNotCompile: return "did not compile";
        case Outcome::Refused: return "refused";
        case Outcome::MissingFile: return "missing file";
    }
    return "unknown";
}

Outcome outcomeNamed(const std::string& name) {
    for (Outcome o : {Outcome::Passed, Outcome::Failed, Outcome::TimedOut, Outcome::Stalled, Outcome::OutOfMemory,
                      Outcome::OutOfDisk, Outcome::Crashed, Outcome::OutputTruncated, Outcome::BadReport, Outcome::DidNotFinish,
                      Outcome::DidNotCompile, Outcome::Refused, Outcome::MissingFile}) {
        if (outcomeName(o) == name) return o;
    }
    throw std::invalid_argument("unknown outcome '" + name + "'");
}

SubmissionStatus buildFailure(const BuildResult& build) {
    return build.stage == "check"  ? SubmissionStatus::ForbiddenCode
           : build.stage == "link" ? SubmissionStatus::DidNotLink
                                   : SubmissionStatus::DidNotCompile;
}

GradeReport notGradedReport(const Assignment& assignment, const Rubric& rubric, SubmissionStatus status,
                            const std::string& note, bool includeHidden) {
    GradeReport report;
    report.assignment = assignment.id;
    report.title = assignment.title;
    report.manual = rubric.manual;
    report.status = status;
    report.note = note;
    report.build.stage = "missing";
    for (const RubricTest& test : rubric.tests) {
        if (!includeHidden && !test.visible()) {
            ++report.notRunCount;
            report.notRunPoints += test.points;
            continue;
        }
        TestResult t;
        t.name = test.name;
        t.visibility = test.visibility;
        t.maxScore = test.points;
        t.outcome = status == SubmissionStatus::MissingFile ? Outcome::MissingFile : Outcome::Refused;
        t.reason = note;
        report.tests.push_back(t);
    }
    return report;
}

std::string placesExposed(const Manifest& manifest) {
    const isolation::SandboxSupport& sandbox = isolation::sandboxSupport();
    if (sandbox.bubblewrap || sandbox.landlock) return "";
    const isolation::Exposure exposure = isolation::exposedPlaces(lentOfPlaces(manifest));
    if (!exposure.exposed()) return "";
    const std::string why = "in this sandbox (" + sandbox.mode + ") ";
    if (!exposure.error.empty()) return why + exposure.error + ", so hidden tests are not run: install bubblewrap";
    // What was read first; a place passed through; or, where the walk stopped at its bound before either, the
    // place it was in.
    const bool tooMany = exposure.readable.empty() && exposure.passable.empty();
    const bool passage = !tooMany && exposure.readable.empty();
    const std::string& first = tooMany   ? exposure.boundedIn
                               : passage ? exposure.passable.front()
                                         : exposure.readable.front();
    if (::geteuid() != 0) {
        // A test runs as this user, and reads what this user may: no mode keeps it out.
        return why + "a test's code runs as you and could read " + printable(first) +
               ", so hidden tests are not run: grade hidden tests as root (each test then runs as a user of its "
               "own), or where bubblewrap or Landlock runs";
    }
    // The command that closes what was read: simlab lock closes the course's places; a lab's folder, a class or
    // its grades it closes when named.
    const std::string place = isolation::placeOf(first);
    std::string named;
    for (const auto& lab : manifest.labs) {
        if (place == lab->dir || (place.rfind(manifest.cacheDir + "/labs/", 0) == 0 &&
                                  place == labBuildFolder(manifest, lab->dir))) {
            named = lab->dir;
        }
    }
    const std::vector<std::string> course = {manifest.sourceDir, manifest.buildDir, manifest.cacheDir,
                                             manifest.sampleClass, fs::path(manifest.path).parent_path().string()};
    const bool ofTheCourse =
        std::any_of(course.begin(), course.end(), [&](const std::string& c) {
            return !c.empty() && (place == c || place.rfind(c + "/", 0) == 0 || c.rfind(place + "/", 0) == 0);
        }) ||
        (manifest.installed && place.rfind(manifest.prefix + "/", 0) == 0);
    if (named.empty() && !ofTheCourse) named = place;
    const std::size_t more = passage || tooMany ? 0 : exposure.readableCount - 1;
    return why +
           (tooMany ? "simlab's places hold more files others may reach than it can try (over 500,000, in " +
                          printable(first) + ")"
            : passage ? "a test's code could pass through " + printable(first) + " to what simlab writes there"
                      : "a test's code could read " + printable(first)) +
           (more > 0 ? " and " + std::string(exposure.bounded ? "at least " : "") + std::to_string(more) +
                           " more file" + (more == 1 ? "" : "s") + " of simlab's places"
                     : std::string()) +
           ", so hidden tests are not run: close them with `simlab lock" +
           (named.empty() ? "" : " " + printable(named)) +
           "` (it leaves other users only what a test is lent), or install bubblewrap";
}

double roundScore(double points) { return std::round(points * 100.0) / 100.0; }

double GradeReport::score() const {
    double total = 0;
    for (const TestResult& t : tests) total += t.score;
    return roundScore(total);
}

double GradeReport::maxScore() const {
    double total = 0;
    for (const TestResult& t : tests) total += t.maxScore;
    return roundScore(total);
}

double StudentRecord::rawTotal() const {
    double sum = score;
    for (const ManualGrade& m : manual) sum += m.points.value_or(0);
    return roundScore(sum);
}

double StudentRecord::latePoints() const { return roundScore(rawTotal() * late.percent / 100); }

double StudentRecord::total() const { return roundScore(rawTotal() - latePoints()); }

double StudentRecord::maxTotal() const {
    double sum = maxScore;
    for (const ManualGrade& m : manual) sum += m.maxPoints;
    return roundScore(sum);
}

double StudentRecord::pendingPoints() const {
    double sum = 0;
    for (const ManualGrade& m : manual) sum += m.points ? 0 : m.maxPoints;
    return roundScore(sum);
}

std::optional<TestCost> readTestCost(const nlohmann::json& record) {
    auto seconds = [](const nlohmann::json& value) {
        return value.is_number() && std::isfinite(value.get<double>()) && value.get<double>() >= 0;
    };
    if (!record.is_object()) return std::nullopt;
    const nlohmann::json took = record.value("seconds", nlohmann::json());
    if (!seconds(took)) return std::nullopt;
    TestCost cost;
    cost.seconds = took.get<double>();
    const nlohmann::json shared = record.value("shared", nlohmann::json());
    if (shared.is_object()) {
        for (const auto& [digest, answer] : shared.items()) {
            if (cost.shared.size() >= 256 || digest.size() > 16 || !seconds(answer)) continue;
            cost.shared[digest] = answer.get<double>();
        }
    }
    return cost;
}

std::vector<std::size_t> shareTests(const std::vector<std::string>& tests,
                                    const std::map<std::string, TestCost>& expected, int judgeCount) {
    const std::size_t n = tests.size();
    const std::size_t judges =
        std::clamp<std::size_t>(static_cast<std::size_t>(std::max(judgeCount, 1)), 1, std::max<std::size_t>(n, 1));
    std::vector<std::size_t> judgeOf(n);
    for (std::size_t i = 0; i < n; ++i) judgeOf[i] = i % judges;
    if (expected.empty() || judges == 1) return judgeOf;
    // A shared answer costs what it took where it was computed; a test's own cost is its time less the answers it
    // computed, and a test not seen before is as long as the longest.
    std::map<std::string, double> answerCost;
    double longest = 0;
    for (const auto& [name, cost] : expected) {
        longest = std::max(longest, cost.seconds);
        for (const auto& [digest, seconds] : cost.shared) answerCost[digest] = std::max(answerCost[digest], seconds);
    }
    // Tests group by shared work: a test joins the others asking its answers when computing them again elsewhere
    // would cost more than the test itself. A group is named by its first test (group[i], test i's).
    std::vector<std::size_t> group(n);
    std::iota(group.begin(), group.end(), 0);
    std::vector<double> own(n, longest);
    std::vector<std::set<std::string>> asks(n);
    std::map<std::string, std::size_t> askedFirstBy;
    for (std::size_t i = 0; i < n; ++i) {
        const auto found = expected.find(tests[i]);
        if (found == expected.end()) continue;
        double computed = 0, again = 0;
        for (const auto& [digest, seconds] : found->second.shared) {
            computed += seconds;
            again += answerCost[digest];
            asks[i].insert(digest);
        }
        own[i] = std::max(found->second.seconds - computed, 0.0);
        if (again <= own[i]) continue;
        for (const std::string& digest : asks[i]) {
            const std::size_t a = group[askedFirstBy.emplace(digest, i).first->second], b = group[i];
            for (std::size_t& g : group) g = g == std::max(a, b) ? std::min(a, b) : g;
        }
    }
    // A group costs its tests' own time and each answer they ask once; the costliest goes first, to the judge with
    // the least so far (the first such judge on a tie).
    std::map<std::size_t, std::pair<double, std::set<std::string>>> groups;
    for (std::size_t i = 0; i < n; ++i) {
        groups[group[i]].first += own[i];
        groups[group[i]].second.insert(asks[i].begin(), asks[i].end());
    }
    std::vector<std::pair<std::size_t, double>> costliest;
    for (auto& [first, cost] : groups) {
        for (const std::string& digest : cost.second) cost.first += answerCost[digest];
        costliest.emplace_back(first, cost.first);
    }
    std::stable_sort(costliest.begin(), costliest.end(),
                     [](const auto& a, const auto& b) { return a.second > b.second; });
    std::vector<double> load(judges, 0.0);
    for (const auto& [first, seconds] : costliest) {
        const auto least = std::min_element(load.begin(), load.end());
        *least += seconds;
        for (std::size_t i = 0; i < n; ++i) {
            if (group[i] == first) judgeOf[i] = static_cast<std::size_t>(least - load.begin());
        }
    }
    return judgeOf;
}

void requireStudentId(const std::string& id) {
    const bool control = std::any_of(id.begin(), id.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; });
    if (id.size() > 256 || control) {
        throw UsageError("a student's id is at most 256 characters with no control characters: " + printable(id));
    }
}

GradeReport gradeSubmission(const Builder& builder, const Assignment& assignment, const Rubric& rubric,
                            const SubmissionFiles& files, const GradeOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    GradeReport report;
    report.assignment = assignment.id;
    report.title = assignment.title;
    report.manual = rubric.manual;
    report.source = files.shown;
    report.sandbox = isolation::sandboxSupport().summary;
    for (const HandedIn& extra : files.extras) {
        if (!extra.ok) report.note += (report.note.empty() ? "" : "; ") + extra.refusal;
    }

    for (const std::string& name : options.onlyTests) {
        if (!rubric.find(name)) throw UsageError("no test named '" + name + "' in " + rubric.path);
    }
    auto wanted = [&](const RubricTest& test) {
        return options.onlyTests.empty() ||
               std::find(options.onlyTests.begin(), options.onlyTests.end(), test.name) != options.onlyTests.end();
    };
    std::vector<const RubricTest*> selected;
    for (const RubricTest& test : rubric.tests) {
        if (!wanted(test)) continue;
        if (options.includeHidden || test.visible()) {
            selected.push_back(&test);
        } else {
            ++report.notRunCount;
            report.notRunPoints += test.points;
        }
    }

    // work/build: the student's file and its object (the compiler's folder); work/probe: the probe, which its
    // sandbox is lent; work/judgeN: the rubric and the files handed in beside the source, which judge N's sandbox
    // is lent - never a probe's. Each process gets an empty folder of its own as well.
    TempDir work("simlab-" + assignment.id + "-", options.workRoot);
    Workspace w{work.path(), work.path() + "/build", work.path() + "/probe", builder.probeHost(), options.student};
    // Every folder of the grading is private from the moment it exists: the judge's copy, the rubric and the
    // student's source are never another user's to read, even while they are being written. Each folder below is
    // handed to the sandbox user of the process that works in it, for that run (0700); the probe's is simlab's
    // alone (each test gets a copy of its own): where files are kept apart by their modes alone, no other
    // student's test may read this one's probe.
    for (const std::string& dir : {w.build, w.probe}) createPrivateFolder(dir);
    makePassable(w.root);
    if (options.progress) options.progress("building");
    report.build =
        builder.buildProbe(assignment, files.name, files.text, w.build, w.probe + "/probe.so", options.checkObject);
    if (report.build.interrupted) throw Interrupted();
    const Limits limits = options.limits.value_or(rubric.limits);

    if (report.build.ok) {
        // The probe's twin with line tables, made only when a failure needs a place (failure_sites.h): the same
        // file and link, compiled with -g1.
        const std::size_t lines = static_cast<std::size_t>(std::count(files.text.begin(), files.text.end(), '\n')) + 1;
        FailureSites sites(w.probe + "/probe.so", report.build.object, files.name, lines, w.root + "/lines",
                           [&](const std::string& folder) {
                               Assignment lined = assignment;
                               lined.compile.push_back("-g1");
                               const BuildResult twin = builder.buildProbe(lined, files.name, files.text, folder,
                                                                           folder + "/probe.so", false);
                               return twin.ok ? FailureSites::LinedTwin{twin.binary, twin.object}
                                              : FailureSites::LinedTwin{};
                           });
        w.sites = &sites;
        report.tests = runJudges(assignment, rubric, files, selected, w, limits, options, &report.graderOutput);
    } else {
        const std::string& stage = report.build.stage;
        report.status = buildFailure(report.build);
        const std::string firstReason = report.build.log.substr(0, report.build.log.find('\n'));
        for (const RubricTest* test : selected) {
            TestResult t;
            t.name = test->name;
            t.visibility = test->visibility;
            t.maxScore = test->points;
            t.outcome = stage == "check" ? Outcome::Refused : Outcome::DidNotCompile;
            t.reason = stage == "check" || report.build.stoppedByLimit ? firstReason : statusName(report.status);
            report.tests.push_back(t);
        }
    }
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return report;
}

}  // namespace simlab::engine
