#include "simlab/engine/process.h"

#include <dirent.h>
#include <fcntl.h>
#include <grp.h>
#include <poll.h>
#include <sched.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <linux/audit.h>
#include <linux/filter.h>
#include <linux/seccomp.h>
#include <sched.h>
#include <cstddef>
#include <cstdint>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <mutex>
#include <set>

namespace simlab::engine {

namespace {

using Clock = std::chrono::steady_clock;

std::atomic<bool> gInterrupted{false};

// Children being waited for, each by the thread that started it. Everything else that ends up our child is an
// orphan: simlab is a subreaper, so processes that bubblewrap (or student code) leaves behind are reparented to
// it rather than to init, which on some machines never reaps them, and their zombies would count against the
// sandbox user's process limit.
std::mutex gChildrenLock;
std::set<pid_t> gChildren;

void becomeSubreaper() {
    static std::once_flag once;
    std::call_once(once, [] { ::prctl(PR_SET_CHILD_SUBREAPER, 1); });
}

void reapOrphans() {
    std::lock_guard<std::mutex> guard(gChildrenLock);
    for (;;) {
        siginfo_t info{};
        if (::waitid(P_ALL, 0, &info, WEXITED | WNOHANG | WNOWAIT) != 0 || info.si_pid == 0) return;
        if (gChildren.count(info.si_pid)) return;  // its thread reaps it; the next call gets past it
        ::waitpid(info.si_pid, nullptr, WNOHANG);
    }
}

// How the child is to be started; all of it decided before fork.
struct Launch {
    std::vector<std::string> argv;  // with bubblewrap's arguments in front when sandboxed
    bool dropUser = false;          // become `uid` (we are root)
    uid_t uid = 0;
    bool newNetwork = false;        // unshare the network ourselves (sandboxed without bubblewrap)
    rlim_t tasks = 0;               // RLIMIT_NPROC; 0 leaves it alone
    pid_t parent = 0;
};

// Throwaway users for sandboxed children: two per concurrent grading of this simlab process (a probe's and its
// judge's), 64 gradings at most.
uid_t sandboxUid(int slot, bool judge) {
    const char* base = std::getenv("SIMLAB_SANDBOX_UID_BASE");
    const uid_t first = base ? static_cast<uid_t>(std::strtoul(base, nullptr, 10)) : 2000000;
    return first + static_cast<uid_t>(::getpid() % 4096) * 128 + (judge ? 64 : 0) + static_cast<uid_t>(slot % 64);
}

const char* const kSetpriv = "/usr/bin/setpriv";
constexpr int kSeccompFd = 10;  // where bubblewrap reads the sandbox's system-call filter

// The system calls a sandboxed process may not make, as a classic BPF program for seccomp: the kernel keyrings
// (which outlive a process and would let one student's code leave a note for the next, who runs as the same
// throwaway user), other processes' memory, new namespaces, and interfaces no simulation needs. Refused calls fail
// with EPERM (clone3 with ENOSYS, so that threads fall back to clone); calls of another architecture are refused
// outright. Empty where simlab does not know the architecture.
std::string seccompProgram() {
#if defined(__x86_64__)
    const std::uint32_t arch = AUDIT_ARCH_X86_64;
#elif defined(__aarch64__)
    const std::uint32_t arch = AUDIT_ARCH_AARCH64;
#else
    return "";
#endif
    const std::vector<long> denied = {
        SYS_add_key, SYS_request_key, SYS_keyctl, SYS_ptrace, SYS_process_vm_readv, SYS_process_vm_writev,
        SYS_perf_event_open, SYS_bpf, SYS_userfaultfd, SYS_io_uring_setup, SYS_io_uring_enter,
        SYS_io_uring_register, SYS_unshare, SYS_setns, SYS_mount, SYS_umount2, SYS_pivot_root, SYS_chroot,
        SYS_kexec_load, SYS_init_module, SYS_finit_module, SYS_delete_module, SYS_swapon, SYS_swapoff, SYS_reboot};
    const std::uint32_t namespaces = CLONE_NEWUSER | CLONE_NEWNS | CLONE_NEWPID | CLONE_NEWNET | CLONE_NEWIPC |
                                     CLONE_NEWUTS | CLONE_NEWCGROUP;
    // The program, by index (n denied calls): 0 load arch; 1 known arch?; 2 kill; 3 load nr; 4 x32 call?;
    // 5 .. 4+n denied?; 5+n clone3?; 6+n clone?; 7+n load flags; 8+n namespace flag?; 9+n and 10+n allow;
    // 11+n EPERM; 12+n ENOSYS. A jump's offset counts from the instruction after it.
    const std::size_t n = denied.size();
    const std::size_t eperm = 11 + n, enosys = 12 + n;
    auto to = [](std::size_t from, std::size_t target) { return static_cast<std::uint8_t>(target - from - 1); };
    std::vector<struct sock_filter> f;
    f.push_back(BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offsetof(struct seccomp_data, arch)));
    f.push_back(BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, arch, 1, 0));
    f.push_back(BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_KILL_PROCESS));
    f.push_back(BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offsetof(struct seccomp_data, nr)));
