// simlab check: a student's self-check on the visible tests (or, for instructors, on all of them).
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.h"
#include "simlab/cli_checks.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/grading/grade.h"
#include "simlab/build/manifest.h"
#include "simlab/grading/report.h"
#include "simlab/common/text.h"
#include "simlab/course/policy.h"
#include "simlab/writers/writers.h"
#include "simlab/rubric/rubric.h"
#include "simlab/trade_question.h"

namespace simlab::cli {

namespace {

struct CheckOptions {
    std::string assignment;
    std::string source;
    std::string format = "text";
    bool all = false;
    double timeout = 0;
    std::string rubric;
    std::vector<std::string> tests;
    int jobs = 0;
    std::string student;
};

/// The trade question's scene the check grades on, in words: the student's own where the rubric gives each one
/// ([variants]), else the question's; empty for a lab without a trade question.
std::string tradeSceneLine(const engine::Assignment& assignment, const Rubric& rubric, const std::string& student) {
    const std::string file = assignment.dir + "/grading/trade-question.json";
    if (assignment.dir.empty() || !std::filesystem::exists(file)) return "";
    const trade::Question q = trade::parseQuestion(engine::readFile(file), file);
    const Variants& v = rubric.variants;
    const trade::Scene& s = trade::sceneFor(q, v.perStudent, v.seed, student);
    std::string whose = "The trade question's scene";
    if (v.perStudent && !q.variants.empty()) {
        whose = student.empty() ? "Each student has a trade scene of their own (check with --student ID to grade on "
                                  "yours); without an id, the question's scene"
                                : "Your trade scene (student " + student + ", variant " +
                                      std::to_string(trade::variantIndex(v.seed, student, q.variants.size()) + 1) +
                                      " of " + std::to_string(q.variants.size()) + ")";
    }
    char time[32];
    std::snprintf(time, sizeof time, "%g", s.finalTime);
    return whose + ": " + s.name + ": " + s.scene.dump() + " to " + time + " s";
}

// What the course's cap on graded submissions (course.toml beside the rubric) means for a self-check: a check counts
// for nothing; how many are left is the platform's to say, in its results. Empty without a cap.
std::string capLine(const engine::Assignment& assignment, const std::string& rubricPath) {
    using namespace simlab::engine;
    const std::string path = (std::filesystem::path(rubricPath).parent_path() / "course.toml").string();
    if (!std::filesystem::is_regular_file(path)) return "";
    try {
        const SubmissionCap cap = loadLatePolicy(path, assignment.id, {}).cap;
        if (cap.max <= 0) return "";
        return "Graded submissions: the course counts " + std::to_string(cap.max) +
               (cap.windowHours > 0 ? " each " + points(cap.windowHours) + " h" : std::string()) +
               " on its platform; this check is none of them, and the platform's results say how many you have left";
    } catch (const std::exception& e) {
        std::cerr << "simlab: warning: " << printable(e.what()) << '\n';
        return "";
    }
}

void runCheck(const CheckOptions& o) {
    using namespace simlab::engine;
    const Manifest manifest = loadManifest();
    sayLeftovers(sweepLeftovers());
    const Assignment& assignment = manifest.find(o.assignment);
    const std::string source = o.source.empty() ? assignment.starter : o.source;
    requireCppSource(source);
    if (o.all && !assignment.hiddenTestsBuilt) {
        throw UsageError("--all needs the hidden tests, which this copy of simlab does not have");
    }
    const Rubric rubric = loadRubric(o.rubric.empty() ? assignment.rubric : o.rubric);
    if (const std::string closed = sandboxCannotReach(manifest, assignment); !closed.empty()) throw UsageError(closed);
    if (const std::string closed = judgeNotYours(assignment); !closed.empty()) throw UsageError(closed);
    // The hidden tests must be out of a test's reach to run, and out of the compiler's whenever they lie among the
    // system's files (an installation in /usr/local), where a sandbox without bubblewrap lets every process read:
    // an #include of one would show its lines in the compiler's messages.
    const bool amongSystemFiles = manifest.sourceDir.rfind("/usr/", 0) == 0 || manifest.buildDir.rfind("/usr/", 0) == 0;
    if (o.all || amongSystemFiles) {
        if (const std::string exposed = placesExposed(manifest); !exposed.empty()) throw UsageError(exposed);
    } else if (const isolation::SandboxSupport& sandbox = isolation::sandboxSupport();
               sandbox.ownUser && !sandbox.bubblewrap && !sandbox.landlock) {
        // As root with limits only, the visible tests of a file one does not trust read what the modes allow: said.
        std::cerr << "simlab: warning: " << sandbox.warning << "\n";
        if (const std::string exposed = placesExposed(manifest); !exposed.empty()) {
            std::cerr << "simlab: warning: " << exposed.substr(0, exposed.find(", so hidden tests")) << " (simlab lock)\n";
        }
    }
    requireStudentId(o.student);
    if (!o.student.empty() && !rubric.variants.perStudent) {
        std::cerr << "simlab: --student: this rubric gives every student the same scene ([variants] is off)\n";
    }
    GradeOptions options;
    options.student = o.student;
    options.includeHidden = o.all;
    options.onlyTests = o.tests;
    options.judges = o.jobs > 0 ? o.jobs : cores();
    // In a terminal, a line as each test starts: a long check is never silent (never in a pipe or a file, whose
    // reader wants the report alone).
    std::size_t started = 0, planned = 0;
    for (const RubricTest& test : rubric.tests) {
        const bool chosen = o.tests.empty() || std::find(o.tests.begin(), o.tests.end(), test.name) != o.tests.end();
        if (chosen && (o.all || test.visible())) ++planned;
    }
    if (::isatty(2)) {
        options.progress = [&started, planned](const std::string& what) {
            if (what == "building") return;
            std::cerr << "  [" << ++started << "/" << planned << "] " << printable(what) << "...\n";
        };
    }
    const Limits limits = limitsWith(rubric.limits, o.timeout, 0);
    options.limits = limits;
    for (const std::string& name : o.tests) {
        if (!rubric.find(name)) throw UsageError("no test named '" + name + "' in " + rubric.path);
    }
    const SubmissionFiles files = readSubmission(source, rubric, limits);
    const Builder builder(manifest);
    // Which scene the trade question is graded on, where it is the student's own or they asked (--student).
    const std::string scene =
        rubric.variants.perStudent || !o.student.empty() ? tradeSceneLine(assignment, rubric, o.student) : "";
    if (!scene.empty()) {
        (o.format == "text" ? std::cout : std::cerr) << printable(scene) << '\n' << std::flush;
    }
    if (o.format == "text") {
        std::cerr << "Building " << printable(source) << " against the " << assignment.id << " grader...\n";
    }
    // What each test cost in the last self-check of this lab (its seconds, the shared answers it used): the
    // judges' shares are made to end together.
    const std::string timesFile = builder.cacheDir() + "/test-costs-" + assignment.id + ".json";
    nlohmann::json times = nlohmann::json::object();
    if (std::ifstream in(timesFile); in) {
        times = nlohmann::json::parse(in, nullptr, false);
        if (!times.is_object()) times = nlohmann::json::object();
    }
    for (const auto& [name, cost] : times.items()) {
        if (std::optional<TestCost> expected = readTestCost(cost)) options.expected[name] = std::move(*expected);
    }
    const GradeReport report = gradeSubmission(builder, assignment, rubric, files, options);
    for (const TestResult& t : report.tests) {
        if (std::isfinite(t.seconds) && t.seconds > 0) times[t.name] = {{"seconds", t.seconds}, {"shared", t.shared}};
    }
    try {
        writeFileAtomically(timesFile, times.dump());
    } catch (const std::exception&) {
        // only a hint for the next check's shares
    }
    // Drawings a test made of the model land beside the student's file (replaced, never written through a link).
    const std::string folder = std::filesystem::absolute(source).parent_path().string();
    std::vector<std::string> written;
    for (const TestResult& t : report.tests) {
        for (const auto& [name, text] : t.attachments) {
            try {
                writeFileAtomically(folder + "/" + name, text);
                written.push_back(name);
            } catch (const std::exception& e) {
                std::cerr << "simlab: could not write " << printable(name) << ": " << printable(e.what()) << '\n';
            }
        }
    }
    if (o.format == "json") {
        std::cout << resultsJson(report);
    } else if (o.format == "classroom") {
        std::cout << classroomJson(report);
    } else {
        std::cout << renderText(report);
        if (const std::string cap = capLine(assignment, o.rubric.empty() ? assignment.rubric : o.rubric);
            !cap.empty()) {
            std::cout << cap << '\n';
        }
        if (!written.empty()) {
            std::cout << "Drawn from your model:";
            for (const std::string& name : written) std::cout << ' ' << printable(folder + "/" + name);
            std::cout << '\n';
        }
    }
}

}  // namespace

void addCheck(CLI::App& app) {
    auto options = std::make_shared<CheckOptions>();
    CLI::App* check = app.add_subcommand(
        "check", "Grade one file on the visible tests: builds it against the grader and runs each test in its own "
                 "process. Exits 0 whenever grading happened, whatever the score.");
    check->add_option("assignment", options->assignment, "which assignment (simlab list shows them)")->required();
    check->add_option("source", options->source, "your file (default: the starter in this tree)");
    check->add_option("--format", options->format,
                      "text; json: a Gradescope results.json on stdout; classroom: GitHub Classroom's two runner "
                      "results, points earned and points missed, one a line (what the template repository's workflow "
                      "reports)")
        ->check(CLI::IsMember({"text", "json", "classroom"}))
        ->capture_default_str();
    check->add_flag("--all", options->all, "run the hidden tests too (instructors)");
    check->add_option("--timeout", options->timeout,
                      "CPU seconds each test may use, its processes together, 0.1 to 3600 (default: the rubric's)")
        ->check(limitOption("cpu_seconds"));
    check->add_option("--test", options->tests, "run only the test of this name (repeatable)");
    check->add_option("--rubric", options->rubric, "another rubric file (default: the assignment's)")
        ->check(CLI::ExistingFile);
    check->add_option("--jobs", options->jobs,
                      "tests run at once, each still alone in its sandbox (default: the number of cores)")
        ->check(CLI::Range(1, 64));
    check->add_option("--student", options->student,
                      "your student id: where the course gives each student their own trade scene, the check grades "
                      "on yours and says which it is");
    check->callback([options] { runCheck(*options); });
}

}  // namespace simlab::cli
