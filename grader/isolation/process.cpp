// Starting sandboxed processes: the request made a Launch (the mode's sandbox around it, its user, its filter),
// the child set up between fork and exec, and the supervisor watching it to its end.
#include "simlab/isolation/process.h"

#include <fcntl.h>
#include <linux/capability.h>
#include <sched.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <sstream>

#include "internal.h"
#include "simlab/isolation/filter.h"
#include "simlab/isolation/host_protocol.h"
#include "simlab/reproducible_math.h"

namespace simlab::isolation {

namespace {

std::atomic<bool> gInterrupted{false};

std::mutex gHostLock;
std::string gHost;  // simlab-probe-host (useProbeHost)

std::string probeHost() {
    std::lock_guard<std::mutex> guard(gHostLock);
    return gHost;
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
    if (launch.ruleset >= 0 && !landlock::restrictSelf(ruleset)) {
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
    host::setLimits(l.cpuSeconds, static_cast<std::uint64_t>(l.memoryMiB) << 20,
                            static_cast<std::uint64_t>(l.fileMiB) << 20, launch.tasks);
    if (launch.newNetwork) {
        // A network namespace of our own holds only a loopback device that is down: no connection goes anywhere.
        if (::unshare(CLONE_NEWNET) != 0 && !launch.dropUser && !launch.switchesUsers) {
            ::unshare(CLONE_NEWUSER | CLONE_NEWNET);
        }
    }
    if (launch.switchesUsers) {
        // Root, but only to become other users: every other capability out of the bounding set, so that the
        // program this execs (a probe's host) gets those three alone, and its tests' children can drop them all.
        for (int cap = 0; cap <= 63; ++cap) {
            if (cap != CAP_SETUID && cap != CAP_SETGID && cap != CAP_SETPCAP) ::prctl(PR_CAPBSET_DROP, cap, 0, 0, 0);
        }
    }
    if (launch.dropUser) {
        // No capability to be had again, then another user, which leaves root's behind.
        if (!host::leaveCapabilities() || !host::becomeUser(launch.uid)) {
            const char message[] = "simlab: cannot switch to the sandbox user\n";
            (void)!::write(2, message, sizeof message - 1);
            ::_exit(127);
        }
        // A change of user clears the parent-death signal: set it again, and mind a parent already gone.
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (::getppid() != launch.parent) ::_exit(127);
    }
    if (launch.filter && !filter::install(*launch.filter)) {
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
    return static_cast<rlim_t>(tasksOf(uid)) + static_cast<rlim_t>(processes);
}

}  // namespace

bool interrupted() { return gInterrupted.load(); }

void useProbeHost(const std::string& path) {
    std::lock_guard<std::mutex> guard(gHostLock);
    gHost = path;
}

void interruptChildren() { gInterrupted.store(true); }

bool childrenInterrupted() { return gInterrupted.load(); }

std::string signalName(int signal) {
    if (const char* abbrev = ::sigabbrev_np(signal)) return std::string("SIG") + abbrev;
    return "signal " + std::to_string(signal);
}

std::string firstLines(const std::string& text, int maxLines) {
    std::istringstream in(text);
    std::string line, out;
    int count = 0, more = 0;
    while (std::getline(in, line)) {
        if (count < maxLines) {
            out += line + "\n";
            ++count;
        } else {
            ++more;
        }
    }
    if (more > 0) out += "... (" + std::to_string(more) + " more lines)\n";
    return out;
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
            launch.uid = freshUser();
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
            // The system-call filter travels on a pipe that bubblewrap reads whole. bubblewrap loads it before
            // setpriv hands the program over to its user: a program of a student's gets the tools' filter there,
            // and the host loads the students' after the handover.
            const std::string host = probeHost();
            const bool viaHost = r.studentCode && handOver && !host.empty();
            ProcessRequest forFilter = r;
            if (viaHost) forFilter.studentCode = false;
            const std::string* program = filterFor(forFilter);
            int filter[2] = {-1, -1};
            if (program && ::pipe2(filter, O_CLOEXEC) == 0) {
                if (::write(filter[1], program->data(), program->size()) == static_cast<ssize_t>(program->size())) {
                    request.passFds.push_back({kSeccompFd, filter[0]});
                } else {
                    ::close(filter[0]);
                    filter[0] = -1;
                }
                ::close(filter[1]);
            }
            ProcessRequest lent = r;
            if (viaHost) lent.readOnlyPaths.push_back(host);
            launch.argv = bubblewrapArguments(support.bwrap, lent, handOver ? launch.uid : 0, filter[0] >= 0);
            launch.ownPids = true;
            if (viaHost) launch.argv.insert(launch.argv.end(), {host, "--exec"});
            launch.argv.insert(launch.argv.end(), r.argv.begin(), r.argv.end());
        } else {
            launch.newNetwork = true;
            launch.filter = filterFor(r);
            if (support.landlock) {
                std::string error;
                launch.ruleset = landlock::makeRuleset(fileRulesFor(r), &error);
                if (launch.ruleset < 0) {
                    if (launch.uid != 0) endProcessesOf(launch.uid);
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
        result.leftBehind = endProcessesOf(launch.uid);
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
        std::lock_guard<std::mutex> guard(childrenLock());
        sigset_t all, mask;
        ::sigfillset(&all);
        ::pthread_sigmask(SIG_SETMASK, &all, &mask);
        pid = mayShareMemory(launch) ? ::vfork() : ::fork();
        if (pid == 0) becomeChild(r, launch, argv.data(), envp.data(), out[1], report[1], mask);
        const int forkError = errno;
        ::pthread_sigmask(SIG_SETMASK, &mask, nullptr);
        errno = forkError;
        if (pid > 0) registerChild(pid);
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
    for (int fd : {out[0], report[0]}) {
        if (fd >= 0) ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
    }

    Watched w;
    w.out = out[0];
    w.report = report[0];
    // The child's exit wakes the supervisor at once through a pidfd, where the kernel has them.
    const int pidfd = static_cast<int>(::syscall(SYS_pidfd_open, pid, 0));
    w.wake = pidfd;
    w.ended = [&](int& status, double& cpuSeconds, long& maxRssKiB) {
        struct rusage usage {};
        if (::wait4(pid, &status, WNOHANG, &usage) != pid) return false;
        forgetChild(pid);
        cpuSeconds = usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
                     1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
        maxRssKiB = usage.ru_maxrss;
        return true;
    };
    w.kill = [&] {
        ::kill(-pid, SIGKILL);
        ::kill(pid, SIGKILL);  // should it not have made its session yet
        if (launch.uid != 0) endProcessesOf(launch.uid);
    };
    // In a pid namespace of its own, whatever the run started is below its first process (an orphan goes to the
    // namespace's first process, bubblewrap's): the tree is all of it, and no look at every process of the machine
    // is needed. Otherwise, with a user of its own, every process of that user wherever it went.
    w.usage = [&] { return usageOf(pid, launch.ownPids ? 0 : launch.uid); };
    w.ownPeak = [&] { return peakResidentOf(pid); };
    // Sandboxed without bubblewrap, the run's folder is on a disk: its size is watched.
    if (r.isolate && !launch.ownPids) w.folder = r.workDir;
    // Without file rules (limits only), its user may write in the machine's shared temporary folders too.
    if (r.isolate && launch.uid != 0 && !sandboxSupport().bubblewrap && !sandboxSupport().landlock) {
        w.sharedUser = launch.uid;
    }
    supervise(r, w, start, result);
    if (pidfd >= 0) ::close(pidfd);
    return result;
}

}  // namespace simlab::isolation