#if defined(__x86_64__)
    f.push_back(BPF_JUMP(BPF_JMP | BPF_JGE | BPF_K, 0x40000000, to(4, eperm), 0));  // the x32 calls
#else
    f.push_back(BPF_JUMP(BPF_JMP | BPF_JA, 0, 0, 0));  // (no x32 here: the same layout)
#endif
    for (std::size_t i = 0; i < n; ++i) {
        f.push_back(BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, static_cast<std::uint32_t>(denied[i]), to(5 + i, eperm), 0));
    }
    f.push_back(BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_clone3, to(5 + n, enosys), 0));
    // clone with a namespace flag (the flags are clone's first argument on both architectures).
    f.push_back(BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_clone, 0, to(6 + n, 10 + n)));
    f.push_back(BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offsetof(struct seccomp_data, args[0])));
    f.push_back(BPF_JUMP(BPF_JMP | BPF_JSET | BPF_K, namespaces, to(8 + n, eperm), 0));
    f.push_back(BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ALLOW));
    f.push_back(BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ALLOW));
    f.push_back(BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ERRNO | (EPERM & SECCOMP_RET_DATA)));
    f.push_back(BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ERRNO | (ENOSYS & SECCOMP_RET_DATA)));
    return std::string(reinterpret_cast<const char*>(f.data()), f.size() * sizeof(struct sock_filter));
}

bool isUnder(const std::string& path, const std::string& folder) {
    return path.size() > folder.size() && path.compare(0, folder.size(), folder) == 0 && path[folder.size()] == '/';
}

