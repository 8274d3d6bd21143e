// bench-self-check: how long a student waits for `simlab check` after an edit, against the least it could take.
//
// For each lab it runs rounds, alternating the two ways (A B A B ..., B first in odd rounds) so that whatever else
// the machine does falls on both alike. Before every run the file gets a new comment line, as a student's edit
// would, so nothing comes from the object cache:
//   check   `simlab check LAB FILE` as a student runs it: the file compiled against its contract in the sandbox,
//           checked, linked into a probe, and every visible test run as sandboxed judges and probes
//   floor   the fastest compile + link + run this machine allows: the same file compiled with the same command,
//           linked with the visible tests and the probe's handlers into one program, run once, every visible test
//           in one process, no sandbox and nothing in between
// With --against SIMLAB the second way is that other simlab's check instead of the floor (two builds compared).
// It prints each run's seconds, then per lab the medians, their ratio and the target, and the machine's load.
// The files: the reference solutions of apple, projectile and book, and for biosim a project of a student's own
// (the corpus's honest-shank: the worked boot's answer alone runs for seconds).
//
//   build/bin/bench-self-check [--rounds R] [--lab LAB]... [--simlab SIMLAB] [--against SIMLAB]
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <thread>
#include <toml++/toml.h>

#include "bench.h"
#include "simlab/common/files.h"
#include "simlab/build/manifest.h"
#include "simlab/isolation/process.h"

namespace fs = std::filesystem;
using namespace simlab::engine;
using namespace simlab::isolation;
using namespace simlab::bench;

namespace {

// The targets of a self-check after an edit, on an idle 2-core machine (seconds).
const std::map<std::string, double> kTargets = {{"apple", 1.0}, {"projectile", 1.2}, {"book", 1.5}, {"biosim", 2.5}};

// The files of one lab's submission, written into `dir`: the source first.
std::vector<std::string> writeSubmission(const Manifest& manifest, const Assignment& a, const std::string& dir) {
    fs::create_directories(dir);
    if (a.id == "biosim") {
        const std::string corpus = manifest.sourceDir + "/tests/corpus/biosim/honest-shank.toml";
        const toml::table t = toml::parse_file(corpus);
        std::vector<std::string> names;
        for (const toml::node& node : *t["file"].as_array()) {
            const toml::table& file = *node.as_table();
            const std::string name = file["name"].value_or(std::string());
            writeFileAtomically(dir + "/" + name, file["text"].value_or(std::string()));
            names.push_back(name);
        }
        std::stable_partition(names.begin(), names.end(), [&](const std::string& n) { return n == a.source; });
        return names;
    }
    if (a.solution.empty()) throw std::runtime_error("no reference solution for " + a.id + " in this tree");
    std::vector<std::string> names = {a.source};
    for (const auto& entry : fs::directory_iterator(fs::path(a.solution).parent_path())) {
        const std::string name = entry.path().filename().string();
        writeFileAtomically(dir + "/" + name, readFile(entry.path().string()));
        if (name != a.source) names.push_back(name);
    }
    return names;
}

// One line added to the end of the file, as an edit would: the next compile cannot come from a cache.
void edit(const std::string& file, const std::string& tag) {
    std::ofstream(file, std::ios::app) << "// " << tag << "\n";
}

double check(const std::string& simlab, const std::string& dir, const std::string& lab, const std::string& source) {
    const auto start = Clock::now();
    const ProcessResult r = run({simlab, "check", lab, source}, dir, sandboxChoices());
    const double seconds = since(start);
    if (!r.exitedCleanly()) throw std::runtime_error("simlab check " + lab + " failed:\n" + r.output);
    return seconds;
}

double floorRun(const Manifest& manifest, const Assignment& a, const std::string& dir, const std::string& source) {
    const auto start = Clock::now();
    std::vector<std::string> cc = a.compile;
    cc.insert(cc.end(), {"-I" + a.contractInclude, "-c", source, "-o", dir + "/student.o"});
    const ProcessResult compiled = run(cc, dir);
    if (!compiled.exitedCleanly()) throw std::runtime_error("the floor's compile failed:\n" + compiled.output);
    std::vector<std::string> ld = manifest.link;
    ld.insert(ld.end(), {"-o", dir + "/floor"});
    ld.insert(ld.end(), a.floorObjects.begin(), a.floorObjects.end());
    ld.push_back(dir + "/student.o");
    ld.insert(ld.end(), manifest.floorLibraries.begin(), manifest.floorLibraries.end());
    const ProcessResult linked = run(ld, dir);
    if (!linked.exitedCleanly()) throw std::runtime_error("the floor's link failed:\n" + linked.output);
    // The visible tests only, as simlab check runs them: hidden ones are tagged [hidden] in the judge.
    run({dir + "/floor", "~[hidden]"}, dir, {"SIMLAB_RUBRIC=" + a.rubric, "SIMLAB_SUBMISSION_DIR=" + dir});
    return since(start);
}

std::string loadAverage() {
    std::ifstream file("/proc/loadavg");
    std::string one;
    file >> one;
    return one;
}

}  // namespace

