// bench-grade-class: what grading a class costs, against the least it could cost.
//
// Runs rounds, alternating the two ways (A B A B ...) so that whatever else the machine does falls on both alike.
// Each round grades a fresh class of distinct apple submissions (from 8 corpus kinds, each file made distinct so
// nothing comes from the object cache):
//   simlab   `simlab grade --jobs J` from an empty cache: each file compiled against its contract in the sandbox,
//            checked, linked into a probe, and every test run as a sandboxed judge and probe
//   floor    the same files compiled with the same command and linked with the tests and the probe's handlers
//            into one program, run once, all tests in one process, no sandbox and nothing in between; J at a time
// It prints each round's seconds per submission, the medians, and the ratio of the medians. Cases that hang (the
// infinite loop) are left out: they cost their time limit, by design, in both.
//
//   build/bin/bench-grade-class [--rounds R] [--students N] [--jobs J]
#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "bench.h"
#include "simlab/common/files.h"
#include "simlab/build/manifest.h"
#include "simlab/isolation/process.h"

namespace fs = std::filesystem;
using namespace simlab::engine;
using namespace simlab::isolation;
using namespace simlab::bench;

namespace {

const std::vector<std::string> kMix = {"reference",         "gravity-up",      "wrong-height", "free-mobilizer",
                                       "euler-coarse-step", "typed-in-answer", "segfault",     "compile-error"};

// A class of `students` distinct files in `dir`, tagged so no two rounds share an object.
std::vector<std::string> makeClass(const Manifest& manifest, const std::string& dir, int students, const std::string& tag) {
    std::vector<std::string> ids;
    for (int i = 0; i < students; ++i) {
        const std::string kind = kMix[i % kMix.size()];
        const std::string id = "s" + std::to_string(100 + i) + "-" + kind;
        fs::create_directories(dir + "/" + id);
        const std::string text = readFile(manifest.sampleClass + "/apple/" + kind + "/NewtonsApple.cpp");
        writeFileAtomically(dir + "/" + id + "/NewtonsApple.cpp", text + "\n// " + tag + " " + id + "\n");
        ids.push_back(id);
    }
    return ids;
}

double gradeWithSimlab(const std::string& classDir, const std::string& work, int jobs) {
    fs::create_directories(work + "/cache");
    std::vector<std::string> environment = sandboxChoices();
    environment.push_back("SIMLAB_CACHE=" + work + "/cache");
    const auto start = Clock::now();
    const ProcessResult graded = run({SIMLAB_SIMLAB_PATH, "grade", "apple", classDir, "--out", work + "/grades",
                                      "--jobs", std::to_string(jobs)},
                                     work, environment);
    const double seconds = since(start);
    if (!graded.exitedCleanly()) throw std::runtime_error("simlab grade failed:\n" + graded.output);
    return seconds;
}

double gradeAtTheFloor(const Manifest& manifest, const Assignment& apple, const std::string& classDir,
                       const std::vector<std::string>& ids, const std::string& work, int jobs) {
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
        for (std::size_t i = next++; i < ids.size(); i = next++) {
            const std::string dir = work + "/" + ids[i];
            fs::create_directories(dir);
            std::vector<std::string> cc = apple.compile;
            cc.insert(cc.end(), {"-I" + apple.contractInclude, "-c", classDir + "/" + ids[i] + "/NewtonsApple.cpp",
                                 "-o", dir + "/student.o"});
            if (!run(cc, dir).exitedCleanly()) continue;
            std::vector<std::string> ld = manifest.link;
            ld.insert(ld.end(), {"-o", dir + "/floor"});
            ld.insert(ld.end(), apple.floorObjects.begin(), apple.floorObjects.end());
            ld.push_back(dir + "/student.o");
            ld.insert(ld.end(), manifest.floorLibraries.begin(), manifest.floorLibraries.end());
            run(ld, dir);
            run({dir + "/floor"}, dir, {"SIMLAB_RUBRIC=" + apple.rubric});
        }
    };
    const auto start = Clock::now();
    std::vector<std::thread> workers;
    for (int j = 0; j < jobs; ++j) workers.emplace_back(worker);
    for (std::thread& w : workers) w.join();
    return since(start);
}

}  // namespace

int main(int argc, char** argv) {
    int rounds = 6, students = 8, jobs = 2;
    CLI::App app{"What grading a class of apple submissions costs, against the floor, in alternating rounds.",
                 "bench-grade-class"};
    app.add_option("--rounds", rounds, "rounds; each grades a class with simlab and one at the floor")
        ->check(CLI::Range(1, 100));
    app.add_option("--students", students, "students per class")->check(CLI::Range(2, 1000));
    app.add_option("--jobs", jobs, "students graded at once")->check(CLI::Range(1, 64));
    CLI11_PARSE(app, argc, argv);

    try {
        const Manifest manifest = loadManifest();
        const Assignment& apple = manifest.find("apple");
        TempDir work("simlab-bench-");
        std::printf("Classes of %d apple submissions (%zu kinds, each file distinct), %d jobs, %d rounds of simlab and "
                    "the floor, alternating; sandbox: %s\n\n",
                    students, kMix.size(), jobs, rounds,
                    (sandboxSupport().summary + (testServers() ? "; each student's probes forked from one server" : ""))
                        .c_str());
        std::printf("%-6s %-8s %12s\n", "round", "what", "s/student");
        std::vector<double> simlab, floor;
        for (int r = 0; r < rounds; ++r) {
            // A B in even rounds, B A in odd ones: neither always goes first.
            for (int half = 0; half < 2; ++half) {
                const bool simlabTurn = (half == 0) == (r % 2 == 0);
                const std::string tag = "round" + std::to_string(r) + (simlabTurn ? "-simlab" : "-floor");
                const std::string dir = work.path() + "/" + tag;
                const std::vector<std::string> ids = makeClass(manifest, dir + "/class", students, tag);
                const double seconds = simlabTurn ? gradeWithSimlab(dir + "/class", dir, jobs)
                                                  : gradeAtTheFloor(manifest, apple, dir + "/class", ids, dir, jobs);
                (simlabTurn ? simlab : floor).push_back(seconds / students);
                std::printf("%-6d %-8s %12.3f\n", r + 1, simlabTurn ? "simlab" : "floor", seconds / students);
                std::fflush(stdout);
                fs::remove_all(dir);
            }
        }
        const double a = median(simlab), b = median(floor);
        std::printf("\nmedian s/student: simlab %.3f (target <= 0.5 at --jobs 2 on an idle 2-core machine), floor %.3f; "
                    "simlab / floor = %.2f\n", a, b, a / b);
        std::vector<double> ratios;
        for (std::size_t i = 0; i < simlab.size(); ++i) ratios.push_back(simlab[i] / floor[i]);
        std::printf("per-round ratios: median %.2f, min %.2f, max %.2f\n", median(ratios),
                    *std::min_element(ratios.begin(), ratios.end()), *std::max_element(ratios.begin(), ratios.end()));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench-grade-class: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