// bubblewrap's arguments: the system's programs and libraries, read-only, with `masked` hidden under empty
// folders where the system holds them; `readOnly` at their own paths; a private /tmp and /dev/shm of at most the
// file-size limit; the working directory, writable (or a scratch one); no network, no view of other processes.
// With `dropTo` (simlab is root), bubblewrap itself runs as root - so that it can lend paths below folders only
// root may enter - and setpriv makes the command the throwaway user `dropTo`, without capabilities.
std::vector<std::string> bubblewrapArguments(const std::string& bwrap, const ProcessRequest& r, uid_t dropTo,
                                             bool seccomp) {
    namespace fs = std::filesystem;
    const std::vector<std::string> system = {"/usr", "/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32"};
    std::vector<std::string> a = {bwrap};
    if (dropTo) {
        a.insert(a.end(), {"--unshare-pid", "--unshare-net", "--unshare-ipc", "--unshare-uts", "--unshare-cgroup-try"});
    } else {
        a.push_back("--unshare-all");
    }
    a.push_back("--die-with-parent");
    for (const std::string& dir : system) {
        std::error_code error;
        if (fs::is_symlink(dir, error)) a.insert(a.end(), {"--symlink", fs::read_symlink(dir, error).string(), dir});
        else if (fs::is_directory(dir, error)) a.insert(a.end(), {"--ro-bind", dir, dir});
    }
    for (const std::string& path : r.maskedPaths) {
        for (const std::string& dir : system) {
            if (isUnder(path, dir)) a.insert(a.end(), {"--tmpfs", path});
        }
    }
    const std::string scratch = std::to_string(static_cast<unsigned long long>(r.limits.fileMiB) << 20);
    // The loader's cache, and Debian's alternatives (BLAS and LAPACK, which Simbody loads, are chosen there).
    a.insert(a.end(), {"--perms", "0755", "--dir", "/etc", "--ro-bind-try", "/etc/ld.so.cache", "/etc/ld.so.cache",
                       "--ro-bind-try", "/etc/alternatives",
                       "/etc/alternatives", "--proc", "/proc", "--dev", "/dev", "--perms", "1777", "--size", scratch,
                       "--tmpfs", "/dev/shm", "--perms", "1777", "--size", scratch, "--tmpfs", "/tmp"});
    // The folders leading to what is lent, made enterable (bubblewrap would make them for root alone).
    std::set<std::string> made;
    auto leadTo = [&](const std::string& path) {
        std::vector<std::string> folders;
        for (fs::path p = fs::path(path).parent_path(); p.has_relative_path(); p = p.parent_path()) folders.push_back(p);
        for (auto f = folders.rbegin(); f != folders.rend(); ++f) {
            const bool isSystem = std::any_of(system.begin(), system.end(), [&](const std::string& d) {
                return *f == d || isUnder(*f, d);
            });
            if (isSystem || *f == "/tmp" || *f == "/dev" || *f == "/proc" || !made.insert(*f).second) continue;
            a.insert(a.end(), {"--perms", "0755", "--dir", *f});
        }
    };
    for (const std::string& path : r.readOnlyPaths) {
        leadTo(path);
        a.insert(a.end(), {"--ro-bind", path, path});
    }
    leadTo(r.workDir);
    if (r.scratchWorkDir) a.insert(a.end(), {"--perms", "1777", "--size", scratch, "--tmpfs", r.workDir});
    else a.insert(a.end(), {"--bind", r.workDir, r.workDir});
    if (seccomp) a.insert(a.end(), {"--seccomp", std::to_string(kSeccompFd)});
    a.insert(a.end(), {"--chdir", r.workDir, "--"});
    if (dropTo) {
        const std::string id = std::to_string(dropTo);
        a.insert(a.end(), {kSetpriv, "--reuid=" + id, "--regid=" + id, "--clear-groups", "--inh-caps=-all",
                           "--bounding-set=-all", "--"});
    }
    return a;
}

void setLimit(int resource, rlim_t value) {
    const struct rlimit limit = {value, value};
    ::setrlimit(resource, &limit);
}

// The child between fork and exec: only async-signal-safe calls, no allocation.
[[noreturn]] void becomeChild(const ProcessRequest& r, const Launch& launch, char* const* argv, char* const* envp,
                              int outWrite, int reportWrite) {
    ::setpgid(0, 0);
    // Die with simlab, even under kill -9: a sleeping child must not outlive the batch.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != launch.parent) ::_exit(127);
    const int devNull = ::open("/dev/null", O_RDONLY);
    if (devNull >= 0) ::dup2(devNull, 0);
    ::dup2(outWrite, 1);
    ::dup2(outWrite, 2);
    // Descriptors handed to the child go to numbers above any target first (targets are below 16), so that moving
    // one to its place never closes another still waiting; dup2 clears close-on-exec on the copy.
    int highest = 2;
    int moved[16];
    const std::size_t passed = std::min<std::size_t>(r.passFds.size(), 15);
    for (std::size_t i = 0; i < passed; ++i) moved[i] = ::fcntl(r.passFds[i].second, F_DUPFD, 64);
    if (reportWrite >= 0) {
        ::dup2(reportWrite, 3);
        highest = 3;
    }
    for (std::size_t i = 0; i < passed; ++i) {
        ::dup2(moved[i], r.passFds[i].first);
        highest = std::max(highest, r.passFds[i].first);
    }
    // Nothing else simlab holds, or inherited from whoever started it (a terminal, a CI runner's pipes), may
    // reach the child.
    ::close_range(static_cast<unsigned>(highest + 1), ~0U, 0);
    if (::chdir(r.workDir.c_str()) != 0) {
        const char message[] = "simlab: cannot enter the test's working directory\n";
        (void)!::write(2, message, sizeof message - 1);
        ::_exit(127);
    }
    const Limits& l = r.limits;
    const rlim_t cpu = static_cast<rlim_t>(std::ceil(l.cpuSeconds));
    const struct rlimit cpuLimit = {cpu, cpu + 1};  // SIGXCPU at the soft limit, SIGKILL a second later
    ::setrlimit(RLIMIT_CPU, &cpuLimit);
    setLimit(RLIMIT_AS, static_cast<rlim_t>(l.memoryMiB) << 20);
    setLimit(RLIMIT_FSIZE, static_cast<rlim_t>(l.fileMiB) << 20);
    if (launch.tasks > 0) setLimit(RLIMIT_NPROC, launch.tasks);
    setLimit(RLIMIT_CORE, 0);
    setLimit(RLIMIT_NOFILE, 256);
    if (launch.newNetwork) {
        // A network namespace of our own holds only a loopback device that is down: no connection goes anywhere.
        if (::unshare(CLONE_NEWNET) != 0 && !launch.dropUser) ::unshare(CLONE_NEWUSER | CLONE_NEWNET);
    }
    if (launch.dropUser) {
        if (::setgroups(0, nullptr) != 0 || ::setgid(launch.uid) != 0 || ::setuid(launch.uid) != 0) {
            const char message[] = "simlab: cannot switch to the sandbox user\n";
            (void)!::write(2, message, sizeof message - 1);
            ::_exit(127);
        }
    }
    ::execve(argv[0], argv, envp);
    const char message[] = "simlab: cannot execute the program\n";
    (void)!::write(2, message, sizeof message - 1);
    ::_exit(127);
}

