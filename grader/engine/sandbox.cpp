#include "sandbox.h"

#include <dirent.h>
#include <fcntl.h>
#include <grp.h>
#include <linux/filter.h>
#include <linux/seccomp.h>
#include <sched.h>
#include <seccomp.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <random>
#include <set>

#include "simlab/test_process.h"

namespace simlab::engine::sandbox {

namespace {

// ---- the system-call filter --------------------------------------------------------------------------------------

// Refused with EPERM, whatever their arguments.
const char* const kRefused[] = {
    // The kernel keyrings outlive a process: one test could leave a note there for the next.
    "add_key", "request_key", "keyctl",
    // Other processes: their memory, their descriptors, their details.
    "ptrace", "process_vm_readv", "process_vm_writev", "pidfd_getfd", "process_madvise", "kcmp",
    // Namespaces and mounts.
    "unshare", "setns", "mount", "umount2", "pivot_root", "chroot", "move_mount", "open_tree", "fsopen", "fsconfig",
    "fsmount", "fspick", "mount_setattr",
    // System V and POSIX IPC: named objects that outlive a process and are shared by every user of the machine.
    "msgget", "msgsnd", "msgrcv", "msgctl", "semget", "semop", "semtimedop", "semctl", "shmget", "shmat", "shmdt",
    "shmctl", "mq_open", "mq_unlink", "mq_timedsend", "mq_timedreceive", "mq_notify", "mq_getsetattr",
    // The network, and abstract sockets between students: a test talks to simlab over the pipes it is given.
    "socket",
    // Leaving the process group or the session: the whole group is ended when the test ends.
    "setsid", "setpgid",
    // The kernel's own interfaces.
    "perf_event_open", "bpf", "userfaultfd", "io_uring_setup", "io_uring_enter", "io_uring_register", "kexec_load",
    "kexec_file_load", "init_module", "finit_module", "delete_module", "swapon", "swapoff", "reboot", "acct",
    "syslog", "quotactl", "quotactl_fd", "lookup_dcookie", "vhangup", "iopl", "ioperm", "settimeofday",
    "clock_settime", "clock_adjtime", "adjtimex", "open_by_handle_at", "name_to_handle_at", "fanotify_init"};

std::string buildFilter() {
    scmp_filter_ctx ctx = seccomp_init(SCMP_ACT_ALLOW);
    if (!ctx) return "";
    struct Release {
        scmp_filter_ctx ctx;
        ~Release() { seccomp_release(ctx); }
    } release{ctx};
    bool ok = seccomp_attr_set(ctx, SCMP_FLTATR_ACT_BADARCH, SCMP_ACT_KILL_PROCESS) == 0;
    // No PR_SET_NO_NEW_PRIVS from libseccomp: installFilter sets it, and bubblewrap for its own child.
    ok = ok && seccomp_attr_set(ctx, SCMP_FLTATR_CTL_NNP, 0) == 0;
    for (const char* name : kRefused) {
        const int nr = seccomp_syscall_resolve_name(name);
        if (nr == __NR_SCMP_ERROR) continue;  // not a call of this architecture
        ok = ok && seccomp_rule_add(ctx, SCMP_ACT_ERRNO(EPERM), nr, 0) == 0;
    }
    // Threads come from clone; clone3 says it does not exist, so that the C library falls back to clone.
    ok = ok && seccomp_rule_add(ctx, SCMP_ACT_ERRNO(ENOSYS), SCMP_SYS(clone3), 0) == 0;
    for (const std::uint64_t flag : {CLONE_NEWUSER, CLONE_NEWNS, CLONE_NEWPID, CLONE_NEWNET, CLONE_NEWIPC,
                                     CLONE_NEWUTS, CLONE_NEWCGROUP, CLONE_NEWTIME}) {
        ok = ok && seccomp_rule_add(ctx, SCMP_ACT_ERRNO(EPERM), SCMP_SYS(clone), 1,
                                    SCMP_A0(SCMP_CMP_MASKED_EQ, flag, flag)) == 0;
    }
    // The terminal: typing into its input queue, the Linux console's own requests, taking the console over. An
    // ioctl's request is 32 bits; the mask keeps a request with high bits set from slipping past.
    for (const std::uint64_t request : {TIOCSTI, TIOCLINUX, TIOCCONS}) {
        ok = ok && seccomp_rule_add(ctx, SCMP_ACT_ERRNO(EPERM), SCMP_SYS(ioctl), 1,
                                    SCMP_A1(SCMP_CMP_MASKED_EQ, 0xffffffffULL, request)) == 0;
    }
    if (!ok) return "";
    const int fd = static_cast<int>(::syscall(SYS_memfd_create, "simlab-seccomp", MFD_CLOEXEC));
    if (fd < 0) return "";
    std::string program;
    if (seccomp_export_bpf(ctx, fd) == 0 && ::lseek(fd, 0, SEEK_SET) == 0) {
        char buffer[4096];
        for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0;) program.append(buffer, static_cast<std::size_t>(n));
    }
    ::close(fd);
    if (program.size() % sizeof(struct sock_filter) != 0) return "";
    return program;
}

// ---- Landlock ------------------------------------------------------------------------------------------------------
// The constants of linux/landlock.h up to ABI 6, spelled out: Debian 12's kernel headers stop at ABI 2.

constexpr std::uint64_t kExecute = 1ULL << 0, kWriteFile = 1ULL << 1, kReadFile = 1ULL << 2, kReadDir = 1ULL << 3,
                        kRemoveDir = 1ULL << 4, kRemoveFile = 1ULL << 5, kMakeChar = 1ULL << 6,
                        kMakeDir = 1ULL << 7, kMakeReg = 1ULL << 8, kMakeSock = 1ULL << 9, kMakeFifo = 1ULL << 10,
                        kMakeBlock = 1ULL << 11, kMakeSym = 1ULL << 12, kRefer = 1ULL << 13,
                        kTruncate = 1ULL << 14, kIoctlDev = 1ULL << 15;
constexpr std::uint64_t kBindTcp = 1ULL << 0, kConnectTcp = 1ULL << 1;
constexpr std::uint64_t kScopeAbstractSocket = 1ULL << 0, kScopeSignal = 1ULL << 1;
constexpr int kRulePathBeneath = 1;
constexpr unsigned kCreateRulesetVersion = 1U << 0;

struct RulesetAttr {
    std::uint64_t handledFs;
    std::uint64_t handledNet;
    std::uint64_t scoped;
};

struct __attribute__((packed)) PathBeneathAttr {
    std::uint64_t allowed;
    std::int32_t parentFd;
};

#ifndef SYS_landlock_create_ruleset
#define SYS_landlock_create_ruleset 444
#define SYS_landlock_add_rule 445
#define SYS_landlock_restrict_self 446
#endif

// Every file-system right the kernel's ABI knows.
std::uint64_t fsRights(int abi) {
    std::uint64_t rights = kExecute | kWriteFile | kReadFile | kReadDir | kRemoveDir | kRemoveFile | kMakeChar |
                           kMakeDir | kMakeReg | kMakeSock | kMakeFifo | kMakeBlock | kMakeSym;
    if (abi >= 2) rights |= kRefer;
    if (abi >= 3) rights |= kTruncate;
    if (abi >= 5) rights |= kIoctlDev;
    return rights;
}

bool addRule(int ruleset, const std::string& path, std::uint64_t dirRights, std::uint64_t fileRights, int abi,
             std::string* error) {
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) return true;  // nothing there to allow
    const int fd = ::open(path.c_str(), O_PATH | O_CLOEXEC);
    if (fd < 0) return true;
    PathBeneathAttr rule{(S_ISDIR(info.st_mode) ? dirRights : fileRights) & fsRights(abi), fd};
    const bool ok = ::syscall(SYS_landlock_add_rule, ruleset, kRulePathBeneath, &rule, 0) == 0;
    if (!ok && error) *error = "Landlock refused a rule for " + path + ": " + std::strerror(errno);
    ::close(fd);
    return ok;
}

