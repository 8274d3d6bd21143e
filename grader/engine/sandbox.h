// The pieces of the sandbox that process.cpp puts around a child: the system-call filter, Landlock's file rules,
// throwaway users, and what a test's processes use together. Internal to the engine.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace simlab::engine::sandbox {

/// The system-call filter, as the BPF program seccomp loads (built once with libseccomp): refused with EPERM are
/// the kernel keyrings, other processes' memory and descriptors, new namespaces and mounts, System V and POSIX
/// message queues, semaphores and shared memory (which outlive a process: notes between students), sockets of
/// any kind (no network, no abstract socket to another student), the terminal's input queue and console
/// (ioctl TIOCSTI, TIOCLINUX, TIOCCONS), leaving the process group or session (setsid, setpgid: the whole group is
/// ended when the test ends), and the kernel's own interfaces (modules, BPF, perf events, io_uring, userfaultfd,
/// the clock, reboot, swap, accounting, file handles). clone with a namespace flag is refused; clone3 reports
/// ENOSYS so that threads fall back to clone. Another architecture's calls end the process.
/// Empty where libseccomp does not know this machine.
const std::string& filterProgram();

/// The system calls the filter refuses outright, by name (for the tests, which try each).
std::vector<std::string> refusedCalls();

/// Loads `program` (from filterProgram) into the calling process, after PR_SET_NO_NEW_PRIVS. Only system calls:
/// safe between fork and exec. Returns false if the kernel refused it.
bool installFilter(const std::string& program);

/// Landlock's ABI version on this kernel (0: none, or the calls are blocked, as by an older container profile).
int landlockAbi();

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

/// A user id no process of this machine runs as and that this process has never handed out: one per sandboxed
/// process, never reused in a batch. $SIMLAB_SANDBOX_UID_BASE moves the range (default 2,000,000,000 and up).
uid_t freshUser();

/// Ends every process that runs as `uid` (also those that left the process group, the session or the process
/// tree): a helper becomes that user and signals them all with SIGKILL until none answers. Returns how many were
/// left when it gave up (0: none).
int endProcessesOf(uid_t uid);

/// What a test's processes use together: the tree under `root`, and every process of `uid` (when not 0) wherever
/// it went. CPU time counts what each has used and what its reaped children used; memory is resident anonymous and
/// shared memory (what they allocated), not the libraries every process maps.
struct Usage {
    double cpuSeconds = 0;
    long residentKiB = 0;
    int processes = 0;
};
Usage usageOf(pid_t root, uid_t uid);

/// The tasks (processes and threads) that run as `uid` now, as RLIMIT_NPROC counts them.
long tasksOf(uid_t uid);

/// The peak resident memory of process `pid` itself (VmHWM, KiB), not of what it started; 0 if it is gone.
long peakResidentOf(pid_t pid);

}  // namespace simlab::engine::sandbox