// RLIMIT_NPROC caps every task (process or thread) of the user, not of one process tree. To let the child
// start `processes` more, count what the user runs now. Root is exempt from the limit: returns 0, "no limit".
rlim_t taskLimitFor(long processes) {
    const uid_t uid = ::getuid();
    if (uid == 0) return 0;
    rlim_t tasks = 0;
    if (DIR* proc = ::opendir("/proc")) {
        while (const struct dirent* entry = ::readdir(proc)) {
            if (entry->d_name[0] < '0' || entry->d_name[0] > '9') continue;
            std::ifstream status(std::string("/proc/") + entry->d_name + "/status");
            std::string key;
            long owner = -1, threads = 0;
            while (status >> key) {
                if (key == "Uid:") status >> owner;
                else if (key == "Threads:") status >> threads;
                std::getline(status, key);
            }
            if (owner == static_cast<long>(uid)) tasks += static_cast<rlim_t>(threads);
        }
        ::closedir(proc);
    }
    return tasks + static_cast<rlim_t>(processes);
}

// The CPU time of the process tree under `root`: each live process's own time and that of the children it has
// reaped. RLIMIT_CPU holds each process to the limit; this holds the test as a whole, so that a fork bomb's
// spinning processes, each under the limit, still time out together.
double treeCpuSeconds(pid_t root) {
    static const double ticksPerSecond = static_cast<double>(::sysconf(_SC_CLK_TCK));
    double total = 0;
    std::vector<pid_t> pending = {root};
    std::set<pid_t> seen;
    while (!pending.empty() && seen.size() < 8192) {
        const pid_t pid = pending.back();
        pending.pop_back();
        if (!seen.insert(pid).second) continue;
        const std::string dir = "/proc/" + std::to_string(pid);
        std::ifstream stat(dir + "/stat");
        std::string line;
        if (!std::getline(stat, line)) continue;
        // The fields after the command's closing parenthesis: state is field 3, utime 14 ... cstime 17.
        std::istringstream fields(line.substr(line.rfind(')') + 2));
        std::string field;
        double ticks = 0;
        for (int index = 3; index <= 17 && fields >> field; ++index) {
            if (index >= 14) ticks += std::strtod(field.c_str(), nullptr);
        }
        total += ticks / ticksPerSecond;
        if (DIR* tasks = ::opendir((dir + "/task").c_str())) {
            while (const struct dirent* task = ::readdir(tasks)) {
                if (task->d_name[0] == '.') continue;
                std::ifstream children(dir + "/task/" + task->d_name + "/children");
                for (pid_t child; children >> child;) pending.push_back(child);
            }
            ::closedir(tasks);
        }
    }
    return total;
}

