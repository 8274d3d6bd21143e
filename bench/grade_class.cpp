// bench-grade-class: what grading a class costs, against the least it could cost.
//
// Makes a class of N students (default 40) from the sample class, each file made distinct so nothing is reused
// from the object cache, and measures, in one run:
//   simlab     `simlab grade --jobs J` on the class, from an empty cache: sandboxed, one process per test
//   floor      the same files compiled with the same command, linked the same way, and each grader run once,
//              all tests in one process, no sandbox and no harness between tests; J at a time
//   cmake      a CMake project per submission (configure + build, no precompiled header), for a few students
// and prints seconds per submission and the ratios. Cases that hang (the infinite loop) are left out: they cost
// their time limit, by design, in both.
//
//   build/bin/bench-grade-class [--students N] [--jobs J] [--cmake-samples K]
#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include "simlab/engine/files.h"
#include "simlab/engine/manifest.h"
#include "simlab/engine/process.h"

namespace fs = std::filesystem;
using namespace simlab::engine;
using Clock = std::chrono::steady_clock;

namespace {

double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

ProcessResult run(const std::vector<std::string>& argv, const std::string& dir, const std::vector<std::string>& env = {}) {
    ProcessRequest r;
    r.argv = argv;
    r.env = childEnvironment(env);
    r.workDir = dir;
    r.limits.wallSeconds = r.limits.cpuSeconds = 3600;
    r.limits.memoryMiB = 1 << 20;
    r.limits.processes = 4096;
    r.limits.fileMiB = 1 << 16;
    r.limits.outputKiB = 1 << 20;
    return runProcess(r);
}

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

}  // namespace

