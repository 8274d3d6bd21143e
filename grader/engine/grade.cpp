#include "simlab/engine/grade.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "simlab/engine/errors.h"
#include "simlab/engine/files.h"
#include "simlab/engine/process.h"

namespace fs = std::filesystem;

namespace simlab::engine {

namespace {

std::string seconds(double s) {
    char text[32];
    std::snprintf(text, sizeof text, "%g s", s);
    return text;
}

// What the report channel said: the test's "end" record if it wrote one, and whether it ran out of memory.
struct Reported {
    bool started = false;
    bool memory = false;
    std::optional<nlohmann::json> end;
};

Reported parseReports(const std::vector<std::string>& lines, const std::string& test) {
    Reported r;
    for (const std::string& line : lines) {
        const nlohmann::json record = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
        if (!record.is_object() || !record.contains("event")) continue;
        const std::string event = record.value("event", "");
        if (event == "memory") r.memory = true;
        if (record.value("test", "") != test) continue;
        if (event == "start") r.started = true;
        if (event == "end") r.end = record;
    }
    return r;
}

TestResult interpret(const RubricTest& test, const ProcessResult& run, const Limits& limits) {
    TestResult t;
    t.name = test.name;
    t.visibility = test.visibility;
    t.maxScore = test.points;
    t.seconds = run.wallSeconds;
    t.output = run.output;
    const Reported reported = parseReports(run.reports, test.name);
    double credit = 0;

    if (!run.started) {
        t.outcome = Outcome::DidNotFinish;
        t.reason = "could not run the grader: " + run.error;
    } else if (reported.memory) {
        t.outcome = Outcome::OutOfMemory;
        t.reason = "killed for memory: it needed more than " + std::to_string(limits.memoryMiB) + " MiB";
    } else if (run.outputLimit) {
        t.outcome = Outcome::OutputTruncated;
        t.reason = "output truncated: it printed more than " + std::to_string(limits.outputKiB) + " KiB, and was stopped";
    } else if (run.wallTimeout) {
        t.outcome = Outcome::TimedOut;
        t.reason = "timed out after " + seconds(limits.wallSeconds);
    } else if (run.cpuTimeout) {
        t.outcome = Outcome::TimedOut;
        t.reason = "timed out after " + seconds(std::ceil(limits.cpuSeconds)) + " of CPU time";
    } else if (run.signal != 0) {
        t.outcome = Outcome::Crashed;
        t.reason = "crashed (" + signalName(run.signal) + ")";
        if (reported.end && !reported.end->value("reason", "").empty()) {
            t.reason += ": " + reported.end->value("reason", "");
        }
    } else if (!reported.end) {
        t.outcome = Outcome::DidNotFinish;
        if (run.output.find("No test cases matched") != std::string::npos) {
            t.reason = "the grader has no test of this name: the rubric and the tests disagree";
        } else {
            t.reason = "did not finish: the process exited with status " + std::to_string(run.exitCode) +
                       (reported.started ? " before the test reported its end" : " before the test started");
            const std::string firstLine = run.output.substr(0, run.output.find('\n'));
            if (!reported.started && !firstLine.empty()) t.reason += " (" + firstLine + ")";
        }
    } else {
        const nlohmann::json& end = *reported.end;
        const bool passed = end.value("passed", false);
        t.outcome = passed ? Outcome::Passed : Outcome::Failed;
        credit = passed ? 1.0 : std::clamp(end.value("credit", 0.0), 0.0, 1.0);
        t.reason = end.value("reason", "");
        if (end.contains("feedback") && end["feedback"].is_array()) {
            for (const auto& line : end["feedback"]) {
                if (line.is_string()) t.feedback.push_back(line.get<std::string>());
            }
        }
        if (end.contains("figure") && end["figure"].is_object()) {
            t.figure = end["figure"].value("value", 0.0);
            t.unit = end["figure"].value("unit", "");
        }
    }
    t.score = roundScore(test.points * credit);
    return t;
}

}  // namespace

std::string outcomeName(Outcome outcome) {
    switch (outcome) {
        case Outcome::Passed: return "passed";
        case Outcome::Failed: return "failed";
        case Outcome::TimedOut: return "timed out";
        case Outcome::OutOfMemory: return "killed for memory";
        case Outcome::Crashed: return "crashed";
        case Outcome::OutputTruncated: return "output truncated";
        case Outcome::DidNotFinish: return "did not finish";
        case Outcome::DidNotCompile: return "did not compile";
        case Outcome::MissingFile: return "missing file";
    }
    return "unknown";
}

Outcome outcomeNamed(const std::string& name) {
    for (Outcome o : {Outcome::Passed, Outcome::Failed, Outcome::TimedOut, Outcome::OutOfMemory, Outcome::Crashed,
                      Outcome::OutputTruncated, Outcome::DidNotFinish, Outcome::DidNotCompile, Outcome::MissingFile}) {
        if (outcomeName(o) == name) return o;
    }
    throw std::invalid_argument("unknown outcome '" + name + "'");
}

GradeReport missingReport(const Assignment& assignment, const Rubric& rubric, const std::string& note,
                          bool includeHidden) {
    GradeReport report;
    report.assignment = assignment.id;
    report.title = assignment.title;
    report.status = "missing file";
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
        t.outcome = Outcome::MissingFile;
        t.reason = note;
        report.tests.push_back(t);
    }
    return report;
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

GradeReport gradeSource(const Builder& builder, const Assignment& assignment, const Rubric& rubric,
                        const std::string& source, const GradeOptions& options) {
    requireCppSource(source);
    const auto start = std::chrono::steady_clock::now();
    GradeReport report;
    report.assignment = assignment.id;
    report.title = assignment.title;
    report.source = source;

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

    // work/build: the student's file and its object; work/grader: the grader and the rubric, which the sandbox
    // lends each test read-only (nothing else: not even the student's own source); work/testN: each test's
    // empty working directory.
    TempDir work("simlab-" + assignment.id + "-", options.workRoot);
    const std::string buildDir = work.path() + "/build", graderDir = work.path() + "/grader";
    fs::create_directory(buildDir);
    fs::create_directory(graderDir);
    report.build = builder.buildGrader(assignment, source, buildDir, graderDir + "/grader");
    const Limits limits = options.limits.value_or(rubric.limits);

    if (report.build.ok) {
        const std::string rubricCopy = graderDir + "/rubric.toml";
        writeFileAtomically(rubricCopy, readFile(rubric.path));
        // Files handed in beside the source (answers, say), for the tests to read.
        const std::string handedIn = graderDir + "/submission";
        fs::create_directory(handedIn);
        for (const std::string& name : rubric.extraFiles) {
            const fs::path file = fs::path(source).parent_path() / name;
            if (fs::is_regular_file(file)) writeFileAtomically(handedIn + "/" + name, readFile(file.string()));
        }
        const fs::perms readable = fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                   fs::perms::others_read | fs::perms::others_exec;
        fs::permissions(work.path(), readable);
        fs::permissions(graderDir, readable);
        fs::permissions(handedIn, readable);
        int index = 0;
        for (const RubricTest* test : selected) {
            const std::string dir = work.path() + "/test" + std::to_string(++index);
            fs::create_directory(dir);
            ProcessRequest request;
            request.argv = {report.build.binary, test->name, "--use-colour", "no"};
            request.env = {"PATH=/usr/bin:/bin", "HOME=" + dir, "TMPDIR=/tmp", "LC_ALL=C",
                           "SIMLAB_RUBRIC=" + rubricCopy, "SIMLAB_SUBMISSION_DIR=" + handedIn};
            request.workDir = dir;
            request.limits = limits;
            request.reportChannel = true;
            request.isolate = true;
            request.readOnlyPaths = {graderDir};
            request.slot = options.slot;
            const ProcessResult run = runProcess(request);
            if (run.interrupted) throw Interrupted();
            report.tests.push_back(interpret(*test, run, limits));
        }
    } else {
        const std::string reason = report.build.stage == "link" ? "did not link" : "did not compile";
        report.status = reason;
        for (const RubricTest* test : selected) {
            TestResult t;
            t.name = test->name;
            t.visibility = test->visibility;
            t.maxScore = test->points;
            t.outcome = Outcome::DidNotCompile;
            t.reason = reason;
            report.tests.push_back(t);
        }
    }
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return report;
}

}  // namespace simlab::engine
