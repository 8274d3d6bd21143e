// The parts of isolation the module's own files share: Landlock's file rules, throwaway users and what their
// processes use, how a child is started (Launch), how each mode's sandbox is built, and the one supervisor that
// watches every sandboxed run. Internal to grader/isolation.
#pragma once

#include <sys/resource.h>
#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "simlab/isolation/process.h"

namespace simlab::isolation {

using Clock = std::chrono::steady_clock;

// ---- Landlock (landlock.cpp) ----------------------------------------------------------------------------------------

namespace landlock {

/// Landlock's ABI version on this kernel (0: none, or the calls are blocked, as by an older container profile).
int abi();

/// What a child may touch under Landlock: read (and run) beneath `readable`, read and write beneath `writable`,
/// read and write the character devices `devices` (/dev/null). Everything else in the filesystem is out of reach,
/// whatever its permissions; with ABI 4 it may neither bind nor connect TCP, and with ABI 6 it may neither signal
/// nor reach an abstract socket outside its own processes.
struct FileRules {
    std::vector<std::string> readable;
    std::vector<std::string> writable;
    std::vector<std::string> devices;
};

/// A Landlock ruleset for `rules` (paths that do not exist are left out), as a close-on-exec descriptor for
/// restrictSelf, or -1 (with `error` saying why) where Landlock is missing or refuses a rule.
int makeRuleset(const FileRules& rules, std::string* error);

/// Restricts the calling process to `ruleset`, after PR_SET_NO_NEW_PRIVS: safe between fork and exec.
bool restrictSelf(int ruleset);

}  // namespace landlock

// ---- throwaway users and their processes (users.cpp) ------------------------------------------------------------------

/// A user id no process of this machine runs as and that this process has never handed out: one per sandboxed
/// process, never reused in a batch. $SIMLAB_SANDBOX_UID_BASE moves the range (default 2,000,000,000 and up).
uid_t freshUser();

/// Ends every process that runs as `uid` (also those that left the process group, the session or the process
/// tree): a helper becomes that user and signals them all with SIGKILL until none answers. Returns how many were
/// left when it gave up (0: none).
int endProcessesOf(uid_t uid);

/// What a run's processes use together: the tree under `root` (0: none), and every process of `uid` (when not 0)
/// wherever it went. CPU time counts what each has used and what its reaped children used; memory is resident
/// anonymous and shared memory (what they allocated), not the libraries every process maps; and the disk their
/// open files take that no folder names any more (a file unlinked after it was written).
struct Usage {
    double cpuSeconds = 0;
    long residentKiB = 0;
    int processes = 0;
    std::uintmax_t unlinkedBytes = 0;  ///< on disk, in files they hold open that no folder names any more
};
Usage usageOf(pid_t root, uid_t uid);

/// The tasks (processes and threads) that run as `uid` now, as RLIMIT_NPROC counts them.
long tasksOf(uid_t uid);

/// The peak resident memory of process `pid` itself (VmHWM, KiB), not of what it started; 0 if it is gone.
long peakResidentOf(pid_t pid);

/// The bytes the files under `path` take on disk, counted until past `stopAt` (or past 20,000 entries, which count
/// as past it): what a run wrote where no memory file system caps it.
std::uintmax_t folderBytes(const std::string& path, std::uintmax_t stopAt);

/// The bytes what `uid` owns in the machine's shared temporary folders (/tmp, /var/tmp, /dev/shm, /run/lock, and
/// the folders every user may write into at their tops) take on disk, counted until past `stopAt`: where no file
/// rules keep a run out of them (limits only), what its user writes there counts as the files of its folder do.
std::uintmax_t sharedTemporaryBytes(uid_t uid, std::uintmax_t stopAt);

/// Hands `path` (and what is in it) to `uid`, shut to everyone else; to root (0) hands it back.
bool handTo(const std::string& path, uid_t uid);

/// What `uid` left in the machine's shared temporary folders (only where no file rules kept it out of them).
void removeFilesOf(uid_t uid);

// ---- the sandbox of each mode (modes.cpp) ---------------------------------------------------------------------------

/// How a child is to be started; all of it decided before fork.
struct Launch {
    std::vector<std::string> argv;  // with bubblewrap's arguments in front when sandboxed
    bool dropUser = false;          // become `uid` (we are root)
    uid_t uid = 0;                  // the child's throwaway user, when it has one (0: none)
    bool newNetwork = false;        // unshare the network ourselves (sandboxed without bubblewrap)
    bool switchesUsers = false;     // stay root, keeping only CAP_SETUID, CAP_SETGID and CAP_SETPCAP (a probe's
                                    // server, without bubblewrap)
    int ruleset = -1;               // a Landlock ruleset to restrict the child to (sandboxed without bubblewrap)
    const std::string* filter = nullptr;  // the system-call filter to load (sandboxed without bubblewrap)
    rlim_t tasks = 0;               // RLIMIT_NPROC; 0 leaves it alone
    bool ownPids = false;           // in a pid namespace of its own (bubblewrap): all it starts is in its tree
    pid_t parent = 0;
};

/// The system-call filter `r` runs under: the students' (an allow-list) for a program built from a student's
/// file, the tools' otherwise; nullptr where libseccomp cannot make one.
const std::string* filterFor(const ProcessRequest& r);

/// bubblewrap's arguments for `r` (the sandbox's filesystem, namespaces, capabilities), up to the command; with
/// `dropTo` (simlab is root), setpriv makes the command that user, without capabilities.
std::vector<std::string> bubblewrapArguments(const std::string& bwrap, const ProcessRequest& r, uid_t dropTo,
                                             bool seccomp);

/// Landlock's rules for `r`: the system (less what is hidden) and what it is lent, readable; its working
/// directory, writable; the harmless devices.
landlock::FileRules fileRulesFor(const ProcessRequest& r);

/// Where bubblewrap reads the sandbox's system-call filter.
constexpr int kSeccompFd = 10;

// ---- starting and watching (process.cpp, supervisor.cpp) ------------------------------------------------------------

/// Forks (or vforks) `launch` for `r` and supervises it to its end.
ProcessResult launchProcess(const ProcessRequest& r, const Launch& launch);

/// What the supervisor watches of one run.
struct Watched {
    int out = -1;     ///< its output (non-blocking), -1 when none
    int report = -1;  ///< its report channel (non-blocking), -1 when none
    int wake = -1;    ///< a descriptor that becomes readable when the run may have ended (a pidfd, an event socket)
    /// Asks, without waiting, whether the run's first process has ended: true with its waitpid status and, where
    /// known, its CPU time (else -1).
    std::function<bool(int& status, double& cpuSeconds, long& maxRssKiB)> ended;
    /// Ends every process of the run.
    std::function<void()> kill;
    /// What the run's processes use together now.
    std::function<Usage()> usage;
    /// The first process's own peak resident memory (KiB); none where it cannot be seen.
    std::function<long()> ownPeak;
    /// The folder the run writes in, where no memory file system of bubblewrap's caps it: its files together may
    /// take what bubblewrap's three give a run (its folder, /tmp and /dev/shm, each of the file-size limit).
    std::string folder;
    /// The run's own user, where no file rules keep it out of the machine's shared temporary folders (limits
    /// only): what it writes there counts with its folder's files. 0: none.
    uid_t sharedUser = 0;
};

/// The one loop every sandboxed run is watched by: output drained and counted (the output limit), the report
/// channel read, the processes' CPU time and memory added up every 100 ms (the CPU and memory limits) and the
/// files of its folder (the disk limit), the wall clock (stalled), an interruption, and orphans reaped; until the first process has ended and its pipes are
/// closed (or half a second after, if something it started holds them). Fills `result` but its starting facts.
void supervise(const ProcessRequest& r, Watched& w, Clock::time_point start, ProcessResult& result);

/// simlab is the subreaper of what its children leave; orphans are reaped as they end.
void becomeSubreaper();
void reapOrphans();
/// Marks `pid` as a child a thread of simlab waits for itself (the reaper leaves it alone), and unmarks it.
void registerChild(pid_t pid);
void forgetChild(pid_t pid);
/// Locks the list of children across a fork, so that the reaper cannot see a child exit before it is registered.
std::mutex& childrenLock();
/// Whether interruptChildren() was called.
bool interrupted();

}  // namespace simlab::isolation
