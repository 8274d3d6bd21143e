// Running untrusted programs: one child process group with resource limits, a CPU-time limit that decides
// "timed out", a generous wall-clock net for what sleeps or blocks, a cap on its output, optionally a report
// channel (descriptor 3) and other descriptors handed to it, and a sandbox.
//
// The sandbox. Run as root (CI, Gradescope), the child becomes a throwaway user of its own, so the process limit
// applies to it alone (root is exempt from that limit); a judge and the probe it questions get different users.
// With bubblewrap it also gets no network, its own process namespace and a filesystem holding only the system's
// programs and libraries, the paths it is lent read-only and a working directory: nothing of other students' or
// of simlab's. Its /tmp and, for tests, its working directory are memory file systems capped at the file-size
// limit. Without bubblewrap it gets a private network namespace where the kernel allows one, and the limits.
#pragma once

#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <string>
#include <vector>

#include "simlab/rubric.h"

namespace simlab::engine {

struct ProcessRequest {
    std::vector<std::string> argv;  ///< argv[0] is a path; nothing is looked up in PATH
    std::vector<std::string> env;   ///< the child's whole environment, "NAME=value"
    std::string workDir;            ///< the child's working directory (must exist)
    Limits limits;
    bool reportChannel = false;     ///< descriptor 3 of the child is a pipe to simlab; its lines are `reports`
    std::vector<std::pair<int, int>> passFds;  ///< {descriptor in the child, simlab's descriptor}: handed to the
                                               ///< child and closed in simlab once the child has started
    std::size_t keepOutput = 16 * 1024;  ///< bytes of output kept for the report (all of it is counted)
    std::function<void(const std::string&)> onOutputLine;  ///< called with each line of output as it comes
                                                            ///< (stdout and stderr together), all of them
    bool isolate = false;           ///< run in the sandbox (see above)
    std::vector<std::string> readOnlyPaths;  ///< with isolate: what the child may read, at the same paths
    std::vector<std::string> maskedPaths;    ///< with bubblewrap: never visible, even inside a system folder
    std::vector<std::string> handOver;       ///< with isolate as root: paths the throwaway user owns for the run
                                             ///< (with what is in them), shut to every other user
    bool scratchWorkDir = false;    ///< with bubblewrap: the working directory is an empty memory file system
                                    ///< (nothing the child writes there comes back) instead of workDir itself
    bool ownUser = true;            ///< with isolate as root: run as a throwaway user, new for this run
    bool serveTests = false;        ///< with isolate, where testServers(): the child stays root, able to do nothing
                                    ///< as root but become another user (it keeps CAP_SETUID and CAP_SETGID alone),
                                    ///< and starts each test's process as a user of its own (see TestServer)
};

struct ProcessResult {
    bool started = false;        ///< false: fork or exec failed (see `error`)
    std::string error;
    int exitCode = -1;           ///< when it exited normally
    int signal = 0;              ///< when a signal ended it
    bool wallTimeout = false;    ///< killed at the wall-clock deadline
    bool cpuTimeout = false;     ///< stopped by the CPU-time limit
    bool outputLimit = false;    ///< killed for printing more than the output limit
    bool memoryLimit = false;    ///< killed when its processes together held more than the memory limit
    bool interrupted = false;    ///< killed, or never started, because interruptChildren() was called
    double wallSeconds = 0;
    double cpuSeconds = 0;
    long maxRssKiB = 0;          ///< the peak resident memory of its processes together (as often as it looked)
    long ownPeakKiB = 0;         ///< the child's own peak resident memory, without what it started
    int leftBehind = 0;          ///< processes of its throwaway user that could not be ended (0: none)
    std::size_t outputBytes = 0; ///< everything it printed, counted
    std::string output;          ///< the first keepOutput bytes of stdout and stderr, interleaved
    std::vector<std::string> reports;  ///< complete lines from the report channel (at most 1 MiB of them)

