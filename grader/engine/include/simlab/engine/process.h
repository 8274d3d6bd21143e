// Running untrusted programs: one child process group with resource limits, a wall-clock deadline, a cap on
// its output, and optionally the private report channel a grader test writes its verdict to and a sandbox.
//
// The sandbox. Run as root (CI, Gradescope), the child becomes a throwaway user of its own, so the process limit
// applies to it alone (root is exempt from that limit). With bubblewrap it also gets no network, its own process
// namespace and a filesystem holding only the system's programs and libraries, the paths it is lent read-only and
// its working directory: nothing of other students'. Without bubblewrap it gets a private network namespace where
// the kernel allows one, and the limits.
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
    bool reportChannel = false;     ///< give the child a report pipe (fd 3) and its token (read from fd 4)
    std::size_t keepOutput = 16 * 1024;  ///< bytes of output kept for the report (all of it is counted)
    bool isolate = false;           ///< run in the sandbox (see above)
    std::vector<std::string> readOnlyPaths;  ///< with isolate: what the child may read, at the same paths
    bool ownUser = true;            ///< with isolate as root: run as a throwaway user (false: a trusted tool
                                    ///< that needs only the private filesystem, such as the compiler)
    int slot = 0;                   ///< with isolate as root: which throwaway user (one per concurrent child)
};

struct ProcessResult {
    bool started = false;        ///< false: fork or exec failed (see `error`)
    std::string error;
    int exitCode = -1;           ///< when it exited normally
    int signal = 0;              ///< when a signal ended it
    bool wallTimeout = false;    ///< killed at the wall-clock deadline
    bool cpuTimeout = false;     ///< stopped by the CPU-time limit
    bool outputLimit = false;    ///< killed for printing more than the output limit
    bool interrupted = false;    ///< killed because interruptChildren() was called
    double wallSeconds = 0;
    double cpuSeconds = 0;
    std::size_t outputBytes = 0; ///< everything it printed, counted
    std::string output;          ///< the first keepOutput bytes of stdout and stderr, interleaved
    std::vector<std::string> reports;  ///< report-channel lines that carried the token, token removed

    bool exitedCleanly() const { return started && signal == 0 && exitCode == 0; }
};

/// Run the request to completion. Never throws for anything the child does.
ProcessResult runProcess(const ProcessRequest& request);

/// What the sandbox can do on this machine, found once by trying bubblewrap.
struct SandboxSupport {
    bool bubblewrap = false;  ///< namespaces and a private filesystem
    std::string bwrap;        ///< bubblewrap's path
    bool ownUser = false;     ///< each child runs as a throwaway user (we are root)
    std::string summary;      ///< one line, e.g. "bubblewrap, one user per test"
    std::string warning;      ///< why isolation is partial; empty when it is complete
};
const SandboxSupport& sandboxSupport();

/// Stop every running child and make runProcess return; safe to call from a signal handler.
void interruptChildren();
bool childrenInterrupted();

/// The environment for children: PATH, HOME, LANG and TMPDIR from this process, plus `extra`.
std::vector<std::string> childEnvironment(const std::vector<std::string>& extra = {});

/// "SIGSEGV" for SIGSEGV, "signal 42" for what has no name.
std::string signalName(int signal);

}  // namespace simlab::engine