int main(int argc, char** argv) {
    int students = 40, jobs = 2, cmakeSamples = 4;
    CLI::App app{"What grading a class of apple submissions costs, against the floor.", "bench-grade-class"};
    app.add_option("--students", students, "class size")->check(CLI::Range(2, 1000));
    app.add_option("--jobs", jobs, "students graded at once")->check(CLI::Range(1, 64));
    app.add_option("--cmake-samples", cmakeSamples, "students built with a CMake project each")->check(CLI::Range(0, 40));
    CLI11_PARSE(app, argc, argv);

    const Manifest manifest = loadManifest();
    const Assignment& apple = manifest.find("apple");
    const std::vector<std::string> mix = {"reference",       "gravity-up",      "wrong-height", "free-mobilizer",
                                          "euler-coarse-step", "typed-in-answer", "segfault",     "compile-error"};
    TempDir work("simlab-bench-");
    const std::string classDir = work.path() + "/class";
    for (int i = 0; i < students; ++i) {
        const std::string id = "s" + std::to_string(100 + i) + "-" + mix[i % mix.size()];
        fs::create_directories(classDir + "/" + id);
        const std::string text = readFile(manifest.sampleClass + "/apple/" + mix[i % mix.size()] + "/NewtonsApple.cpp");
        writeFileAtomically(classDir + "/" + id + "/NewtonsApple.cpp", text + "\n// " + id + "\n");
    }
    std::vector<std::string> ids;
    for (const auto& e : fs::directory_iterator(classDir)) ids.push_back(e.path().filename().string());
    std::sort(ids.begin(), ids.end());
    std::printf("Class of %d apple submissions (%zu kinds, each file distinct), %d jobs, sandbox: %s\n", students,
                mix.size(), jobs, sandboxSupport().summary.c_str());

    // simlab grade, from an empty object cache.
    fs::create_directories(work.path() + "/cache");
    auto start = Clock::now();
    const ProcessResult graded = run({SIMLAB_SIMLAB_PATH, "grade", "apple", classDir, "--out", work.path() + "/grades",
                                      "--jobs", std::to_string(jobs)},
                                     work.path(), {"SIMLAB_CACHE=" + work.path() + "/cache"});
    const double simlabSeconds = since(start);
    if (!graded.exitedCleanly()) {
        std::fprintf(stderr, "simlab grade failed:\n%s", graded.output.c_str());
        return 1;
    }

    // The floor: compile, link and one run of every test, without simlab in between.
    std::atomic<std::size_t> next{0};
    std::vector<double> compile(ids.size()), link(ids.size()), tests(ids.size());
    auto floorWorker = [&] {
        for (std::size_t i = next++; i < ids.size(); i = next++) {
            const std::string dir = work.path() + "/floor/" + ids[i];
            fs::create_directories(dir);
            std::vector<std::string> cc = manifest.compile;
            cc.insert(cc.end(), {"-c", classDir + "/" + ids[i] + "/NewtonsApple.cpp", "-o", dir + "/student.o"});
            auto t = Clock::now();
            const bool compiled = run(cc, dir).exitedCleanly();
            compile[i] = since(t);
            if (!compiled) continue;
            std::vector<std::string> ld = manifest.link;
            ld.insert(ld.end(), {"-o", dir + "/grader", dir + "/student.o"});
            ld.insert(ld.end(), apple.graderObjects.begin(), apple.graderObjects.end());
            ld.insert(ld.end(), manifest.graderLibraries.begin(), manifest.graderLibraries.end());
            t = Clock::now();
            run(ld, dir);
            link[i] = since(t);
            t = Clock::now();
            run({dir + "/grader"}, dir, {"SIMLAB_RUBRIC=" + apple.rubric});
            tests[i] = since(t);
        }
    };
    start = Clock::now();
    std::vector<std::thread> workers;
    for (int j = 0; j < jobs; ++j) workers.emplace_back(floorWorker);
    for (std::thread& w : workers) w.join();
    const double floorSeconds = since(start);

    // A CMake project per submission, for a few.
    std::vector<double> cmake;
    for (int i = 0; i < cmakeSamples && i < static_cast<int>(ids.size()); ++i) {
        const std::string dir = work.path() + "/cmake/" + ids[i];
        fs::create_directories(dir);
        std::string objects, libraries;
        for (const std::string& o : apple.graderObjects) objects += " " + o;
        for (const std::string& l : manifest.graderLibraries) libraries += " " + l;
        writeFileAtomically(dir + "/CMakeLists.txt",
            "cmake_minimum_required(VERSION 3.25)\nproject(submission CXX)\nset(CMAKE_CXX_STANDARD 17)\n"
            "add_compile_options(-O1)\n"
            "add_executable(grader " + classDir + "/" + ids[i] + "/NewtonsApple.cpp" + objects + ")\n"
            "target_include_directories(grader PRIVATE " + manifest.sourceDir + "/assignments " + manifest.sourceDir +
            "/assignments/support/include /usr/include/simbody)\n"
            "target_link_libraries(grader PRIVATE" + libraries + " pthread)\n");
        const auto t = Clock::now();
        run({"/usr/bin/cmake", "-S", dir, "-B", dir + "/build"}, dir);
        run({"/usr/bin/cmake", "--build", dir + "/build"}, dir);
        cmake.push_back(since(t));
    }

    const double perSubmission = simlabSeconds / students, floorPer = floorSeconds / students;
    std::printf("\n%-44s %10s\n", "", "s/student");
    std::printf("%-44s %10.2f   (%.1f s in all)\n", "simlab grade (sandbox, a process per test)", perSubmission,
                simlabSeconds);
    std::printf("%-44s %10.2f   (%.1f s in all)\n", "floor: compile + link + one run of all tests", floorPer,
                floorSeconds);
    std::printf("%-44s %10.2f   (each, one at a time; median of %zu)\n", "a CMake project per submission",
                median(cmake), cmake.size());
    std::printf("\nsimlab / floor = %.2f   (target <= 1.3; <= 2 s per submission on 2 cores)\n",
                simlabSeconds / floorSeconds);
    if (!cmake.empty()) {
        std::printf("CMake per submission / simlab per submission (both per core) = %.1f\n",
                    median(cmake) / (perSubmission * jobs));
    }
    std::printf("floor phases, median per student: compile %.2f s, link %.2f s, tests %.2f s\n", median(compile),
                median(link), median(tests));
    return 0;
}