// ---- processes -----------------------------------------------------------------------------------------------------

bool isNumber(const char* name) {
    if (!*name) return false;
    for (const char* c = name; *c; ++c) {
        if (*c < '0' || *c > '9') return false;
    }
    return true;
}

// What a small /proc file holds now (up to 16 KiB: every file read here is far smaller), read with one open and
// one or two reads. /proc is read many times a second while tests run: no stream, no locale, no allocation but
// the string.
std::string readProcFile(const char* path) {
    std::string text;
    const int fd = ::open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return text;
    char buffer[16384];
    std::size_t used = 0;
    for (;;) {
        const ssize_t n = ::read(fd, buffer + used, sizeof buffer - used);
        if (n > 0) {
            used += static_cast<std::size_t>(n);
            if (used < sizeof buffer) continue;
        } else if (n < 0 && errno == EINTR) {
            continue;
        }
        break;
    }
    ::close(fd);
    text.assign(buffer, used);
    return text;
}

// The number after `key` (a line's start, such as "Uid:") in a /proc status text, or -1.
long statusField(const std::string& status, const char* key) {
    const std::size_t length = std::strlen(key);
    for (std::size_t at = 0; at < status.size();) {
        if (status.compare(at, length, key) == 0) return std::strtol(status.c_str() + at + length, nullptr, 10);
        const std::size_t next = status.find('\n', at);
        if (next == std::string::npos) break;
        at = next + 1;
    }
    return -1;
}