int main(int argc, char** argv) {
    int rounds = 5;
    std::vector<std::string> labs = {"apple", "projectile", "book", "biosim"};
    CLI::App app{"How long simlab check takes after an edit, against the floor, in alternating rounds.",
                 "bench-self-check"};
    app.add_option("--rounds", rounds, "rounds per lab; each runs simlab check once and the floor once")
        ->check(CLI::Range(1, 100))
        ->capture_default_str();
    app.add_option("--lab", labs, "labs to measure (default: all four)")
        ->check(CLI::IsMember({"apple", "projectile", "book", "biosim"}));
    app.add_option("--simlab", simlabPath(), "the simlab to measure")->capture_default_str();
    std::string against;
    app.add_option("--against", against, "another simlab whose check is measured instead of the floor");
    CLI11_PARSE(app, argc, argv);
    const std::string other = against.empty() ? "floor" : "against";

    try {
        const Manifest manifest = loadManifest();
        TempDir work("simlab-bench-check-");
        // This run's own mark in every edit: no file a check compiles was ever compiled before, by an earlier run
        // of the benchmark either (the object cache would answer it without the compiler).
        const std::string run = std::to_string(std::random_device{}()) + std::to_string(std::random_device{}());
        std::printf(
            "simlab check after a one-line edit against %s, %d rounds per lab, alternating; "
            "%u cores, load %s; sandbox: %s\n",
            against.empty() ? "the floor" : against.c_str(), rounds, std::thread::hardware_concurrency(),
            loadAverage().c_str(), sandboxSupport().summary.c_str());
        std::printf("compiler: %s\n\n", manifest.compile.front().c_str());
        std::printf("%-11s %-6s %8s %8s\n", "lab", "round", "check s", (other + " s").c_str());
        struct Row {
            std::string lab;
            double check, floor;
        };
        std::vector<Row> rows;
        for (const std::string& lab : labs) {
            const Assignment& a = manifest.find(lab);
            const std::string dir = work.path() + "/" + lab;
            const std::vector<std::string> files = writeSubmission(manifest, a, dir);
            const std::string source = dir + "/" + files.front();
            // Once to warm the caches a student's machine has warm (not the object's).
            check(simlabPath(), dir, lab, source);
            if (!against.empty()) check(against, dir, lab, source);
            std::vector<double> checks, floors;
            for (int r = 0; r < rounds; ++r) {
                double c = 0, f = 0;
                for (int half = 0; half < 2; ++half) {
                    const bool checkTurn = (half == 0) == (r % 2 == 0);
                    edit(source, lab + " round " + std::to_string(r) + (checkTurn ? " check " : " floor ") + run);
                    if (checkTurn) {
                        c = check(simlabPath(), dir, lab, source);
                    } else {
                        f = against.empty() ? floorRun(manifest, a, dir, source) : check(against, dir, lab, source);
                    }
                }
                checks.push_back(c);
                floors.push_back(f);
                std::printf("%-11s %-6d %8.2f %8.2f\n", lab.c_str(), r + 1, c, f);
                std::fflush(stdout);
            }
            rows.push_back({lab, median(checks), median(floors)});
        }
        std::printf("\n%-11s %10s %10s %8s %8s\n", "lab", "check (s)", (other + " (s)").c_str(), "ratio", "target");
        for (const Row& row : rows) {
            std::printf("%-11s %10.2f %10.2f %8.2f %8.1f\n", row.lab.c_str(), row.check, row.floor,
                        row.check / row.floor, kTargets.at(row.lab));
        }
        std::printf("(medians; load now %s)\n", loadAverage().c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench-self-check: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
