#include "simlab/engine/process.h"

#include "simlab/engine/build.h"

#include "sandbox.h"
#include "simlab/reproducible_math.h"
#include "simlab/test_process.h"

#include <dirent.h>
#include <fcntl.h>
#include <grp.h>
#include <linux/capability.h>
#include <poll.h>
#include <sched.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/syscall.h>
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
#include <functional>
#include <sstream>
#include <mutex>
#include <optional>
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
    uid_t uid = 0;                  // the child's throwaway user, when it has one (0: none)
    bool newNetwork = false;        // unshare the network ourselves (sandboxed without bubblewrap)
    bool switchesUsers = false;     // stay root, keeping only CAP_SETUID and CAP_SETGID (a test server, without
                                    // bubblewrap)
    int ruleset = -1;               // a Landlock ruleset to restrict the child to (sandboxed without bubblewrap)
    const std::string* filter = nullptr;  // the system-call filter to load (sandboxed without bubblewrap)
    rlim_t tasks = 0;               // RLIMIT_NPROC; 0 leaves it alone
    bool ownPids = false;           // in a pid namespace of its own (bubblewrap): all it starts is in its tree
    pid_t parent = 0;
};

const char* const kSetpriv = "/usr/bin/setpriv";
constexpr int kSeccompFd = 10;  // where bubblewrap reads the sandbox's system-call filter

// What a sandboxed child may always read (and run): the system's programs and libraries, the loader's cache,
// Debian's alternatives (BLAS and LAPACK, which Simbody loads, are chosen there), fonts (gnuplot, in the judge).
const std::vector<std::string>& systemFolders() {
    static const std::vector<std::string> folders = {"/usr", "/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32"};
    return folders;
}
const char* const kSystemFiles[] = {"/etc/ld.so.cache", "/etc/alternatives", "/etc/fonts", "/etc/localtime"};
const char* const kDevices[] = {"/dev/null", "/dev/zero", "/dev/urandom", "/dev/random"};

bool isUnder(const std::string& path, const std::string& folder) {
    return path.size() > folder.size() && path.compare(0, folder.size(), folder) == 0 && path[folder.size()] == '/';
}