    bool exitedCleanly() const { return started && signal == 0 && exitCode == 0; }
};

/// Run the request to completion. Never throws for anything the child does.
ProcessResult runProcess(const ProcessRequest& request);

/// Sends `size` bytes from `data` and the descriptors `fds` (SCM_RIGHTS) as one message on the socket `socket`;
/// true if all of it went. The descriptors stay open here.
bool sendWithDescriptors(int socket, const void* data, std::size_t size, const std::vector<int>& fds);

/// Whether a test's processes can be forked from a program started once for them (TestServer): as root, with
/// bubblewrap or Landlock, unless $SIMLAB_NO_TEST_SERVER=1.
bool testServers();

/// A probe's server: the probe's program, started once in the sandbox for a submission's tests, that forks each
/// test's probe on request - so that a test pays neither for a sandbox of its own nor for loading the program and
/// its libraries again. The server serves from the course's first constructor, before any of the student's code
/// has run (the object check refuses what would run earlier: constructors with priorities, ifuncs, .preinit_array,
/// definitions of what the course's code calls), and never calls it. Every test's probe goes on from there as a user
/// of its own, never used before or again, with no capability, the test's limits and a folder of its own (its HOME
/// and TMPDIR: nothing else is writable, so nothing one test leaves reaches the next); its CPU time and memory are
/// its user's processes together, and every one of them ends with the test. What the server says of a probe (that
/// it started, how it ended) comes from the kernel (waitpid), never from the probe.
class TestServer {
public:
    /// Starts `server` (a request with serveTests set; its argv asks the program to serve, and its limits are the
    /// server's own, its tests' included) on a thread of its own.
    explicit TestServer(ProcessRequest server);
    /// Ends the server, whatever tests it still runs, and waits for it.
    ~TestServer();
    TestServer(const TestServer&) = delete;
    TestServer& operator=(const TestServer&) = delete;

    /// Runs one test's probe to completion, as runProcess runs `test` (its argv and workDir are unused: the
    /// program is the server's, and the probe makes a folder of its own in the server's; its descriptors 4 and 5
    /// are the two it hands over, and closes). Safe from several threads at once. None where the server cannot
    /// take the test (it is gone, never started, or could not fork): `test` still holds its descriptors, for
    /// runProcess to run it.
    std::optional<ProcessResult> run(ProcessRequest& test);

private:
    int control_ = -1;  // simlab's end of the server's requests
    int tests_ = 0;
    ProcessResult result_;  // the server's own
    std::thread thread_;
    std::mutex lock_;
};

/// What the sandbox can do on this machine, found once by trying it. Three modes, the first that works:
///  - bubblewrap: namespaces (its own filesystem of the system and what it is lent, no network, its own
///    processes), the system-call filter;
///  - Landlock (where bubblewrap cannot make namespaces, as in Docker's default profile): the kernel lets the child
///    read only the system and what it is lent and write only its working directory, whatever the files'
///    permissions; no network (sockets are filtered); the system-call filter;
///  - limits only: the filter and the limits; files are kept apart by permissions alone.
/// In every mode, as root, each sandboxed process runs as a user of its own, never used before or again in this
/// simlab, and when it ends every process of that user is ended; each runs in a session of its own with no
/// terminal; its CPU time and memory are those of all its processes together.
struct SandboxSupport {
    std::string mode;         ///< "bubblewrap", "Landlock" or "limits only"
    bool bubblewrap = false;  ///< namespaces and a private filesystem
    bool landlock = false;    ///< without bubblewrap: Landlock's file rules
    bool filter = false;      ///< the system-call filter is loaded
    std::string bwrap;        ///< bubblewrap's path
    bool ownUser = false;     ///< each child runs as a throwaway user (we are root)
    bool rootBubblewrap = false;  ///< as root, bubblewrap runs as root and setpriv hands over to that user, so that
                                  ///< it can lend paths below folders only root may enter
    std::string summary;      ///< one line: the mode and what it guarantees
    std::string warning;      ///< why isolation is partial; empty when it is complete
};
const SandboxSupport& sandboxSupport();

/// Of `paths` (files or folders), those a sandboxed process can read here: each is tried as a test's probe would
/// be run (its own user, its rules, its filter), lent `lent` as a tool is lent its inputs. Empty when nothing leaks.
std::vector<std::string> readableInSandbox(const std::vector<std::string>& paths,
                                           const std::vector<std::string>& lent = {});

/// Stop every running child, start no other, and make runProcess return; safe to call from a signal handler.
void interruptChildren();
bool childrenInterrupted();

/// The environment for children: PATH, HOME, LANG and TMPDIR from this process, GLIBC_TUNABLES with libm's
/// reproducible versions (simlab/reproducible_math.h), plus `extra`.
std::vector<std::string> childEnvironment(const std::vector<std::string>& extra = {});

/// Run a trusted tool of the system (pandoc, gnuplot, zip, git, a study program): `argv` with argv[0] an absolute
/// path, in `dir`, with childEnvironment() in the C locale, under generous nets (5 minutes, 4 GiB of files, 64 MiB
/// of output) and no sandbox. Its standard output and error, interleaved; throws std::runtime_error naming the tool
/// and its first lines when it fails. No shell: nothing in an argument is ever read as a command.
std::string runTool(const std::vector<std::string>& argv, const std::string& dir);

/// "SIGSEGV" for SIGSEGV, "signal 42" for what has no name.
std::string signalName(int signal);

}  // namespace simlab::engine
