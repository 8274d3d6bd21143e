// What the benchmarks share: a tool run with generous limits, the clock and the median.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <vector>

#include "simlab/isolation/process.h"

namespace simlab::bench {

using Clock = std::chrono::steady_clock;

inline double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// `argv` in `dir`, as simlab's own tools run: an hour of CPU and wall time, room for a class's processes.
inline isolation::ProcessResult run(const std::vector<std::string>& argv, const std::string& dir,
                                    const std::vector<std::string>& env = {}) {
    isolation::ProcessRequest r;
    r.argv = argv;
    r.env = isolation::childEnvironment(env);
    r.workDir = dir;
    r.limits.wallSeconds = r.limits.cpuSeconds = 3600;
    r.limits.memoryMiB = 1 << 16;
    r.limits.processes = 4096;
    r.limits.fileMiB = 1 << 12;
    r.limits.outputKiB = 1 << 20;
    return isolation::runProcess(r);
}

/// The variables that choose how simlab sandboxes a test, passed on from the benchmark's own environment, so that
/// each way can be measured: SIMLAB_NO_BUBBLEWRAP, SIMLAB_NO_LANDLOCK, SIMLAB_NO_TEST_SERVER.
inline std::vector<std::string> sandboxChoices() {
    std::vector<std::string> passed;
    for (const char* name : {"SIMLAB_NO_BUBBLEWRAP", "SIMLAB_NO_LANDLOCK", "SIMLAB_NO_TEST_SERVER"}) {
        if (const char* value = std::getenv(name)) passed.push_back(std::string(name) + "=" + value);
    }
    return passed;
}

/// The simlab a benchmark measures: this build's unless --simlab names another.
inline std::string& simlabPath() {
    static std::string path = SIMLAB_SIMLAB_PATH;
    return path;
}

inline double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

}  // namespace simlab::bench