// bubblewrap's arguments: the system's programs and libraries, read-only, with `masked` hidden under empty
// folders where the system holds them; `readOnly` at their own paths; a private /tmp and /dev/shm of at most the
// file-size limit; the working directory, writable (or a scratch one); no network, no view of other processes.
// With `dropTo` (simlab is root), bubblewrap itself runs as root - so that it can lend paths below folders only
// root may enter - and setpriv makes the command the throwaway user `dropTo`, without capabilities.
// A test server (r.serveTests) stays root, with CAP_SETUID and CAP_SETGID alone, to start each test's process as
// a user of its own.
std::vector<std::string> bubblewrapArguments(const std::string& bwrap, const ProcessRequest& r, uid_t dropTo,
                                             bool seccomp) {
    namespace fs = std::filesystem;
    const std::vector<std::string>& system = systemFolders();
    std::vector<std::string> a = {bwrap};
    if (dropTo || r.serveTests) {
        a.insert(a.end(), {"--unshare-pid", "--unshare-net", "--unshare-ipc", "--unshare-uts", "--unshare-cgroup-try"});
        if (r.serveTests) a.insert(a.end(), {"--cap-add", "CAP_SETUID", "--cap-add", "CAP_SETGID"});
    } else {
        a.push_back("--unshare-all");
    }
    // A session of its own, with no terminal (simlab's child has one already; this holds whatever bubblewrap does).
    a.insert(a.end(), {"--die-with-parent", "--new-session"});
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
                       "/etc/alternatives", "--proc", "/proc", "--dev", "/dev"});
    if (r.serveTests) {
        // A server's tests write in their own folders alone (their TMPDIR): a shared /tmp would carry notes between
        // them.
        a.insert(a.end(), {"--perms", "0755", "--dir", "/dev/shm", "--perms", "0755", "--dir", "/tmp"});
    } else {
        a.insert(a.end(), {"--perms", "1777", "--size", scratch, "--tmpfs", "/dev/shm", "--perms", "1777", "--size",
                           scratch, "--tmpfs", "/tmp"});
    }
    // The folders leading to what is lent, made enterable (bubblewrap would make them for root alone).
    std::set<std::string> made;
    auto leadTo = [&](const std::string& path) {
        std::vector<std::string> folders;
        for (fs::path p = fs::path(path).parent_path(); p.has_relative_path(); p = p.parent_path()) folders.push_back(p);
        for (auto f = folders.rbegin(); f != folders.rend(); ++f) {
            // A system folder is there already, unless it lies in a hidden one (an installation in /usr/local).
            const bool isSystem = std::any_of(system.begin(), system.end(), [&](const std::string& d) {
                return *f == d || isUnder(*f, d);
            }) && std::none_of(r.maskedPaths.begin(), r.maskedPaths.end(), [&](const std::string& m) {
                return isUnder(*f, m);
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
    // A server's folder: root's, where only its group (root's, which the server's tests make their folders with)
    // may add, and anyone may pass through.
    if (r.scratchWorkDir) {
        a.insert(a.end(), {"--perms", r.serveTests ? "0731" : "1777", "--size", scratch, "--tmpfs", r.workDir});
    } else {
        a.insert(a.end(), {"--bind", r.workDir, r.workDir});
    }
    if (seccomp) a.insert(a.end(), {"--seccomp", std::to_string(kSeccompFd)});
    a.insert(a.end(), {"--chdir", r.workDir, "--"});
    if (dropTo) {
        const std::string id = std::to_string(dropTo);
        a.insert(a.end(), {kSetpriv, "--reuid=" + id, "--regid=" + id, "--clear-groups", "--inh-caps=-all",
                           "--bounding-set=-all", "--"});
    }
    return a;
}

// Whether the child may borrow simlab's memory until it execs (vfork: no copy of simlab's page tables, which
// costs a millisecond or more per process): not when it may have to make a user namespace of its own, which a
// process sharing its memory cannot.
bool mayShareMemory(const Launch& launch) { return !(launch.newNetwork && !launch.dropUser); }

// The child between fork (or vfork) and exec: only async-signal-safe calls, no allocation, nothing written that
// simlab reads (the memory may be simlab's own), and user and group ids changed by the system calls themselves,
// never by the C library's wrappers, which would change them in every thread of simlab too. Signals arrive
// blocked (`mask` is what to restore for the program).
[[noreturn]] void becomeChild(const ProcessRequest& r, const Launch& launch, char* const* argv, char* const* envp,
                              int outWrite, int reportWrite, const sigset_t& mask) {
    // simlab's handlers are not the child's: every caught signal back to its default before any is let in.
    for (int signal = 1; signal < NSIG; ++signal) {
        struct sigaction current {};
        if (::sigaction(signal, nullptr, &current) == 0 && current.sa_handler != SIG_DFL &&
            current.sa_handler != SIG_IGN) {
            struct sigaction reset {};
            reset.sa_handler = SIG_DFL;
            ::sigaction(signal, &reset, nullptr);
        }
    }
    // A session of its own: a process group simlab ends as a whole, and no controlling terminal, so that nothing
    // it runs can open /dev/tty or type into the terminal simlab was started from.
    ::setsid();
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
    // The Landlock ruleset too, whatever its number: a target below could be it.
    const int ruleset = launch.ruleset >= 0 ? ::fcntl(launch.ruleset, F_DUPFD_CLOEXEC, 64) : -1;
    if (reportWrite >= 0) {
        ::dup2(reportWrite, 3);
        highest = 3;
    }
    for (std::size_t i = 0; i < passed; ++i) {
        ::dup2(moved[i], r.passFds[i].first);
        highest = std::max(highest, r.passFds[i].first);
    }
    // Landlock's rules, while the ruleset's descriptor is still open (what is already open stays usable).
    if (launch.ruleset >= 0 && !sandbox::restrictSelf(ruleset)) {
        const char message[] = "simlab: cannot restrict the sandbox's files (Landlock)\n";
        (void)!::write(2, message, sizeof message - 1);
        ::_exit(127);
    }
    // Nothing else simlab holds, or inherited from whoever started it (a terminal, a CI runner's pipes), may
    // reach the child.
    ::close_range(static_cast<unsigned>(highest + 1), ~0U, 0);
    if (::chdir(r.workDir.c_str()) != 0) {
        const char message[] = "simlab: cannot enter the test's working directory\n";
        (void)!::write(2, message, sizeof message - 1);
        ::_exit(127);
    }
    // The test's CPU time is its processes' together, which the poll loop adds up and stops at the limit; each
    // process's own limit is a backstop two seconds later, so that the loop, which names the outcome, comes first.
    const Limits& l = r.limits;
    test_process::setLimits(l.cpuSeconds, static_cast<std::uint64_t>(l.memoryMiB) << 20,
                            static_cast<std::uint64_t>(l.fileMiB) << 20, launch.tasks);
    if (launch.newNetwork) {
        // A network namespace of our own holds only a loopback device that is down: no connection goes anywhere.
        if (::unshare(CLONE_NEWNET) != 0 && !launch.dropUser && !launch.switchesUsers) {
            ::unshare(CLONE_NEWUSER | CLONE_NEWNET);
        }
    }
    if (launch.switchesUsers) {
        // Root, but only to become other users: every other capability out of the bounding set, so that the
        // program this execs gets those two alone.
        for (int cap = 0; cap <= 63; ++cap) {
            if (cap != CAP_SETUID && cap != CAP_SETGID) ::prctl(PR_CAPBSET_DROP, cap, 0, 0, 0);
        }
    }
    if (launch.dropUser) {
        if (!test_process::becomeUser(launch.uid)) {
            const char message[] = "simlab: cannot switch to the sandbox user\n";
            (void)!::write(2, message, sizeof message - 1);
            ::_exit(127);
        }
        // A change of user clears the parent-death signal: set it again, and mind a parent already gone.
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (::getppid() != launch.parent) ::_exit(127);
    }
    if (launch.filter && !sandbox::installFilter(*launch.filter)) {
        const char message[] = "simlab: cannot load the sandbox's system-call filter\n";
        (void)!::write(2, message, sizeof message - 1);
        ::_exit(127);
    }
    ::sigprocmask(SIG_SETMASK, &mask, nullptr);
    // A program simlab has just written can be busy for a moment: a process another thread forked while it was
    // open for writing holds it until that process execs or exits (microseconds). Try again, briefly.
    for (int attempt = 0; attempt < 50; ++attempt) {
        ::execve(argv[0], argv, envp);
        if (errno != ETXTBSY) break;
        ::usleep(10000);
    }
    const char* why = ::strerrordesc_np(errno);  // a table's entry: safe here, unlike strerror
    const char message[] = "simlab: cannot execute the program: ";
    (void)!::write(2, message, sizeof message - 1);
    if (why) (void)!::write(2, why, std::strlen(why));
    (void)!::write(2, "\n", 1);
    ::_exit(127);
}

// RLIMIT_NPROC caps every task (process or thread) of the user, not of one process tree. To let the child
// start `processes` more, count what the user runs now. Root is exempt from the limit: returns 0, "no limit".
rlim_t taskLimitFor(long processes) {
    const uid_t uid = ::getuid();
    if (uid == 0) return 0;
    return static_cast<rlim_t>(sandbox::tasksOf(uid)) + static_cast<rlim_t>(processes);
}

// The complete lines of a report channel: a line cut short by a crash is not a report.
std::vector<std::string> reportLines(const std::string& buffer) {
    std::vector<std::string> lines;
    for (std::size_t begin = 0; begin < buffer.size();) {
        const std::size_t end = buffer.find('\n', begin);
        if (end == std::string::npos) break;
        lines.push_back(buffer.substr(begin, end - begin));
        begin = end + 1;
    }
    return lines;
}

// What a test's processes use together, against its limits: the CPU time (the most seen so far) and memory are
// kept in `result`, and the limit passed first is marked there. True if one was passed: the caller ends them.
bool overLimits(const sandbox::Usage& usage, const Limits& limits, double& treeCpu, long& peakResidentKiB,
                ProcessResult& result) {
    treeCpu = std::max(treeCpu, usage.cpuSeconds);
    peakResidentKiB = std::max(peakResidentKiB, usage.residentKiB);
    // Both are judged at every poll, and both are recorded when both are past: processes that fill memory are
    // charged the kernel's page zeroing as CPU time, so on a busy machine the two limits can be crossed between
    // the same two polls, and the verdict (memory first) must not depend on the order they are checked in.
    if (treeCpu > limits.cpuSeconds) result.cpuTimeout = true;
    if (usage.residentKiB > static_cast<long>(limits.memoryMiB) * 1024) result.memoryLimit = true;
    return result.cpuTimeout || result.memoryLimit;
}

// How the process ended (`status`, as waitpid gives it), in `result`: its exit status or signal, a CPU limit the
// kernel enforced (SIGXCPU, or a SIGKILL simlab did not send once the CPU time reached the limit), and a start
// that failed in the child ("simlab: cannot ...", status 127); then its report channel's lines.
void concludeResult(int status, bool killed, const ProcessRequest& r, const std::string& reportBuffer,
                    ProcessResult& result) {
    if (WIFEXITED(status)) result.exitCode = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
    if (!result.memoryLimit && (result.signal == SIGXCPU ||
                                (result.signal == SIGKILL && !killed && result.cpuSeconds >= std::ceil(r.limits.cpuSeconds)))) {
        result.cpuTimeout = true;
    }
    if (result.exitCode == 127 && result.output.rfind("simlab: cannot", 0) == 0) {
        result.started = false;
        result.error = result.output.substr(0, result.output.find('\n'));
    }
    if (r.reportChannel) result.reports = reportLines(reportBuffer);
}

// Reads what `fd` holds now into `keep` (up to keepLimit), counting it; with `lines`, also hands each complete
// line to it (`partial` holds the start of the next).
void drain(int& fd, std::string* keep, std::size_t keepLimit, std::size_t* counted,
           const std::function<void(const std::string&)>* lines = nullptr, std::string* partial = nullptr) {
    char buffer[65536];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n > 0) {
            if (counted) *counted += static_cast<std::size_t>(n);
            if (keep->size() < keepLimit) keep->append(buffer, std::min<std::size_t>(n, keepLimit - keep->size()));
            if (lines && *lines) {
                for (ssize_t i = 0; i < n; ++i) {
                    if (buffer[i] != '\n') {
                        if (partial->size() < (1u << 20)) partial->push_back(buffer[i]);
                        continue;
                    }
                    (*lines)(*partial);
                    partial->clear();
                }
            }
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

std::string runTool(const std::vector<std::string>& argv, const std::string& dir) {
    ProcessRequest r;
    r.argv = argv;
    r.env = childEnvironment({"LC_ALL=C"});
    r.workDir = dir;
    r.limits.wallSeconds = r.limits.cpuSeconds = 300;
    r.limits.fileMiB = 4096;
    r.limits.outputKiB = 64 * 1024;
    r.keepOutput = 64 << 20;
    const ProcessResult result = runProcess(r);
    if (!result.exitedCleanly()) {
        throw std::runtime_error(argv[0] + " failed: " + (result.started ? firstLines(result.output, 3) : result.error));
    }
    return result.output;
}

std::vector<std::string> childEnvironment(const std::vector<std::string>& extra) {
    std::vector<std::string> env;
    for (const char* name : {"PATH", "HOME", "LANG", "TMPDIR"}) {
        if (const char* value = std::getenv(name)) env.push_back(std::string(name) + "=" + value);
    }
    // libm's reproducible versions, in every child (simlab/reproducible_math.h).
    env.push_back("GLIBC_TUNABLES=" + reproducibleMathTunables(std::getenv("GLIBC_TUNABLES")));
    env.insert(env.end(), extra.begin(), extra.end());
    return env;
}

void interruptChildren() { gInterrupted.store(true); }

bool childrenInterrupted() { return gInterrupted.load(); }

namespace {
ProcessResult launchProcess(const ProcessRequest& r, const Launch& launch);
}

namespace {

// The system-call filter for a child started without bubblewrap (bubblewrap loads it itself).
const std::string* filterFor() {
    const std::string& program = sandbox::filterProgram();
    return program.empty() ? nullptr : &program;
}

// The Landlock rules of a child started without bubblewrap: the system and what it is lent, readable; its working
// directory, writable; the harmless devices.
sandbox::FileRules fileRulesFor(const ProcessRequest& r) {
    sandbox::FileRules rules;
    rules.readable = systemFolders();
    rules.readable.insert(rules.readable.end(), std::begin(kSystemFiles), std::end(kSystemFiles));
    rules.readable.insert(rules.readable.end(), r.readOnlyPaths.begin(), r.readOnlyPaths.end());
    rules.writable = {r.workDir};
    rules.devices.assign(std::begin(kDevices), std::end(kDevices));
    return rules;
}

// Hands `path` (and what is in it) to `uid`, shut to everyone else: the sandbox user owns its working directory
// and what it is lent for the run, and no other sandbox user can enter them. Handed back to root (uid 0) after.
bool handTo(const std::string& path, uid_t uid) {
    namespace fs = std::filesystem;
    std::error_code error;
    auto give = [&](const fs::path& p) {
        struct stat info {};
        if (::lstat(p.c_str(), &info) != 0 || S_ISLNK(info.st_mode)) return true;
        return ::lchown(p.c_str(), uid, uid) == 0 && ::chmod(p.c_str(), info.st_mode & 0700) == 0;
    };
    if (!give(path)) return false;
    if (!fs::is_directory(path, error)) return true;
    for (auto it = fs::recursive_directory_iterator(path, error); !error && it != fs::recursive_directory_iterator();
         it.increment(error)) {
        if (!give(it->path())) return false;
    }
    return !error;
}

// Without bubblewrap or Landlock a sandbox user could write to the machine's shared temporary folders: what it
// left there goes with it.
void removeFilesOf(uid_t uid) {
    namespace fs = std::filesystem;
    for (const char* dir : {"/tmp", "/var/tmp", "/dev/shm"}) {
        std::error_code error;
        for (auto it = fs::directory_iterator(dir, error); !error && it != fs::directory_iterator(); it.increment(error)) {
            struct stat info {};
            if (::lstat(it->path().c_str(), &info) == 0 && info.st_uid == uid) fs::remove_all(it->path(), error);
        }
    }
}

}  // namespace

const SandboxSupport& sandboxSupport() {
    static SandboxSupport support;
    static std::once_flag probed;
    std::call_once(probed, [] {
        support.ownUser = ::geteuid() == 0;
        support.filter = filterFor() != nullptr;
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
        // Each way is tried as tests will use it: as a throwaway user when we are root, in a folder of its own.
        auto works = [](Launch launch, const std::function<std::vector<std::string>(const ProcessRequest&)>& argvFor) {
            char dir[] = "/tmp/simlab-probe-XXXXXX";
            if (!::mkdtemp(dir)) return false;
            ProcessRequest probe;
            probe.workDir = dir;
            probe.env = childEnvironment();
            probe.limits.fileMiB = 1;
            launch.argv = argvFor(probe);
            launch.parent = ::getpid();
            if (launch.uid != 0 && ::chown(dir, launch.uid, launch.uid) != 0) launch.dropUser = false;
            const bool ok = launchProcess(probe, launch).exitedCleanly();
            ::rmdir(dir);
            if (launch.uid != 0) sandbox::endProcessesOf(launch.uid);
            return ok;
        };
        if (!bwrap.empty()) {
            // As root, bubblewrap hands over to the user itself (or, without setpriv, runs as that user from the
            // start); as ourselves otherwise.
            Launch launch;
            launch.uid = support.ownUser ? sandbox::freshUser() : 0;
            launch.dropUser = support.ownUser && !support.rootBubblewrap;
            const uid_t handOver = support.rootBubblewrap ? launch.uid : 0;
            support.bubblewrap = works(launch, [&](const ProcessRequest& probe) {
                std::vector<std::string> argv = bubblewrapArguments(bwrap, probe, handOver, false);
                argv.push_back("/bin/true");
                return argv;
            });
        }
        // SIMLAB_NO_LANDLOCK=1 tries the last fallback on a machine that has Landlock.
        const char* noLandlock = std::getenv("SIMLAB_NO_LANDLOCK");
        if (!support.bubblewrap && sandbox::landlockAbi() > 0 && !(noLandlock && std::string(noLandlock) == "1")) {
            Launch launch;
            launch.uid = support.ownUser ? sandbox::freshUser() : 0;
            launch.dropUser = support.ownUser;
            launch.filter = filterFor();
            ProcessRequest rules;
            rules.workDir = "/tmp";
            launch.ruleset = sandbox::makeRuleset(fileRulesFor(rules), nullptr);
            support.landlock = launch.ruleset >= 0 && works(launch, [](const ProcessRequest&) {
                return std::vector<std::string>{"/bin/true"};
            });
            if (launch.ruleset >= 0) ::close(launch.ruleset);
        }
        const std::string user = support.ownUser ? "a user of its own for each process" : "running as you";
        const std::string calls = support.filter ? ", system calls filtered" : "";
        if (support.bubblewrap) {
            support.bwrap = bwrap;
            support.mode = "bubblewrap";
            support.summary = "bubblewrap: a filesystem of its own, no network, its own processes; " + user + calls;
        } else if (support.landlock) {
            support.mode = "Landlock";
            support.summary = "Landlock: only the system and what the test is lent can be read, no network; " + user +
                              calls;
        } else {
            support.mode = "limits only";
            support.summary = "limits only: CPU, memory, processes, output and files capped; " + user + calls;
            const std::string why = bwrap.empty() ? "bubblewrap is not installed" : "bubblewrap cannot create namespaces here";
            support.warning = why + " and this kernel offers no Landlock: student code " +
                              (support.ownUser ? "can read every file other users can"
                                               : "runs as you and can read your files") +
                              " (install bubblewrap, or grade as root with the course's files unreadable to others)";
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
    ProcessRequest request = r;  // with the system-call filter's pipe and the sandbox's environment
    Launch launch;
    launch.argv = r.argv;
    launch.parent = ::getpid();
    launch.tasks = taskLimitFor(r.limits.processes);
    auto refuse = [&](const std::string& why) {
        for (const auto& fd : r.passFds) ::close(fd.second);
        ProcessResult failed;
        failed.error = why;
        return failed;
    };
    if (r.isolate) {
        const SandboxSupport& support = sandboxSupport();
        if (r.serveTests && !testServers()) return refuse("this sandbox (" + support.mode + ") starts each test itself");
        launch.switchesUsers = r.serveTests && !support.bubblewrap;
        if (support.ownUser && r.ownUser && !r.serveTests) {
            // A user never used before and never again: nothing another test left can reach this one. bubblewrap
            // run as root hands over to it itself (setpriv); otherwise we switch before the program starts.
            launch.dropUser = !(support.bubblewrap && support.rootBubblewrap);
            launch.uid = sandbox::freshUser();
            launch.tasks = static_cast<rlim_t>(r.limits.processes);  // the user is ours alone
            if (!handTo(r.workDir, launch.uid)) {
                return refuse("cannot hand the test's directory to the sandbox user: " + std::string(std::strerror(errno)));
            }
            for (const std::string& path : r.handOver) {
                if (!handTo(path, launch.uid)) return refuse("cannot hand " + path + " to the sandbox user");
            }
        }
        if (support.bubblewrap) {
            const bool handOver = support.rootBubblewrap && support.ownUser && r.ownUser;
            // The system-call filter travels on a pipe that bubblewrap reads whole.
            const std::string& program = sandbox::filterProgram();
            int filter[2] = {-1, -1};
            if (!program.empty() && ::pipe2(filter, O_CLOEXEC) == 0) {
                if (::write(filter[1], program.data(), program.size()) == static_cast<ssize_t>(program.size())) {
                    request.passFds.push_back({kSeccompFd, filter[0]});
                } else {
                    ::close(filter[0]);
                    filter[0] = -1;
                }
                ::close(filter[1]);
            }
            launch.argv = bubblewrapArguments(support.bwrap, r, handOver ? launch.uid : 0, filter[0] >= 0);
            launch.ownPids = true;
            launch.argv.insert(launch.argv.end(), r.argv.begin(), r.argv.end());
        } else {
            launch.newNetwork = true;
            launch.filter = filterFor();
            if (support.landlock) {
                std::string error;
                launch.ruleset = sandbox::makeRuleset(fileRulesFor(r), &error);
                if (launch.ruleset < 0) {
                    if (launch.uid != 0) sandbox::endProcessesOf(launch.uid);
                    return refuse(error);
                }
            }
            // Temporary files go to the working directory: /tmp is every user's.
            for (std::string& e : request.env) {
                if (e.rfind("TMPDIR=", 0) == 0) e = "TMPDIR=" + r.workDir;
            }
        }
    }
    ProcessResult result = launchProcess(request, launch);
    if (launch.ruleset >= 0) ::close(launch.ruleset);
    if (launch.uid != 0) {
        // Every process of the user ends with the run, also one that left the process group or the tree; what
        // it was handed is simlab's again, and what it left in the shared temporary folders goes.
        result.leftBehind = sandbox::endProcessesOf(launch.uid);
        handTo(r.workDir, 0);
        for (const std::string& path : r.handOver) handTo(path, 0);
        if (!sandboxSupport().bubblewrap && !sandboxSupport().landlock) removeFilesOf(launch.uid);
    }
    // bubblewrap reports a child's death by signal N as exit status 128 + N.
    if (r.isolate && sandboxSupport().bubblewrap && result.signal == 0 && result.exitCode > 128 &&
        result.exitCode < 128 + 65) {
        result.signal = result.exitCode - 128;
        result.exitCode = -1;
        // As launchProcess judges a child of its own: SIGXCPU is the CPU limit, and so is a SIGKILL simlab did not
        // send once the CPU time reached the limit (the hard limit, after a program that catches SIGXCPU - clang
        // prints a stack dump - went on).
        const bool simlabStopped = result.memoryLimit || result.wallTimeout || result.outputLimit || result.interrupted;
        if (result.signal == SIGXCPU ||
            (result.signal == SIGKILL && !simlabStopped && result.cpuSeconds >= std::ceil(r.limits.cpuSeconds))) {
            result.cpuTimeout = true;
        }
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
        sigset_t all, mask;
        ::sigfillset(&all);
        ::pthread_sigmask(SIG_SETMASK, &all, &mask);
        pid = mayShareMemory(launch) ? ::vfork() : ::fork();
        if (pid == 0) becomeChild(r, launch, argv.data(), envp.data(), out[1], report[1], mask);
        const int forkError = errno;
        ::pthread_sigmask(SIG_SETMASK, &mask, nullptr);
        errno = forkError;
        if (pid > 0) gChildren.insert(pid);
    }
    if (pid < 0) {
        result.error = std::string("cannot start a process: ") + std::strerror(errno);
        closeAll();
        return result;
    }

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
    std::string reportBuffer, partialLine;
    bool reaped = false, killed = false;
    int status = 0;
    struct rusage usage {};
    auto killGroup = [&] {
        ::kill(-pid, SIGKILL);
        ::kill(pid, SIGKILL);  // should it not have made its session yet
        if (launch.uid != 0) sandbox::endProcessesOf(launch.uid);
        killed = true;
    };
    Clock::time_point reapedAt;
    // The test's processes are added up every 100 ms (each process's own limits hold in between): a look at every
    // process of the machine, so not more often than that.
    Clock::time_point nextCpuCheck = start + std::chrono::milliseconds(50);
    double treeCpu = 0;
    long peakResidentKiB = 0, ownPeakKiB = 0;

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

        if (outRead >= 0) drain(outRead, &result.output, r.keepOutput, &result.outputBytes, &r.onOutputLine, &partialLine);
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
        // The test's processes together: its tree and, with a user of its own, every process of that user
        // wherever it went. Their CPU time and their memory are the test's.
        if (!reaped && !killed && Clock::now() >= nextCpuCheck) {
            nextCpuCheck = Clock::now() + std::chrono::milliseconds(100);
            // In a pid namespace of its own, whatever the test started is below its first process (an orphan goes
            // to the namespace's first process, bubblewrap's): the tree is all of it, and no look at every process
            // of the machine is needed.
            const sandbox::Usage usage = sandbox::usageOf(pid, launch.ownPids ? 0 : launch.uid);
            ownPeakKiB = std::max(ownPeakKiB, sandbox::peakResidentOf(pid));
            if (overLimits(usage, r.limits, treeCpu, peakResidentKiB, result)) killGroup();
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
    if (r.onOutputLine && !partialLine.empty()) r.onOutputLine(partialLine);
    reapOrphans();

    result.cpuSeconds = usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
                        1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    result.cpuSeconds = std::max(result.cpuSeconds, treeCpu);
    result.maxRssKiB = std::max(usage.ru_maxrss, peakResidentKiB);
    result.ownPeakKiB = ownPeakKiB;
    concludeResult(status, killed, r, reportBuffer, result);
    return result;
}

}  // namespace

bool sendWithDescriptors(int socket, const void* data, std::size_t size, const std::vector<int>& fds) {
    struct iovec part = {const_cast<void*>(data), size};
    std::vector<char> control(CMSG_SPACE(sizeof(int) * fds.size()), 0);
    struct msghdr m {};
    m.msg_iov = &part;
    m.msg_iovlen = 1;
    m.msg_control = control.data();
    m.msg_controllen = control.size();
    struct cmsghdr* c = CMSG_FIRSTHDR(&m);
    c->cmsg_level = SOL_SOCKET;
    c->cmsg_type = SCM_RIGHTS;
    c->cmsg_len = CMSG_LEN(sizeof(int) * fds.size());
    std::memcpy(CMSG_DATA(c), fds.data(), sizeof(int) * fds.size());
    for (;;) {
        const ssize_t sent = ::sendmsg(socket, &m, MSG_NOSIGNAL);
        if (sent < 0 && errno == EINTR) continue;
        return sent == static_cast<ssize_t>(size);
    }
}

bool testServers() {
    static const bool can = [] {
        const char* off = std::getenv("SIMLAB_NO_TEST_SERVER");
        if (off && std::string(off) == "1") return false;
        const SandboxSupport& s = sandboxSupport();
        return s.ownUser && ((s.bubblewrap && s.rootBubblewrap) || s.landlock);
    }();
    return can;
}

TestServer::TestServer(ProcessRequest server) {
    int ends[2];
    if (::socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, ends) != 0) {
        result_.error = std::string("cannot create a socket: ") + std::strerror(errno);
        return;
    }
    control_ = ends[0];
    server.passFds.push_back({test_process::kServerFd, ends[1]});
    server.isolate = true;
    server.serveTests = true;
    thread_ = std::thread([this, server] { result_ = runProcess(server); });
}

TestServer::~TestServer() {
    // The server reads the end of its requests and leaves; its tests' probes die with it.
    if (control_ >= 0) ::shutdown(control_, SHUT_RDWR);
    if (thread_.joinable()) thread_.join();
    if (control_ >= 0) ::close(control_);
}

namespace {

// One message from the server on a test's socket, waiting at most until `deadline` (and no longer than an
// interruption); false if the socket ended or nothing came.
bool nextEvent(int fd, test_process::TestEvent& event, Clock::time_point deadline) {
    for (;;) {
        struct pollfd p = {fd, POLLIN, 0};
        const int n = ::poll(&p, 1, 100);
        if (n > 0) {
            const ssize_t got = ::recv(fd, &event, sizeof event, 0);
            if (got < 0 && errno == EINTR) continue;
            return got == static_cast<ssize_t>(sizeof event);
        }
        if (n < 0 && errno != EINTR) return false;
        if (Clock::now() >= deadline || gInterrupted.load()) return false;
    }
}

}  // namespace

std::optional<ProcessResult> TestServer::run(ProcessRequest& t) {
    ProcessResult result;
    if (control_ < 0) return std::nullopt;
    if (gInterrupted.load()) {
        for (const auto& fd : t.passFds) ::close(fd.second);
        result.interrupted = true;
        result.error = "interrupted";
        return result;
    }
    // The test's own socket to the server, its output and its event channel; the judge's pipes come with the test.
    int notify[2] = {-1, -1}, out[2] = {-1, -1}, report[2] = {-1, -1};
    auto closeOurs = [&] {
        for (int fd : {notify[0], notify[1], out[0], out[1], report[0], report[1]}) {
            if (fd >= 0) ::close(fd);
        }
    };
    int requests = -1, answers = -1;
    for (const auto& [target, fd] : t.passFds) {
        if (target == 4) requests = fd;
        if (target == 5) answers = fd;
    }
    if (requests < 0 || answers < 0 || t.passFds.size() != 2 ||
        ::socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, notify) != 0 || ::pipe2(out, O_CLOEXEC) != 0 ||
        ::pipe2(report, O_CLOEXEC) != 0) {
        closeOurs();
        return std::nullopt;  // runProcess starts it as a program of its own
    }
    const uid_t uid = sandbox::freshUser();
    test_process::StartTest ask;
    ask.uid = uid;
    ask.cpuSeconds = t.limits.cpuSeconds;
    ask.memoryBytes = static_cast<std::uint64_t>(t.limits.memoryMiB) << 20;
    ask.fileBytes = static_cast<std::uint64_t>(t.limits.fileMiB) << 20;
    ask.tasks = static_cast<std::uint64_t>(std::max(1L, t.limits.processes));
    {
        std::lock_guard<std::mutex> guard(lock_);
        std::snprintf(ask.folder, sizeof ask.folder, "test%d", ++tests_);
    }
    static_assert(test_process::kStartTestFds == 5, "the server takes five descriptors with a test");
    bool sent = false;
    {
        std::lock_guard<std::mutex> guard(lock_);
        sent = sendWithDescriptors(control_, &ask, sizeof ask, {notify[1], out[1], report[1], requests, answers});
    }
    if (!sent) {
        closeOurs();
        return std::nullopt;  // the server is gone: the judge's pipes are still the caller's
    }
    // The server and the probe hold what they need now; a pipe ends when its last holder closes it.
    for (int* fd : {&notify[1], &out[1], &report[1]}) {
        ::close(*fd);
        *fd = -1;
    }

    const auto start = Clock::now();
    test_process::TestEvent event;
    if (!nextEvent(notify[0], event, start + std::chrono::seconds(60)) || event.kind != test_process::TestEvent::Started) {
        // The server could not fork, or is gone: the caller starts the probe as a program of its own, with the
        // judge's pipes it still holds.
        closeOurs();
        sandbox::endProcessesOf(uid);
        return std::nullopt;
    }
    for (const auto& fd : t.passFds) ::close(fd.second);
    t.passFds.clear();
    result.started = true;
    int outRead = out[0], reportRead = report[0], events = notify[0];
    out[0] = report[0] = notify[0] = -1;
    for (int fd : {outRead, reportRead}) ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);

    const auto deadline = start + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(std::min(t.limits.wallSeconds, 86400.0)));
    const std::size_t outputLimit = static_cast<std::size_t>(t.limits.outputKiB) * 1024;
    std::string reportBuffer, partialLine;
    bool ended = false, killed = false;
    int status = 0;
    double treeCpu = 0, endedCpu = 0;
    long peakResidentKiB = 0;
    Clock::time_point endedAt, nextCpuCheck = start + std::chrono::milliseconds(50);
    auto killAll = [&] {
        sandbox::endProcessesOf(uid);
        killed = true;
    };
    for (;;) {
        struct pollfd p[3];
        nfds_t n = 0;
        if (outRead >= 0) p[n++] = {outRead, POLLIN, 0};
        if (reportRead >= 0) p[n++] = {reportRead, POLLIN, 0};
        if (events >= 0) p[n++] = {events, POLLIN, 0};
        if (n > 0) ::poll(p, n, 50);
        else ::usleep(20000);
        if (outRead >= 0) drain(outRead, &result.output, t.keepOutput, &result.outputBytes, &t.onOutputLine, &partialLine);
        if (reportRead >= 0) drain(reportRead, &reportBuffer, 1 << 20, nullptr);
        if (!killed && result.outputBytes > outputLimit) {
            result.outputLimit = true;
            killAll();
        }
        if (events >= 0) {
            struct pollfd e = {events, POLLIN, 0};
            if (::poll(&e, 1, 0) > 0) {
                test_process::TestEvent said;
                const ssize_t got = ::recv(events, &said, sizeof said, MSG_DONTWAIT);
                if (got == static_cast<ssize_t>(sizeof said) && said.kind == test_process::TestEvent::Ended) {
                    ended = true;
                    endedAt = Clock::now();
                    status = said.status;
                    endedCpu = 1e-6 * static_cast<double>(said.cpuMicroseconds);
                    result.wallSeconds = std::chrono::duration<double>(endedAt - start).count();
                }
                if (got <= 0 || ended) {
                    ::close(events);
                    events = -1;
                    if (!ended) {  // the server went away with the test: it ended with the server
                        ended = true;
                        endedAt = Clock::now();
                        status = SIGKILL;
                        result.wallSeconds = std::chrono::duration<double>(endedAt - start).count();
                    }
                    if (!killed) sandbox::endProcessesOf(uid);  // whatever it left behind
                }
            }
        }
        // The test's processes together: every process of its user, wherever it went.
        if (!ended && !killed && Clock::now() >= nextCpuCheck) {
            nextCpuCheck = Clock::now() + std::chrono::milliseconds(100);
            if (overLimits(sandbox::usageOf(0, uid), t.limits, treeCpu, peakResidentKiB, result)) killAll();
        }
        if (!ended && !killed && Clock::now() >= deadline) {
            result.wallTimeout = true;
            killAll();
        }
        if (!ended && !killed && gInterrupted.load()) {
            result.interrupted = true;
            killAll();
        }
        if (ended && ((outRead < 0 && reportRead < 0) || Clock::now() - endedAt > std::chrono::milliseconds(500))) break;
    }
    for (int fd : {outRead, reportRead, events}) {
        if (fd >= 0) ::close(fd);
    }
    if (t.onOutputLine && !partialLine.empty()) t.onOutputLine(partialLine);
    result.leftBehind = sandbox::endProcessesOf(uid);

    result.cpuSeconds = std::max(endedCpu, treeCpu);
    result.maxRssKiB = peakResidentKiB;
    concludeResult(status, killed, t, reportBuffer, result);
    return result;
}

std::vector<std::string> readableInSandbox(const std::vector<std::string>& paths, const std::vector<std::string>& lent) {
    namespace fs = std::filesystem;
    std::vector<std::string> existing;
    for (const std::string& path : paths) {
        std::error_code error;
        if (!path.empty() && fs::exists(path, error)) existing.push_back(path);
    }
    if (existing.empty()) return {};
    char dir[] = "/tmp/simlab-audit-XXXXXX";
    if (!::mkdtemp(dir)) return {};
    // Opened, not merely looked at: access(2) would answer by the permissions alone, past Landlock.
    ProcessRequest request;
    request.argv = {"/bin/sh", "-c",
                    "for f; do if [ -d \"$f\" ]; then ls -- \"$f\" >/dev/null 2>&1 && echo \"$f\"; "
                    "else head -c 1 -- \"$f\" >/dev/null 2>&1 && echo \"$f\"; fi; done",
                    "simlab-audit"};
    request.argv.insert(request.argv.end(), existing.begin(), existing.end());
    request.env = childEnvironment({"LC_ALL=C"});
    request.workDir = dir;
    request.isolate = true;
    request.readOnlyPaths = lent;
    request.scratchWorkDir = true;
    request.limits.cpuSeconds = 10;
    request.limits.wallSeconds = 60;
    request.keepOutput = 1 << 20;
    const ProcessResult result = runProcess(request);
    std::error_code ignored;
    fs::remove_all(dir, ignored);
    std::vector<std::string> readable;
    std::istringstream lines(result.output);
    for (std::string line; std::getline(lines, line);) {
        if (std::find(existing.begin(), existing.end(), line) != existing.end()) readable.push_back(line);
    }
    return readable;
}

}  // namespace simlab::engine