void drain(int& fd, std::string* keep, std::size_t keepLimit, std::size_t* counted) {
    char buffer[65536];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n > 0) {
            if (counted) *counted += static_cast<std::size_t>(n);
            if (keep->size() < keepLimit) keep->append(buffer, std::min<std::size_t>(n, keepLimit - keep->size()));
            continue;
        }
        if (n < 0 && errno == EINTR) continue;
        if (n < 0 && errno == EAGAIN) return;
        ::close(fd);  // end of file, or an error we cannot recover from
        fd = -1;
        return;
    }
}

}  // namespace

std::string signalName(int signal) {
    if (const char* abbrev = ::sigabbrev_np(signal)) return std::string("SIG") + abbrev;
    return "signal " + std::to_string(signal);
}

std::vector<std::string> childEnvironment(const std::vector<std::string>& extra) {
    std::vector<std::string> env;
    for (const char* name : {"PATH", "HOME", "LANG", "TMPDIR"}) {
        if (const char* value = std::getenv(name)) env.push_back(std::string(name) + "=" + value);
    }
    env.insert(env.end(), extra.begin(), extra.end());
    return env;
}

void interruptChildren() { gInterrupted.store(true); }

bool childrenInterrupted() { return gInterrupted.load(); }

namespace {
ProcessResult launchProcess(const ProcessRequest& r, const Launch& launch);
}

const SandboxSupport& sandboxSupport() {
    static SandboxSupport support;
    static std::once_flag probed;
    std::call_once(probed, [] {
        support.ownUser = ::geteuid() == 0;
        const char* candidates[] = {"/usr/bin/bwrap", "/bin/bwrap", "/usr/local/bin/bwrap"};
        std::string bwrap;
        // SIMLAB_NO_BUBBLEWRAP=1 tries the fallback on a machine that has bubblewrap.
        const char* without = std::getenv("SIMLAB_NO_BUBBLEWRAP");
        for (const char* c : candidates) {
            if (!(without && std::string(without) == "1") && ::access(c, X_OK) == 0) {
                bwrap = c;
                break;
            }
        }
        support.rootBubblewrap = support.ownUser && ::access(kSetpriv, X_OK) == 0;
        if (!bwrap.empty()) {
            // Try it the way tests will use it: as root handing over to a throwaway user (or, without setpriv,
            // as that user from the start) when we are root; as ourselves otherwise.
            char dir[] = "/tmp/simlab-probe-XXXXXX";
            if (::mkdtemp(dir)) {
                ProcessRequest probe;
                probe.workDir = dir;
                probe.env = childEnvironment();
                probe.limits.fileMiB = 1;
                Launch launch;
                launch.uid = sandboxUid(63, true);
                launch.argv = bubblewrapArguments(bwrap, probe, support.rootBubblewrap ? launch.uid : 0, false);
                launch.argv.push_back("/bin/true");
                launch.dropUser = support.ownUser && !support.rootBubblewrap;
                launch.parent = ::getpid();
                if (support.ownUser && ::chown(dir, launch.uid, launch.uid) != 0) launch.dropUser = false;
                support.bubblewrap = launchProcess(probe, launch).exitedCleanly();
                ::rmdir(dir);
            }
        }
        if (support.bubblewrap) {
            support.bwrap = bwrap;
            support.summary = support.ownUser ? "bubblewrap, a user of its own for each test" : "bubblewrap";
        } else {
            support.summary = support.ownUser ? "limits, a user of its own for each test" : "limits only";
            support.warning = bwrap.empty()
                ? "bubblewrap is not installed (apt-get install bubblewrap): student code runs with limits but can "
                  "read files readable by all users"
                : "bubblewrap cannot create namespaces here: student code runs with limits but can read files "
                  "readable by all users";
        }
    });
    return support;
}

