// simlab grade: grade every submission of a class on every test.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.h"
#include "simlab/engine/errors.h"
#include "simlab/engine/grade.h"
#include "simlab/engine/manifest.h"
#include "simlab/engine/report.h"

namespace fs = std::filesystem;

namespace simlab::cli {

namespace {

struct GradeCommandOptions {
    std::string assignment;
    std::string submissions;
};

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
    const Rubric rubric = loadRubric(assignment.rubric);

    std::vector<fs::path> students;
    for (const fs::directory_entry& e : fs::directory_iterator(root)) {
        if (e.is_directory()) students.push_back(e.path());
    }
    std::sort(students.begin(), students.end());
    std::printf("Grading %zu submissions of %s (%s) in %s\n", students.size(), assignment.id.c_str(),
                assignment.title.c_str(), root.c_str());

    const Builder builder(manifest);
    GradeOptions options;
    options.includeHidden = true;
    for (const fs::path& student : students) {
        const fs::path file = student / rubric.submission;
        std::string line;
        if (!fs::exists(file)) {
            line = "0/" + points(rubric.totalPoints()) + "  missing " + rubric.submission;
        } else {
            const GradeReport report = gradeSource(builder, assignment, rubric, file.string(), options);
            line = points(report.score()) + "/" + points(report.maxScore());
            if (!report.build.ok) line += "  " + std::string(report.build.stage == "link" ? "did not link" : "did not compile");
        }
        std::printf("  %-24s %s\n", student.filename().c_str(), line.c_str());
        std::fflush(stdout);
    }
}

}  // namespace

void addGrade(CLI::App& app) {
    auto options = std::make_shared<GradeCommandOptions>();
    CLI::App* grade = app.add_subcommand("grade", "Grade a class: one folder per student, each with their file.");
    grade->add_option("assignment", options->assignment, "which assignment")->required();
    grade->add_option("submissions", options->submissions,
                      "folder of student folders (default: the bundled sample class)");
    grade->callback([options] { runGrade(*options); });
}

}  // namespace simlab::cli