// "/proc/<pid>/<file>", in a buffer of the caller's.
const char* procPath(char (&path)[320], const char* pid, const char* file) {
    std::snprintf(path, sizeof path, "/proc/%s/%s", pid, file);
    return path;
}

// The real user id of process `pid` (from its status, which shows it even for a process that made itself
// non-dumpable, whose /proc folder then belongs to root), or -1.
long realUserOf(const char* pid) {
    char path[320];
    return statusField(readProcFile(procPath(path, pid, "status")), "Uid:");
}

// False for a kernel thread (or a zombie), which has no program: /proc/<pid>/exe leads nowhere. Most of the
// folders that belong to root are kernel threads', and this answers without the kernel writing out a status.
bool mayRunAsOther(int procFd, const char* pid) {
    char path[320], target[8];
    std::snprintf(path, sizeof path, "%s/exe", pid);
    return ::readlinkat(procFd, path, target, sizeof target) >= 0 || errno != ENOENT;
}

// A process's state ('Z' for a zombie) from its stat line, or '?'.
char stateIn(const std::string& stat) {
    const std::size_t close = stat.rfind(')');
    return close != std::string::npos && close + 2 < stat.size() ? stat[close + 2] : '?';
}

// Calls `visit(pid)` (the pid as its /proc folder names it) for each process that runs as `uid`, found by one pass
// over /proc: its folder belongs to the process's user, or to root for one that made itself non-dumpable, whose
// status then tells.
template <typename Visit>
void visitProcessesOf(uid_t uid, Visit visit) {
    DIR* proc = ::opendir("/proc");
    if (!proc) return;
    const int procFd = ::dirfd(proc);
    while (const struct dirent* entry = ::readdir(proc)) {
        if (!isNumber(entry->d_name)) continue;
        struct stat info {};
        if (::fstatat(procFd, entry->d_name, &info, 0) != 0) continue;
        if (info.st_uid == uid || (info.st_uid == 0 && mayRunAsOther(procFd, entry->d_name) &&
                                   realUserOf(entry->d_name) == static_cast<long>(uid))) {
            visit(entry->d_name);
        }
    }
    ::closedir(proc);
}

// Processes that run as `uid`, with their state ('Z' for a zombie).
std::vector<std::pair<pid_t, char>> processesOf(uid_t uid) {
    std::vector<std::pair<pid_t, char>> found;
    visitProcessesOf(uid, [&](const char* pid) {
        char path[320];
        const char state = stateIn(readProcFile(procPath(path, pid, "stat")));
        found.emplace_back(static_cast<pid_t>(std::strtol(pid, nullptr, 10)), state);
    });
    return found;
}

// A process's CPU time (its own and its reaped children's, in s) and its resident anonymous memory (KiB): what it
// allocated, not the shared libraries every process maps, which would count once per process of a test.
struct ProcessStat {
    bool alive = false;
    double cpuSeconds = 0;
    long residentKiB = 0;
};

