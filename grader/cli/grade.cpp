// simlab grade: grade every submission of a class on every test, in parallel, resumably.
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <thread>

#include "commands.h"
#include "simlab/cli_checks.h"
#include "simlab/engine/batch.h"
#include "simlab/engine/errors.h"
#include "simlab/engine/files.h"
#include "simlab/engine/manifest.h"
#include "simlab/engine/process.h"
#include "simlab/engine/report.h"

namespace fs = std::filesystem;

namespace simlab::cli {

namespace {

struct GradeCommandOptions {
    std::string assignment;
    std::string submissions;
    std::string out;
    int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    std::vector<std::string> only;
    std::string junit;
    double timeout = 0;
    double memory = 0;
    std::string rubric;
};

std::string minutesAndSeconds(double seconds) {
    char text[32];
    const int s = static_cast<int>(seconds + 0.5);
    if (s >= 60) std::snprintf(text, sizeof text, "%dm%02ds", s / 60, s % 60);
    else std::snprintf(text, sizeof text, "%ds", s);
    return text;
}

std::string studentLine(const engine::StudentRecord& r, bool reused) {
    char text[512];
    std::string status = r.status + (r.note.empty() ? "" : ": " + r.note);
    if (reused) status += " (unchanged)";
    std::snprintf(text, sizeof text, "  %-24s %7s  %s", r.id.c_str(),
                  (engine::points(r.score) + "/" + engine::points(r.maxScore)).c_str(), status.c_str());
    return text;
}

void onSignal(int) { engine::interruptChildren(); }

void runGrade(const GradeCommandOptions& o) {
    using namespace simlab::engine;
    const Manifest manifest = loadManifest();
    const Assignment& assignment = manifest.find(o.assignment);
    if (!assignment.hiddenTestsBuilt) {
        throw UsageError("grading needs the hidden tests, which this copy of simlab does not have");
    }
    const std::string root = o.submissions.empty() ? manifest.sampleClass + "/" + assignment.id : o.submissions;
    if (!fs::is_directory(root)) {
        throw UsageError(o.submissions.empty() ? "this copy of simlab has no sample class for " + assignment.id +
                                                     "; name a folder of submissions"
                                               : "no submissions folder " + root);
    }
    const std::string out = o.out.empty() ? "grades/" + assignment.id : o.out;
    const Rubric rubric = loadRubric(o.rubric.empty() ? assignment.rubric : o.rubric);

    ClassOptions options;
    options.jobs = o.jobs;
    options.only = o.only;
    options.grade.includeHidden = true;
    if (o.timeout > 0 || o.memory > 0) {
        Limits limits = rubric.limits;
        if (o.timeout > 0) limits.wallSeconds = limits.cpuSeconds = o.timeout;
        if (o.memory > 0) limits.memoryMiB = static_cast<long>(o.memory);
        options.grade.limits = limits;
    }

    const SandboxSupport& sandbox = sandboxSupport();
    if (!sandbox.warning.empty()) std::cerr << "simlab: warning: " << sandbox.warning << "\n";
    std::printf("Grading %s (%s) from %s into %s: %d jobs, sandbox: %s\n", assignment.id.c_str(),
                assignment.title.c_str(), root.c_str(), out.c_str(), o.jobs, sandbox.summary.c_str());
    std::fflush(stdout);

    // On a terminal, a live status line under the log; otherwise the log alone.
    const bool live = ::isatty(STDERR_FILENO) && ::isatty(STDOUT_FILENO);
    auto onProgress = [&](const ClassProgress& p) {
        if (live) std::fprintf(stderr, "\r\x1b[K");
        std::printf("%s\n", studentLine(*p.last, p.lastReused).c_str());
        std::fflush(stdout);
        if (live) {
            std::fprintf(stderr, "  [%d/%d] %s elapsed%s", p.done, p.total, minutesAndSeconds(p.elapsed).c_str(),
                         p.eta >= 0 && p.done < p.total ? (", about " + minutesAndSeconds(p.eta) + " left").c_str() : "");
            std::fflush(stderr);
        }
    };

    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
    const Builder builder(manifest);
    std::vector<StudentRecord> records;
    try {
        records = gradeClass(builder, assignment, rubric, root, out, options, onProgress);
    } catch (const Interrupted&) {
        if (live) std::fprintf(stderr, "\r\x1b[K");
        std::cerr << "simlab: interrupted; what finished is in " << out
                  << "/gradebook.csv. Run the same command again to grade the rest.\n";
        std::exit(130);
    }
    if (live) std::fprintf(stderr, "\r\x1b[K");

    std::cout << "\n" << summaryTable(rubric, records);
    if (!o.junit.empty()) writeFileAtomically(o.junit, junitXml(assignment, records));
    std::cout << "\nWrote " << out << "/gradebook.csv, " << out << "/summary.csv and " << out
              << "/students/<id>/{results.json,feedback.md}" << (o.junit.empty() ? "" : ", " + o.junit) << "\n";
}

}  // namespace

void addGrade(CLI::App& app) {
    auto options = std::make_shared<GradeCommandOptions>();
    CLI::App* grade = app.add_subcommand(
        "grade", "Grade a class on every test: one folder per student (its name is the student id) holding their "
                 "file. Each student's results are written as they finish; run the command again after an "
                 "interruption and only what is unfinished or changed is graded again.");
    grade->add_option("assignment", options->assignment, "which assignment")->required();
    grade->add_option("submissions", options->submissions,
                      "folder of student folders (default: the bundled sample class)");
    grade->add_option("--out,-o", options->out, "where the gradebook and reports go (default: grades/<assignment>)");
    grade->add_option("--jobs,-j", options->jobs, "students graded at once (default: the number of cores)")
        ->check(CLI::Range(1, 64));
    grade->add_option("--only", options->only, "regrade only this student (repeatable); other rows are kept");
    grade->add_option("--junit", options->junit, "also write JUnit XML to this file");
    grade->add_option("--timeout", options->timeout, "seconds each test may run (default: the rubric's)")
        ->check(simlab::positive());
    grade->add_option("--memory", options->memory, "MiB each test may use (default: the rubric's)")
        ->check(simlab::positive());
    grade->add_option("--rubric", options->rubric, "another rubric file (default: the assignment's)")
        ->check(CLI::ExistingFile);
    grade->callback([options] { runGrade(*options); });
}

}  // namespace simlab::cli