ProcessResult runProcess(const ProcessRequest& r) {
    if (gInterrupted.load()) {
        for (const auto& fd : r.passFds) ::close(fd.second);
        ProcessResult refused;
        refused.interrupted = true;
        refused.error = "interrupted";
        return refused;
    }
    ProcessRequest withFilter = r;  // the request, with the system-call filter's pipe when there is one
    Launch launch;
    launch.argv = r.argv;
    launch.parent = ::getpid();
    launch.tasks = taskLimitFor(r.limits.processes);
    if (r.isolate) {
        const SandboxSupport& support = sandboxSupport();
        if (support.ownUser && r.ownUser) {
            // bubblewrap run as root hands over to the user itself (setpriv); otherwise we switch before it.
            launch.dropUser = !(support.bubblewrap && support.rootBubblewrap);
            launch.uid = sandboxUid(r.slot, r.judgeUser);
            launch.tasks = static_cast<rlim_t>(r.limits.processes);  // the user is ours alone
            if (::chown(r.workDir.c_str(), launch.uid, launch.uid) != 0) {
                ProcessResult failed;
                failed.error = "cannot hand the test's directory to the sandbox user: " + std::string(std::strerror(errno));
                for (const auto& fd : r.passFds) ::close(fd.second);
                return failed;
            }
        }
        if (support.bubblewrap) {
            const bool handOver = support.rootBubblewrap && support.ownUser && r.ownUser;
            // The system-call filter travels on a pipe that bubblewrap reads whole.
            static const std::string program = seccompProgram();
            int filter[2] = {-1, -1};
            if (!program.empty() && ::pipe2(filter, O_CLOEXEC) == 0) {
                if (::write(filter[1], program.data(), program.size()) == static_cast<ssize_t>(program.size())) {
                    withFilter.passFds.push_back({kSeccompFd, filter[0]});
                } else {
                    ::close(filter[0]);
                    filter[0] = -1;
                }
                ::close(filter[1]);
            }
            launch.argv = bubblewrapArguments(support.bwrap, r, handOver ? launch.uid : 0, filter[0] >= 0);
            launch.argv.insert(launch.argv.end(), r.argv.begin(), r.argv.end());
        } else {
            launch.newNetwork = true;
        }
    }
    ProcessResult result = launchProcess(withFilter, launch);
    // bubblewrap reports a child's death by signal N as exit status 128 + N.
    if (r.isolate && sandboxSupport().bubblewrap && result.signal == 0 && result.exitCode > 128 &&
        result.exitCode < 128 + 65) {
        result.signal = result.exitCode - 128;
        result.exitCode = -1;
        if (result.signal == SIGXCPU) result.cpuTimeout = true;
    }
    return result;
}

namespace {

ProcessResult launchProcess(const ProcessRequest& r, const Launch& launch) {
    ProcessResult result;
    // The descriptors handed over belong to this child alone: simlab keeps no copy once it has started.
    auto closePassed = [&] {
        for (const auto& fd : r.passFds) ::close(fd.second);
    };

    // Everything the child needs is prepared before fork.
    std::vector<std::string> envStrings = r.env;
    if (r.reportChannel) envStrings.push_back("SIMLAB_REPORT_FD=3");
    std::vector<char*> argv, envp;
    for (const std::string& a : launch.argv) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    for (const std::string& e : envStrings) envp.push_back(const_cast<char*>(e.c_str()));
    envp.push_back(nullptr);

    int out[2] = {-1, -1}, report[2] = {-1, -1};
    auto closeAll = [&] {
        for (int fd : {out[0], out[1], report[0], report[1]}) {
            if (fd >= 0) ::close(fd);
        }
        closePassed();
    };
    if (::pipe2(out, O_CLOEXEC) != 0 || (r.reportChannel && ::pipe2(report, O_CLOEXEC) != 0)) {
        result.error = std::string("cannot create a pipe: ") + std::strerror(errno);
        closeAll();
        return result;
    }

    becomeSubreaper();
    const auto start = Clock::now();
    pid_t pid = 0;
    {
        // Registered before the reaper can see it exit.
        std::lock_guard<std::mutex> guard(gChildrenLock);
        pid = ::fork();
        if (pid == 0) becomeChild(r, launch, argv.data(), envp.data(), out[1], report[1]);
        if (pid > 0) gChildren.insert(pid);
    }
    if (pid < 0) {
        result.error = std::string("cannot start a process: ") + std::strerror(errno);
        closeAll();
        return result;
    }

    ::setpgid(pid, pid);  // also done by the child; whichever runs first wins the race harmlessly
    result.started = true;
    ::close(out[1]);
    if (report[1] >= 0) ::close(report[1]);
    closePassed();
    int outRead = out[0], reportRead = report[0];
    for (int fd : {outRead, reportRead}) {
        if (fd >= 0) ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
    }

    // Limits are checked when rubrics and options are read; a day is far more than any of them allows.
    const auto deadline = start + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(std::min(r.limits.wallSeconds, 86400.0)));
    const std::size_t outputLimit = static_cast<std::size_t>(r.limits.outputKiB) * 1024;
    std::string reportBuffer;
    bool reaped = false, killed = false;
    int status = 0;
    struct rusage usage {};
    auto killGroup = [&] {
        ::kill(-pid, SIGKILL);
        killed = true;
    };
    Clock::time_point reapedAt;
    Clock::time_point nextCpuCheck = start;
    double treeCpu = 0;

