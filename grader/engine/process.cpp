#include "simlab/engine/process.h"

#include <dirent.h>
#include <fcntl.h>
#include <grp.h>
#include <poll.h>
#include <sched.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <random>
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

// Throwaway users for sandboxed children: one per concurrent child of this simlab process.
uid_t sandboxUid(int slot) {
    const char* base = std::getenv("SIMLAB_SANDBOX_UID_BASE");
    const uid_t first = base ? static_cast<uid_t>(std::strtoul(base, nullptr, 10)) : 2000000;
    return first + static_cast<uid_t>(::getpid() % 4096) * 64 + static_cast<uid_t>(slot % 64);
}

// bubblewrap's arguments: the system's programs and libraries, read-only; `readOnly` at their own paths; a
// private /tmp; the working directory writable; no network, no view of other processes.
std::vector<std::string> bubblewrapArguments(const std::string& bwrap, const std::vector<std::string>& readOnly,
                                             const std::string& workDir) {
    namespace fs = std::filesystem;
    std::vector<std::string> a = {bwrap, "--unshare-all", "--die-with-parent", "--ro-bind", "/usr", "/usr"};
    for (const char* dir : {"/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32"}) {
        std::error_code error;
        if (fs::is_symlink(dir, error)) a.insert(a.end(), {"--symlink", fs::read_symlink(dir, error).string(), dir});
        else if (fs::is_directory(dir, error)) a.insert(a.end(), {"--ro-bind", dir, dir});
    }
    // The loader's cache, and Debian's alternatives (BLAS and LAPACK, which Simbody loads, are chosen there).
    a.insert(a.end(), {"--ro-bind-try", "/etc/ld.so.cache", "/etc/ld.so.cache", "--ro-bind-try", "/etc/alternatives",
                       "/etc/alternatives", "--proc", "/proc", "--dev", "/dev", "--tmpfs", "/tmp"});
    for (const std::string& path : readOnly) a.insert(a.end(), {"--ro-bind", path, path});
    a.insert(a.end(), {"--bind", workDir, workDir, "--chdir", workDir, "--"});
    return a;
}

std::string randomToken() {
    std::random_device device;
    static const char* hex = "0123456789abcdef";
    std::string token;
    for (int i = 0; i < 32; ++i) token += hex[device() % 16];
    return token;
}

void setLimit(int resource, rlim_t value) {
    const struct rlimit limit = {value, value};
    ::setrlimit(resource, &limit);
}