ProcessStat statOf(pid_t pid) {
    static const double ticksPerSecond = static_cast<double>(::sysconf(_SC_CLK_TCK));
    ProcessStat s;
    char id[24], path[320];
    std::snprintf(id, sizeof id, "%d", static_cast<int>(pid));
    const std::string line = readProcFile(procPath(path, id, "stat"));
    const std::size_t close = line.rfind(')');
    if (close == std::string::npos || close + 2 >= line.size()) return s;
    // The fields after the command's closing parenthesis: state is field 3, utime 14 ... cstime 17.
    const char* at = line.c_str() + close + 2;
    double ticks = 0;
    for (int index = 3; index <= 17 && *at; ++index) {
        char* end = nullptr;
        const double value = std::strtod(at, &end);
        if (index >= 14) ticks += value;
        at = std::strchr(at, ' ');
        if (!at) break;
        ++at;
    }
    s.alive = true;
    s.cpuSeconds = ticks / ticksPerSecond;
    const std::string status = readProcFile(procPath(path, id, "status"));
    for (const char* key : {"RssAnon:", "RssShmem:"}) s.residentKiB += std::max(0L, statusField(status, key));
    return s;
}

}  // namespace

const std::string& filterProgram() {
    static const std::string program = buildFilter();
    return program;
}

std::vector<std::string> refusedCalls() { return {std::begin(kRefused), std::end(kRefused)}; }

bool installFilter(const std::string& program) {
    if (program.empty()) return false;
    if (::prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0) return false;
    struct sock_fprog filter;
    filter.len = static_cast<unsigned short>(program.size() / sizeof(struct sock_filter));
    filter.filter = reinterpret_cast<struct sock_filter*>(const_cast<char*>(program.data()));
    return ::prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &filter, 0, 0) == 0;
}

int landlockAbi() {
    static const int abi = [] {
        const long version = ::syscall(SYS_landlock_create_ruleset, nullptr, 0, kCreateRulesetVersion);
        return version > 0 ? static_cast<int>(version) : 0;
    }();
    return abi;
}

int makeRuleset(const FileRules& rules, std::string* error) {
    const int abi = landlockAbi();
    if (abi == 0) {
        if (error) *error = "this kernel has no Landlock, or it is blocked here";
        return -1;
    }
    RulesetAttr attr{fsRights(abi), abi >= 4 ? kBindTcp | kConnectTcp : 0,
                     abi >= 6 ? kScopeAbstractSocket | kScopeSignal : 0};
    // The attribute's size says which fields this kernel reads.
    const std::size_t size = abi >= 6 ? sizeof attr : abi >= 4 ? 2 * sizeof(std::uint64_t) : sizeof(std::uint64_t);
    const int ruleset = static_cast<int>(::syscall(SYS_landlock_create_ruleset, &attr, size, 0));
    if (ruleset < 0) {
        if (error) *error = std::string("cannot create a Landlock ruleset: ") + std::strerror(errno);
        return -1;
    }
    ::fcntl(ruleset, F_SETFD, FD_CLOEXEC);
    const std::uint64_t read = kExecute | kReadFile | kReadDir;
    const std::uint64_t write = fsRights(abi) & ~(kMakeChar | kMakeBlock | kMakeSock);
    const std::uint64_t device = kReadFile | kWriteFile | kTruncate | kIoctlDev;
    bool ok = true;
    for (const std::string& path : rules.readable) ok = ok && addRule(ruleset, path, read, kExecute | kReadFile, abi, error);
    for (const std::string& path : rules.writable) ok = ok && addRule(ruleset, path, write, write, abi, error);
    for (const std::string& path : rules.devices) ok = ok && addRule(ruleset, path, device, device, abi, error);
    if (!ok) {
        ::close(ruleset);
        return -1;
    }
    return ruleset;
}

bool restrictSelf(int ruleset) {
    if (::prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0) return false;
    return ::syscall(SYS_landlock_restrict_self, ruleset, 0) == 0;
}