    // The child's exit wakes the loop at once through a pidfd, where the kernel has them.
    int pidfd = static_cast<int>(::syscall(SYS_pidfd_open, pid, 0));
    for (;;) {
        struct pollfd fds[3];
        nfds_t n = 0;
        if (outRead >= 0) fds[n++] = {outRead, POLLIN, 0};
        if (reportRead >= 0) fds[n++] = {reportRead, POLLIN, 0};
        if (pidfd >= 0 && !reaped) fds[n++] = {pidfd, POLLIN, 0};
        if (n > 0) ::poll(fds, n, 50);
        else if (!reaped) ::usleep(20000);

        if (outRead >= 0) drain(outRead, &result.output, r.keepOutput, &result.outputBytes);
        if (reportRead >= 0) drain(reportRead, &reportBuffer, 1 << 20, nullptr);

        if (!killed && result.outputBytes > outputLimit) {
            result.outputLimit = true;
            killGroup();
        }
        reapOrphans();
        if (!reaped) {
            const pid_t done = ::wait4(pid, &status, WNOHANG, &usage);
            if (done == pid) {
                {
                    std::lock_guard<std::mutex> guard(gChildrenLock);
                    gChildren.erase(pid);
                }
                reaped = true;
                reapedAt = Clock::now();
                result.wallSeconds = std::chrono::duration<double>(reapedAt - start).count();
                ::kill(-pid, SIGKILL);  // whatever it left behind in its group
            }
        }
        if (!reaped && !killed && Clock::now() >= nextCpuCheck) {
            nextCpuCheck = Clock::now() + std::chrono::milliseconds(100);
            treeCpu = std::max(treeCpu, treeCpuSeconds(pid));
            if (treeCpu > r.limits.cpuSeconds) {
                result.cpuTimeout = true;
                killGroup();
            }
        }
        if (!reaped && !killed && Clock::now() >= deadline) {
            result.wallTimeout = true;
            killGroup();
        }
        if (!reaped && !killed && gInterrupted.load()) {
            result.interrupted = true;
            killGroup();
        }
        // Done when the child is gone and its pipes are closed, or shortly after it is gone if something it
        // started (and moved out of its group) still holds them.
        if (reaped && ((outRead < 0 && reportRead < 0) || Clock::now() - reapedAt > std::chrono::milliseconds(500))) {
            break;
        }
    }
    for (int fd : {outRead, reportRead, pidfd}) {
        if (fd >= 0) ::close(fd);
    }
    reapOrphans();

    result.cpuSeconds = usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
                        1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    result.cpuSeconds = std::max(result.cpuSeconds, treeCpu);
    result.maxRssKiB = usage.ru_maxrss;
    if (WIFEXITED(status)) result.exitCode = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
    if (result.signal == SIGXCPU ||
        (result.signal == SIGKILL && !killed && result.cpuSeconds >= std::ceil(r.limits.cpuSeconds))) {
        result.cpuTimeout = true;
    }
    if (result.exitCode == 127 && result.output.rfind("simlab: cannot", 0) == 0) {
        result.started = false;
        result.error = result.output.substr(0, result.output.find('\n'));
    }

    std::size_t begin = 0;
    while (r.reportChannel && begin < reportBuffer.size()) {
        const std::size_t end = reportBuffer.find('\n', begin);
        if (end == std::string::npos) break;  // a line cut short by a crash is not a report
        result.reports.push_back(reportBuffer.substr(begin, end - begin));
        begin = end + 1;
    }
    return result;
}

}  // namespace

}  // namespace simlab::engine