// The child between fork and exec: only async-signal-safe calls, no allocation.
[[noreturn]] void becomeChild(const ProcessRequest& r, const Launch& launch, char* const* argv, char* const* envp,
                              int outWrite, int reportWrite, int tokenRead) {
    ::setpgid(0, 0);
    // Die with simlab, even under kill -9: a sleeping child must not outlive the batch.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != launch.parent) ::_exit(127);
    const int devNull = ::open("/dev/null", O_RDONLY);
    if (devNull >= 0) ::dup2(devNull, 0);
    ::dup2(outWrite, 1);
    ::dup2(outWrite, 2);
    if (reportWrite >= 0) ::dup2(reportWrite, 3);  // dup2 clears close-on-exec on the copy
    if (tokenRead >= 0) ::dup2(tokenRead, 4);
    // Nothing else simlab holds, or inherited from whoever started it (a terminal, a CI runner's pipes), may
    // reach the child.
    ::close_range(reportWrite >= 0 ? 5 : 3, ~0U, 0);
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
        for (const char* c : candidates) {
            if (::access(c, X_OK) == 0) {
                bwrap = c;
                break;
            }
        }
        if (!bwrap.empty()) {
            // Try it the way tests will use it: as the throwaway user when we are root.
            char dir[] = "/tmp/simlab-probe-XXXXXX";
            if (::mkdtemp(dir)) {
                ProcessRequest probe;
                probe.workDir = dir;
                probe.env = childEnvironment();
                Launch launch;
                launch.argv = bubblewrapArguments(bwrap, {}, dir);
                launch.argv.push_back("/bin/true");
                launch.dropUser = support.ownUser;
                launch.uid = sandboxUid(63);
                launch.parent = ::getpid();
                if (launch.dropUser && ::chown(dir, launch.uid, launch.uid) != 0) launch.dropUser = false;
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
    Launch launch;
    launch.argv = r.argv;
    launch.parent = ::getpid();
    launch.tasks = taskLimitFor(r.limits.processes);
    if (r.isolate) {
        const SandboxSupport& support = sandboxSupport();
        if (support.ownUser && r.ownUser) {
            launch.dropUser = true;
            launch.uid = sandboxUid(r.slot);
            launch.tasks = static_cast<rlim_t>(r.limits.processes);  // the user is ours alone
            if (::chown(r.workDir.c_str(), launch.uid, launch.uid) != 0) {
                ProcessResult failed;
                failed.error = "cannot hand the test's directory to the sandbox user: " + std::string(std::strerror(errno));
                return failed;
            }
        }
        if (support.bubblewrap) {
            launch.argv = bubblewrapArguments(support.bwrap, r.readOnlyPaths, r.workDir);
            launch.argv.insert(launch.argv.end(), r.argv.begin(), r.argv.end());
        } else {
            launch.newNetwork = true;
        }
    }
    ProcessResult result = launchProcess(r, launch);
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
    const std::string token = r.reportChannel ? randomToken() : "";

    // Everything the child needs is prepared before fork.
    std::vector<std::string> envStrings = r.env;
    if (r.reportChannel) {
        envStrings.push_back("SIMLAB_REPORT_FD=3");
        envStrings.push_back("SIMLAB_TOKEN_FD=4");
    }
    std::vector<char*> argv, envp;
    for (const std::string& a : launch.argv) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    for (const std::string& e : envStrings) envp.push_back(const_cast<char*>(e.c_str()));
    envp.push_back(nullptr);

    int out[2] = {-1, -1}, report[2] = {-1, -1}, tokenPipe[2] = {-1, -1};
    auto closeAll = [&] {
        for (int fd : {out[0], out[1], report[0], report[1], tokenPipe[0], tokenPipe[1]}) {
            if (fd >= 0) ::close(fd);
        }
    };
    if (::pipe2(out, O_CLOEXEC) != 0 ||
        (r.reportChannel && (::pipe2(report, O_CLOEXEC) != 0 || ::pipe2(tokenPipe, O_CLOEXEC) != 0))) {
        result.error = std::string("cannot create a pipe: ") + std::strerror(errno);
        closeAll();
        return result;
    }
    if (tokenPipe[1] >= 0) {
        // The token travels by pipe, not environment: the harness reads it before any student code runs. It is
        // written now, while we hold the read end, so a child that dies unread cannot SIGPIPE simlab.
        const std::string line = token + "\n";
        (void)!::write(tokenPipe[1], line.data(), line.size());
        ::close(tokenPipe[1]);
        tokenPipe[1] = -1;
    }

    becomeSubreaper();
    const auto start = Clock::now();
    pid_t pid = 0;
    {
        // Registered before the reaper can see it exit.
        std::lock_guard<std::mutex> guard(gChildrenLock);
        pid = ::fork();
        if (pid == 0) becomeChild(r, launch, argv.data(), envp.data(), out[1], report[1], tokenPipe[0]);
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
    if (tokenPipe[0] >= 0) ::close(tokenPipe[0]);
    int outRead = out[0], reportRead = report[0];
    for (int fd : {outRead, reportRead}) {
        if (fd >= 0) ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
    }

    const auto deadline = start + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(r.limits.wallSeconds));
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

    for (;;) {
        struct pollfd fds[2];
        nfds_t n = 0;
        if (outRead >= 0) fds[n++] = {outRead, POLLIN, 0};
        if (reportRead >= 0) fds[n++] = {reportRead, POLLIN, 0};
        if (n > 0) ::poll(fds, n, 50);
        else if (!reaped) ::usleep(20000);

        if (outRead >= 0) drain(outRead, &result.output, r.keepOutput, &result.outputBytes);
        if (reportRead >= 0) drain(reportRead, &reportBuffer, 4 << 20, nullptr);

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
    for (int fd : {outRead, reportRead}) {
        if (fd >= 0) ::close(fd);
    }
    reapOrphans();

    result.cpuSeconds = usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
                        1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
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

    // Report lines count only with the token this run handed out.
    std::size_t begin = 0;
    while (r.reportChannel && begin < reportBuffer.size()) {
        std::size_t end = reportBuffer.find('\n', begin);
        if (end == std::string::npos) break;  // a line cut short by a crash is not a report
        const std::string line = reportBuffer.substr(begin, end - begin);
        if (line.size() > token.size() && line.compare(0, token.size(), token) == 0 && line[token.size()] == ' ') {
            result.reports.push_back(line.substr(token.size() + 1));
        }
        begin = end + 1;
    }
    return result;
}

}  // namespace

}  // namespace simlab::engine