uid_t freshUser() {
    static std::mutex lock;
    static std::set<uid_t> given;
    static std::mt19937_64 random{std::random_device{}()};
    const char* base = std::getenv("SIMLAB_SANDBOX_UID_BASE");
    const std::uint64_t first = base ? std::strtoull(base, nullptr, 10) : 2000000000ULL;
    constexpr std::uint64_t kRange = 1ULL << 27;  // below 2^31 from the default base: safe for every tool
    std::lock_guard<std::mutex> guard(lock);
    for (;;) {
        const uid_t uid = static_cast<uid_t>(first + random() % kRange);
        if (given.count(uid) || !processesOf(uid).empty()) continue;
        given.insert(uid);
        return uid;
    }
}

int endProcessesOf(uid_t uid) {
    int left = 0;
    for (int round = 0; round < 10; ++round) {
        // The helper borrows simlab's memory until it exits (vfork), with every signal blocked: it changes its ids
        // by the system calls themselves (the C library's wrappers would change those of every thread of simlab).
        sigset_t all, mask;
        ::sigfillset(&all);
        ::pthread_sigmask(SIG_SETMASK, &all, &mask);
        const pid_t helper = ::vfork();
        if (helper == 0) {
            // Nothing simlab holds stays open in it (a program being written, say, would be busy meanwhile).
            ::close_range(3, ~0U, 0);
            // As that user, signal every process it may signal: exactly that user's, wherever they are. A few
            // times over: a child whose fork was under way during one signal is listed by the next. (A zombie can
            // be signalled too, so "no process left" is never the answer while one waits to be reaped: the rounds
            // below count what is left, zombies aside.)
            if (!test_process::becomeUser(uid)) ::_exit(2);
            for (int i = 0; i < 8; ++i) {
                if (::kill(-1, SIGKILL) != 0) ::_exit(errno == ESRCH ? 0 : 3);
            }
            ::_exit(1);
        }
        ::pthread_sigmask(SIG_SETMASK, &mask, nullptr);
        if (helper < 0) return -1;
        int status = 0;
        while (::waitpid(helper, &status, __WALL) < 0 && errno == EINTR) {
        }
        // No process of the user answered a signal, not even a zombie: nothing is left, and nothing can start one.
        if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return 0;
        // What is left but zombies (which their parents, or simlab as the subreaper, reap).
        left = 0;
        for (const auto& [pid, state] : processesOf(uid)) left += state != 'Z' && state != 'X';
        if (left == 0) return 0;
        ::usleep(2000 << std::min(round, 6));  // a killed process may take a moment to be gone
    }
    return left;
}

Usage usageOf(pid_t root, uid_t uid) {
    std::set<pid_t> members;
    std::vector<pid_t> pending = {root};
    while (!pending.empty() && members.size() < 8192) {
        const pid_t pid = pending.back();
        pending.pop_back();
        if (!members.insert(pid).second) continue;
        const std::string dir = "/proc/" + std::to_string(pid) + "/task";
        if (DIR* tasks = ::opendir(dir.c_str())) {
            while (const struct dirent* task = ::readdir(tasks)) {
                if (task->d_name[0] == '.') continue;
                const std::string children = readProcFile((dir + "/" + task->d_name + "/children").c_str());
                for (const char* at = children.c_str(); *at;) {
                    char* end = nullptr;
                    const long child = std::strtol(at, &end, 10);
                    if (end == at) break;
                    pending.push_back(static_cast<pid_t>(child));
                    at = end;
                }
            }
            ::closedir(tasks);
        }
    }
    if (uid != 0) {
        for (const auto& [pid, state] : processesOf(uid)) members.insert(pid);
    }
    Usage usage;
    for (const pid_t pid : members) {
        const ProcessStat s = statOf(pid);
        if (!s.alive) continue;
        ++usage.processes;
        usage.cpuSeconds += s.cpuSeconds;
        usage.residentKiB += s.residentKiB;
    }
    return usage;
}

long tasksOf(uid_t uid) {
    long tasks = 0;
    visitProcessesOf(uid, [&](const char* pid) {
        char path[320];
        tasks += std::max(0L, statusField(readProcFile(procPath(path, pid, "status")), "Threads:"));
    });
    return tasks;
}

long peakResidentOf(pid_t pid) {
    char id[24], path[320];
    std::snprintf(id, sizeof id, "%d", static_cast<int>(pid));
    return std::max(0L, statusField(readProcFile(procPath(path, id, "status")), "VmHWM:"));
}

}  // namespace simlab::engine::sandbox
