// simlab-corpus: the corpus of sample submissions, each with the score the grader must give it.
//
// A case is a TOML file, tests/corpus/<assignment>/<case>.toml: a base file (the reference solution or the
// starter) plus exact edits, so the bug a case carries is the few lines it changes:
//
//     description = "Gravity points up."
//     base = "solution"                        # or "starter"
//     score = 35                               # total the grader must give, hidden tests included
//     report_contains = ["..."]                # optional: text the report must show
//     [[edit]]                                 # `find` must occur exactly once in the base
//     find = "Vec3(0, -scene.gravity, 0)"
//     replace = "Vec3(0, scene.gravity, 0)"
//     [outcomes]                               # every test not listed must pass
//     "y at the final time has the target accuracy digits" = "failed"
//
//   simlab-corpus materialize <assignment> <case.toml>... --out DIR   write DIR/<case>/<submission file>
//   simlab-corpus check <assignment> <case.toml>                      grade it and compare; exit 1 on a mismatch
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <map>
#include <toml++/toml.h>

#include "simlab/engine/errors.h"
#include "simlab/engine/files.h"
#include "simlab/engine/grade.h"
#include "simlab/engine/manifest.h"
#include "simlab/engine/report.h"

namespace fs = std::filesystem;
using namespace simlab::engine;

namespace {

struct Case {
    std::string name;
    std::string description;
    std::string source;  // the submission's text
    double score = 0;
    std::vector<std::string> reportContains;
    std::map<std::string, std::string> outcomes;
};

[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw std::runtime_error(path + ": " + what);
}

Case loadCase(const Assignment& assignment, const std::string& path) {
    toml::table t;
    try {
        t = toml::parse_file(path);
    } catch (const toml::parse_error& e) {
        fail(path, std::string(e.description()));
    }
    Case c;
    c.name = fs::path(path).stem().string();
    c.description = t["description"].value_or(std::string());
    const std::string base = t["base"].value_or(std::string());
    if (base != "solution" && base != "starter") fail(path, "base must be \"solution\" or \"starter\"");
    const std::string basePath = base == "solution" ? assignment.solution : assignment.starter;
    if (basePath.empty()) fail(path, "this tree has no solution for " + assignment.id);
    c.source = readFile(basePath);
    const auto score = t["score"].value<double>();
    if (!score) fail(path, "score is missing");
    c.score = *score;
    if (const toml::array* edits = t["edit"].as_array()) {
        for (const toml::node& node : *edits) {
            const toml::table* edit = node.as_table();
            const auto find = edit ? (*edit)["find"].value<std::string>() : std::nullopt;
            const auto replace = edit ? (*edit)["replace"].value<std::string>() : std::nullopt;
            if (!find || !replace) fail(path, "each [[edit]] needs find and replace");
            const std::size_t at = c.source.find(*find);
            if (at == std::string::npos || c.source.find(*find, at + 1) != std::string::npos) {
                fail(path, "edit must match exactly once in the " + base + ", and does not: " + *find);
            }
            c.source.replace(at, find->size(), *replace);
        }
    }
    if (const toml::array* texts = t["report_contains"].as_array()) {
        for (const toml::node& node : *texts) c.reportContains.push_back(node.value_or(std::string()));
    }
    if (const toml::table* outcomes = t["outcomes"].as_table()) {
        for (auto&& [test, outcome] : *outcomes) c.outcomes[std::string(test.str())] = outcome.value_or(std::string());
    }
    return c;
}

std::string submissionName(const Assignment& assignment) { return assignment.source; }

int materialize(const Assignment& assignment, const std::vector<std::string>& cases, const std::string& out) {
    for (const std::string& path : cases) {
        const Case c = loadCase(assignment, path);
        const fs::path dir = fs::path(out) / c.name;
        fs::create_directories(dir);
        const fs::path file = dir / submissionName(assignment);
        // Rewrite only on change, so the file keeps its time stamp and nothing downstream rebuilds for nothing.
        if (!fs::exists(file) || readFile(file.string()) != c.source) writeFileAtomically(file.string(), c.source);
    }
    return 0;
}

int check(const Manifest& manifest, const Assignment& assignment, const std::string& path) {
    const Case c = loadCase(assignment, path);
    const simlab::Rubric rubric = simlab::loadRubric(assignment.rubric);
    for (const auto& [test, outcome] : c.outcomes) {
        if (!rubric.find(test)) fail(path, "no test named '" + test + "' in " + assignment.rubric);
    }
    TempDir dir("simlab-corpus-");
    const std::string file = dir.path() + "/" + submissionName(assignment);
    writeFileAtomically(file, c.source);
    GradeOptions options;
    options.includeHidden = true;
    const GradeReport report = gradeSource(Builder(manifest), assignment, rubric, file, options);
    const std::string text = renderText(report);
    std::cout << c.name << ": " << c.description << "\n" << text;

    std::vector<std::string> mismatches;
    for (const TestResult& t : report.tests) {
        const auto listed = c.outcomes.find(t.name);
        const std::string expected = listed == c.outcomes.end() ? "passed" : listed->second;
        if (outcomeName(t.outcome) != expected) {
            mismatches.push_back("'" + t.name + "' " + outcomeName(t.outcome) + ", expected " + expected);
        }
    }
    if (std::abs(report.score() - c.score) > 0.005) {
        mismatches.push_back("score " + points(report.score()) + ", expected " + points(c.score));
    }
    for (const std::string& needle : c.reportContains) {
        if (text.find(needle) == std::string::npos) mismatches.push_back("the report does not say '" + needle + "'");
    }
    for (const std::string& m : mismatches) std::cout << "MISMATCH: " << m << "\n";
    std::cout << (mismatches.empty() ? "OK: as expected\n" : "FAILED\n");
    return mismatches.empty() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"The corpus of sample submissions with their expected scores.", "simlab-corpus"};
    app.require_subcommand(1);
    std::string assignmentId, out;
    std::vector<std::string> cases;
    CLI::App* materializeCommand = app.add_subcommand("materialize", "Write each case's submission file.");
    materializeCommand->add_option("assignment", assignmentId)->required();
    materializeCommand->add_option("cases", cases)->required()->check(CLI::ExistingFile);
    materializeCommand->add_option("--out", out)->required();
    CLI::App* checkCommand = app.add_subcommand("check", "Grade one case and compare with its expectations.");
    checkCommand->add_option("assignment", assignmentId)->required();
    checkCommand->add_option("case", cases)->required()->expected(1)->check(CLI::ExistingFile);
    CLI11_PARSE(app, argc, argv);
    try {
        const Manifest manifest = loadManifest();
        const Assignment& assignment = manifest.find(assignmentId);
        if (materializeCommand->parsed()) return materialize(assignment, cases, out);
        return check(manifest, assignment, cases.front());
    } catch (const std::exception& e) {
        std::cerr << "simlab-corpus: error: " << e.what() << '\n';
        return 2;
    }
}
