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
//     file = "BookAnswers.toml"                # optional: edit one of the rubric's extra files instead
//     [outcomes]                               # every test not listed must pass
//     "y at the final time has the target accuracy digits" = "failed"
//
//   simlab-corpus materialize <assignment> <case.toml>... --out DIR   write DIR/<case>/<submission file>
//   simlab-corpus check <assignment> <case.toml>                      grade it and compare; exit 1 on a mismatch
//   simlab-corpus class <assignment> <case.toml>... --simlab PATH     grade them all as one class with
//       `simlab grade`, while listening on 127.0.0.1:47810, and compare every student; also check that each
//       student has one gradebook row, that nobody connected to the listener, and that no student's report
//       holds another student's file
#include <CLI/CLI.hpp>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>
#include <iostream>
#include <map>
#include <toml++/toml.h>

#include "simlab/engine/errors.h"
#include "simlab/engine/files.h"
#include "simlab/engine/grade.h"
#include "simlab/engine/manifest.h"
#include "simlab/engine/process.h"
#include "simlab/engine/report.h"

namespace fs = std::filesystem;
using namespace simlab::engine;

namespace {

struct Case {
    std::string name;
    std::string description;
    std::map<std::string, std::string> files;  // what the student hands in: the submission and its extra files
    double score = 0;
    std::vector<std::string> reportContains;
    std::map<std::string, std::string> outcomes;
};

[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw std::runtime_error(path + ": " + what);
}

Case loadCase(const Assignment& assignment, const simlab::Rubric& rubric, const std::string& path) {
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
    c.files[assignment.source] = readFile(basePath);
    for (const std::string& extra : rubric.extraFiles) {
        const fs::path file = fs::path(basePath).parent_path() / extra;
        if (fs::exists(file)) c.files[extra] = readFile(file.string());
    }
    const auto score = t["score"].value<double>();
    if (!score) fail(path, "score is missing");
    c.score = *score;
    if (const toml::array* edits = t["edit"].as_array()) {
        for (const toml::node& node : *edits) {
            const toml::table* edit = node.as_table();
            const auto find = edit ? (*edit)["find"].value<std::string>() : std::nullopt;
            const auto replace = edit ? (*edit)["replace"].value<std::string>() : std::nullopt;
            if (!find || !replace) fail(path, "each [[edit]] needs find and replace");
            const std::string file = (*edit)["file"].value_or(assignment.source);
            if (!c.files.count(file)) fail(path, "the " + base + " has no " + file + " to edit");
            std::string& text = c.files[file];
            const std::size_t at = text.find(*find);
            if (at == std::string::npos || text.find(*find, at + 1) != std::string::npos) {
                fail(path, "edit must match exactly once in the " + base + "'s " + file + ", and does not: " + *find);
            }
            text.replace(at, find->size(), *replace);
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

// Write a case's files into `dir`; a file is rewritten only when it changed, so it keeps its time stamp.
void writeCase(const Case& c, const fs::path& dir) {
    fs::create_directories(dir);
    for (const auto& [name, text] : c.files) {
        const fs::path file = dir / name;
        if (!fs::exists(file) || readFile(file.string()) != text) writeFileAtomically(file.string(), text);
    }
}

int materialize(const Assignment& assignment, const simlab::Rubric& rubric, const std::vector<std::string>& cases,
                const std::string& out) {
    for (const std::string& path : cases) {
        const Case c = loadCase(assignment, rubric, path);
        writeCase(c, fs::path(out) / c.name);
    }
    return 0;
}

// What differs between a case's expectations and a grade: outcomes, the score, texts the report must show.
std::vector<std::string> compare(const Case& c, const std::vector<TestResult>& tests, double score,
                                 const std::string& text) {
    std::vector<std::string> mismatches;
    for (const TestResult& t : tests) {
        const auto listed = c.outcomes.find(t.name);
        const std::string expected = listed == c.outcomes.end() ? "passed" : listed->second;
        if (outcomeName(t.outcome) != expected) {
            mismatches.push_back("'" + t.name + "' " + outcomeName(t.outcome) + ", expected " + expected);
        }
    }
    if (std::abs(score - c.score) > 0.005) {
        mismatches.push_back("score " + points(score) + ", expected " + points(c.score));
    }
    for (const std::string& needle : c.reportContains) {
        if (text.find(needle) == std::string::npos) mismatches.push_back("the report does not say '" + needle + "'");
    }
    return mismatches;
}

int check(const Manifest& manifest, const Assignment& assignment, const simlab::Rubric& rubric,
          const std::string& path) {
    const Case c = loadCase(assignment, rubric, path);
    for (const auto& [test, outcome] : c.outcomes) {
        if (!rubric.find(test)) fail(path, "no test named '" + test + "' in " + assignment.rubric);
    }
    TempDir dir("simlab-corpus-");
    writeCase(c, dir.path());
    const std::string file = dir.path() + "/" + assignment.source;
    GradeOptions options;
    options.includeHidden = true;
    const GradeReport report = gradeSource(Builder(manifest), assignment, rubric, file, options);
    const std::string text = renderText(report);
    std::cout << c.name << ": " << c.description << "\n" << text;

    const std::vector<std::string> mismatches = compare(c, report.tests, report.score(), text);
    for (const std::string& m : mismatches) std::cout << "MISMATCH: " << m << "\n";
    std::cout << (mismatches.empty() ? "OK: as expected\n" : "FAILED\n");
    return mismatches.empty() ? 0 : 1;
}

// Counts connections to 127.0.0.1:port while it lives.
class Listener {
public:
    explicit Listener(int port) {
        fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
        const int yes = 1;
        ::setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
        sockaddr_in address{};
        address.sin_family = AF_INET;
        address.sin_port = htons(static_cast<uint16_t>(port));
        address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        if (::bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 || ::listen(fd_, 16) != 0) {
            throw std::runtime_error("cannot listen on 127.0.0.1:" + std::to_string(port));
        }
        thread_ = std::thread([this] {
            while (!stop_) {
                pollfd p{fd_, POLLIN, 0};
                if (::poll(&p, 1, 100) > 0) {
                    const int client = ::accept(fd_, nullptr, nullptr);
                    if (client >= 0) {
                        ++connections_;
                        ::close(client);
                    }
                }
            }
        });
    }
    ~Listener() {
        stop_ = true;
        thread_.join();
        ::close(fd_);
    }
    int connections() const { return connections_; }

private:
    int fd_ = -1;
    std::atomic<bool> stop_{false};
    std::atomic<int> connections_{0};
    std::thread thread_;
};

std::string marker(const std::string& student) { return "corpus student " + student + " wrote this file"; }

int gradeAsClass(const Assignment& assignment, const simlab::Rubric& rubric, const std::vector<std::string>& paths,
                 const std::string& simlab, int jobs) {
    std::vector<Case> cases;
    for (const std::string& path : paths) cases.push_back(loadCase(assignment, rubric, path));
    TempDir dir("simlab-class-");
    const std::string submissions = dir.path() + "/submissions", out = dir.path() + "/grades";
    for (const Case& c : cases) {
        Case marked = c;
        marked.files[assignment.source] += "\n// " + marker(c.name) + "\n";
        writeCase(marked, submissions + "/" + c.name);
    }

    Listener listener(47810);
    ProcessRequest request;
    request.argv = {simlab, "grade", assignment.id, submissions, "--out", out, "--jobs", std::to_string(jobs)};
    request.env = childEnvironment();
    request.workDir = dir.path();
    request.limits.wallSeconds = request.limits.cpuSeconds = 1800;
    request.limits.memoryMiB = 1 << 20;
    request.limits.processes = 4096;
    request.limits.fileMiB = 4096;
    request.limits.outputKiB = 16 * 1024;
    request.keepOutput = 1 << 20;
    const ProcessResult batch = runProcess(request);
    std::cout << batch.output;

    std::vector<std::string> problems;
    if (!batch.exitedCleanly()) problems.push_back("simlab grade did not complete (status " + std::to_string(batch.exitCode) + ")");
    if (listener.connections() > 0) {
        problems.push_back(std::to_string(listener.connections()) + " connection(s) reached 127.0.0.1:47810");
    }
    // One gradebook row per student, none twice.
    std::ifstream gradebook(out + "/gradebook.csv");
    std::string row;
    std::getline(gradebook, row);
    std::multiset<std::string> rows;
    while (std::getline(gradebook, row)) rows.insert(row.substr(0, row.find(',')));
    for (const Case& c : cases) {
        if (rows.count(c.name) != 1) {
            problems.push_back(c.name + ": " + std::to_string(rows.count(c.name)) + " gradebook rows");
        }
    }
    if (rows.size() != cases.size()) problems.push_back("the gradebook has " + std::to_string(rows.size()) + " rows");

    for (const Case& c : cases) {
        const std::string student = out + "/students/" + c.name;
        if (!fs::exists(student + "/results.json")) {
            problems.push_back(c.name + ": no results.json");
            continue;
        }
        const std::string results = readFile(student + "/results.json");
        const std::string feedback = readFile(student + "/feedback.md");
        const nlohmann::json json = nlohmann::json::parse(results);
        std::vector<TestResult> tests;
        for (const nlohmann::json& t : json.at("tests")) {
            TestResult r;
            r.name = t.at("name");
            r.outcome = outcomeNamed(t.at("extra_data").at("outcome"));
            tests.push_back(r);
        }
        std::vector<std::string> mismatches = compare(c, tests, json.at("score"), results + feedback);
        for (const Case& other : cases) {
            if (other.name != c.name && (results + feedback).find(marker(other.name)) != std::string::npos) {
                mismatches.push_back("its report holds " + other.name + "'s file");
            }
        }
        std::cout << (mismatches.empty() ? "OK       " : "MISMATCH ") << c.name << ": " << points(json.at("score"))
                  << " (expected " << points(c.score) << ")\n";
        for (const std::string& m : mismatches) problems.push_back(c.name + ": " + m);
    }
    for (const std::string& p : problems) std::cout << "MISMATCH: " << p << "\n";
    std::cout << (problems.empty() ? "OK: every student as expected\n" : "FAILED\n");
    return problems.empty() ? 0 : 1;
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
    std::string simlab;
    int jobs = 2;
    CLI::App* classCommand = app.add_subcommand("class", "Grade the cases as one class with simlab grade and compare.");
    classCommand->add_option("assignment", assignmentId)->required();
    classCommand->add_option("cases", cases)->required()->check(CLI::ExistingFile);
    classCommand->add_option("--simlab", simlab)->required()->check(CLI::ExistingFile);
    classCommand->add_option("--jobs", jobs);
    CLI11_PARSE(app, argc, argv);
    try {
        const Manifest manifest = loadManifest();
        const Assignment& assignment = manifest.find(assignmentId);
        const simlab::Rubric rubric = simlab::loadRubric(assignment.rubric);
        if (materializeCommand->parsed()) return materialize(assignment, rubric, cases, out);
        if (classCommand->parsed()) return gradeAsClass(assignment, rubric, cases, simlab, jobs);
        return check(manifest, assignment, rubric, cases.front());
    } catch (const std::exception& e) {
        std::cerr << "simlab-corpus: error: " << e.what() << '\n';
        return 2;
    }
}
