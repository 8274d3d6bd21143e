// Isolation: running what simlab does not trust. Every sandboxed process simlab starts - a compiler, a linker, a
// judge, a probe and its host, a program built from a student's file, a tool - is built here (one place for each
// mode's sandbox), watched here (one supervisor: its CPU time and memory together with everything it started, its
// output, the wall clock, an interruption) and ended here with everything it left behind.
//
// What holds in every mode, for every sandboxed process:
//  - no student's code runs as root or with a capability: a probe's host holds none of it and loads it only as
//    the test's own user, after every capability is gone (host/probe_host.cpp); a program built from a student's
//    file is started as a user of its own (as root) or as the user who started simlab;
//  - it reads the system, what it is lent and its own folder, and nothing of simlab's places (its sources, build or
//    installation, the labs' folders, caches, the class and the grades), whatever folder holds them (reach.h);
//  - code built from a student's file runs under the students' system-call filter, an allow-list (filter.h);
//  - each process is in a session of its own with no terminal, its limits its own and its processes' together.
//
// The modes, the first this machine allows (sandboxSupport): bubblewrap (namespaces: a filesystem of the system
// and what is lent, no network, its own processes); Landlock (where bubblewrap cannot make namespaces, as in
// Docker's default profile: the kernel lets it read only the system and what is lent, write only its folder); limits
// only (no bubblewrap, no Landlock: files are kept apart by their permissions alone, which simlab audits before it
// runs hidden tests). As root each process runs as a throwaway user of its own; not as root, as simlab's user.
#pragma once

#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "simlab/isolation/reach.h"
#include "simlab/rubric/rubric.h"

namespace simlab::isolation {

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
    bool isolate = false;           ///< run in the sandbox
    bool studentCode = false;       ///< with isolate: the program is built from a student's file, so it runs under
                                    ///< the students' system-call filter (an allow-list) instead of the tools'
    std::vector<std::string> readOnlyPaths;  ///< with isolate: what the child may read, at the same paths (lent
                                             ///< even where it lies inside a hidden folder)
    std::vector<std::string> handOver;       ///< with isolate as root: paths the throwaway user owns for the run
                                             ///< (with what is in them), shut to every other user
    bool scratchWorkDir = false;    ///< with bubblewrap: the working directory is an empty memory file system
                                    ///< (nothing the child writes there comes back) instead of workDir itself
    bool ownUser = true;            ///< with isolate as root: run as a throwaway user, new for this run
    bool serveTests = false;        ///< with isolate, where testServers(): a probe's host serving a submission's
                                    ///< tests; it keeps CAP_SETUID, CAP_SETGID and CAP_SETPCAP alone, to start each
                                    ///< test's probe as a user of its own with none (see TestServer)
    std::function<bool(double)> stalled;  ///< called as the run's processes are added up (every 100 ms) with their
                                          ///< CPU time so far: true ends the run as at the wall-clock net
                                          ///< (wallTimeout). The caller's judgement, never the child's
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
    bool diskLimit = false;      ///< killed when its files took more than its scratch space holds (three times the
                                 ///< file-size limit, as bubblewrap's memory folders give it)
    bool interrupted = false;    ///< killed, or never started, because interruptChildren() was called
    double wallSeconds = 0;
    double cpuSeconds = 0;
    long maxRssKiB = 0;          ///< the peak resident memory of its processes together (as often as it looked)
    long ownPeakKiB = 0;         ///< the child's own peak resident memory, without what it started (0: unknown)
    int leftBehind = 0;          ///< processes of its throwaway user that could not be ended (0: none)
    std::size_t outputBytes = 0; ///< everything it printed, counted
    std::string output;          ///< the first keepOutput bytes of stdout and stderr, interleaved
    std::vector<std::string> reports;  ///< complete lines from the report channel (at most 1 MiB of them)

    bool exitedCleanly() const { return started && signal == 0 && exitCode == 0; }
};

/// Run the request to completion. Never throws for anything the child does.
ProcessResult runProcess(const ProcessRequest& request);

/// simlab-probe-host, which the engine names when it reads its manifest: where bubblewrap, run as root, hands a
/// program built from a student's file over to its user (setpriv), the host loads the students' filter after the
/// handover and runs the program (bubblewrap itself could only load it before, and setpriv may not change users
/// under it). Without it such a program runs under the tools' filter there.
void useProbeHost(const std::string& path);

/// Sends `size` bytes from `data` and the descriptors `fds` (SCM_RIGHTS) as one message on the socket `socket`;
/// true if all of it went. The descriptors stay open here.
bool sendWithDescriptors(int socket, const void* data, std::size_t size, const std::vector<int>& fds);

/// Whether a test's processes can be forked from a host started once for them (TestServer): as root, with
/// bubblewrap or Landlock, unless $SIMLAB_NO_TEST_SERVER=1.
bool testServers();

/// A submission's probe server: simlab-probe-host started once in the sandbox for a submission's tests, which
/// forks each test's probe on request - so that a test pays neither for a sandbox of its own nor for loading the
/// host and its libraries again. The host holds no student code; each test's child takes a user of its own, never
/// used before or again, with no capability, the test's limits and a folder of its own (its HOME and TMPDIR:
/// nothing else is writable, so nothing one test leaves reaches the next), and only then loads the submission's
/// probe. Its CPU time and memory are its user's processes together, and every one of them ends with the test.
/// What the server says of a probe (that it started, how it ended) comes from the kernel (waitpid), never from the
/// probe.
class TestServer {
public:
    /// Starts `server` (a request with serveTests set, whose argv asks the host to serve; its limits are the
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
    std::string folder_;  // the server's folder, where each test's is
    int tests_ = 0;
    ProcessResult result_;  // the server's own
    std::thread thread_;
    std::mutex lock_;
};

/// What the sandbox can do on this machine, found once by trying it: the first of bubblewrap, Landlock and
/// limits only that works (see the top of this file).
struct SandboxSupport {
    std::string mode;         ///< "bubblewrap", "Landlock" or "limits only"
    bool bubblewrap = false;  ///< namespaces and a private filesystem
    bool landlock = false;    ///< without bubblewrap: Landlock's file rules
    bool filter = false;      ///< the system-call filters are loaded
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

/// At most `maxLines` lines of a tool's output, the rest summarized as "... (N more lines)".
std::string firstLines(const std::string& text, int maxLines);

}  // namespace simlab::isolation
