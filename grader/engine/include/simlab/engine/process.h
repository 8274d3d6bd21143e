// Running untrusted programs: one child process group with resource limits, a wall-clock deadline, a cap on
// its output, and optionally the private report channel a grader test writes its verdict to.
#pragma once

#include <string>
#include <vector>

#include "simlab/rubric.h"

namespace simlab::engine {

struct ProcessRequest {
    std::vector<std::string> argv;  ///< argv[0] is a path; nothing is looked up in PATH
    std::vector<std::string> env;   ///< the child's whole environment, "NAME=value"
    std::string workDir;            ///< the child's working directory (must exist)
    Limits limits;
    bool reportChannel = false;     ///< give the child SIMLAB_REPORT_FD and SIMLAB_REPORT_TOKEN
    std::size_t keepOutput = 16 * 1024;  ///< bytes of output kept for the report (all of it is counted)
};

struct ProcessResult {
    bool started = false;        ///< false: fork or exec failed (see `error`)
    std::string error;
    int exitCode = -1;           ///< when it exited normally
    int signal = 0;              ///< when a signal ended it
    bool wallTimeout = false;    ///< killed at the wall-clock deadline
    bool cpuTimeout = false;     ///< stopped by the CPU-time limit
    bool outputLimit = false;    ///< killed for printing more than the output limit
    double wallSeconds = 0;
    double cpuSeconds = 0;
    std::size_t outputBytes = 0; ///< everything it printed, counted
    std::string output;          ///< the first keepOutput bytes of stdout and stderr, interleaved
    std::vector<std::string> reports;  ///< report-channel lines that carried the token, token removed

    bool exitedCleanly() const { return started && signal == 0 && exitCode == 0; }
};

/// Run the request to completion. Never throws for anything the child does.
ProcessResult runProcess(const ProcessRequest& request);

/// The environment for children: PATH, HOME, LANG and TMPDIR from this process, plus `extra`.
std::vector<std::string> childEnvironment(const std::vector<std::string>& extra = {});

/// "SIGSEGV" for SIGSEGV, "signal 42" for what has no name.
std::string signalName(int signal);

}  // namespace simlab::engine
