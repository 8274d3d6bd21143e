// simlab-probe-host: the program every probe runs in. It holds none of a student's code. It is linked against the
// libraries a probe uses (Simbody, the C++ runtime), so that they are loaded once; then, as the test's own user,
// with no capability and under the students' system-call filter, it loads the submission's probe - a shared
// object of the course's probe side and the student's object, which the engine links for each submission - and
// hands it the test. The student's code (its static initializers, ifunc resolvers, constructors of any priority,
// symbols it defines) runs from that load on, and never before.
//
//   simlab-probe-host PROBE.so           one test's probe; the engine starts it as the test's own user
//   simlab-probe-host --serve PROBE.so   a submission's server (engine::TestServer): it keeps CAP_SETUID,
//                                        CAP_SETGID and CAP_SETPCAP alone and, for each test the engine asks for,
//                                        forks a child that drops them, becomes the test's user and loads its
//                                        own copy of PROBE.so (which only the server may read)
//   simlab-probe-host --exec PROGRAM...  a program built from a student's file (a study of one): loads the
//                                        students' filter, execs allowed, then runs PROGRAM - where the sandbox
//                                        could not load that filter before the user was handed over (bubblewrap
//                                        run as root, whose setpriv changes users)
//
// Descriptors (host_protocol.h): 3 events to the engine, 4 the judge's requests, 5 the answers; the server reads
// the engine's requests on 7. What the server says of a probe (that it started, how it ended) comes from the
// kernel (waitpid), never from the probe. Where the student's code was when a test fails, the host's watches tell on
// 3, as data (failure_sites.cpp).
#include <dlfcn.h>
#include <fcntl.h>
#include <ftw.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/ucontext.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "failure_sites.h"
#include "simlab/isolation/filter.h"
#include "simlab/isolation/host_protocol.h"

namespace {

namespace host = simlab::isolation::host;
namespace filter = simlab::isolation::filter;

// A probe that cannot become what its test needs says so where the engine reads it ("simlab: cannot ..."), and goes.
[[noreturn]] void cannot(const char* what, const char* detail = nullptr) {
    (void)!::write(2, what, std::strlen(what));
    if (detail) {
        (void)!::write(2, ": ", 2);
        (void)!::write(2, detail, std::strlen(detail));
    }
    (void)!::write(2, "\n", 1);
    ::_exit(127);
}

// Appends `text` to the fixed buffer `line` (of `size`, with `used` bytes in it); no allocation.
void append(char* line, std::size_t size, std::size_t& used, const char* text) {
    for (; *text && used + 1 < size; ++text) line[used++] = *text;
    line[used] = '\0';
}

// A system call the students' filter refuses stops the probe with SIGSYS: named on the event channel first, so
// that the test's reason says which call it was. Only async-signal-safe calls; the names were looked up before.
void onRefusedCall(int, siginfo_t* info, void* context) {
    char line[160];
    std::size_t used = 0;
    append(line, sizeof line, used, "{\"event\":\"refused\",\"call\":\"");
    const char* name = filter::callName(info->si_syscall);
    if (name) {
        append(line, sizeof line, used, name);
    } else {
        char number[24];
        std::snprintf(number, sizeof number, "%d", info->si_syscall);  // no allocation for an int
        append(line, sizeof line, used, "system call ");
        append(line, sizeof line, used, number);
    }
#if defined(__x86_64__)
    // For an ioctl, its request: which question of a device it was.
    if (name && std::strcmp(name, "ioctl") == 0 && context) {
        const auto* uc = static_cast<const ucontext_t*>(context);
        char request[32];
        std::snprintf(request, sizeof request, " 0x%llx",
                      static_cast<unsigned long long>(uc->uc_mcontext.gregs[REG_RSI]) & 0xffffffffULL);
        append(line, sizeof line, used, request);
    }
#else
    (void)context;
#endif
    append(line, sizeof line, used, "\"}\n");
    (void)!::write(host::kEventFd, line, used);
    host::tellFailureSite(SIGSYS);
    // Then as SIGSYS would: the engine sees the signal.
    host::endAs(SIGSYS);
    ::_exit(128 + SIGSYS);
}

// The probe: the students' filter, then the submission's shared object, then its entry point. Never returns. A
// test's own copy (`ownCopy`) goes once it is loaded: the folder's space is the test's.
[[noreturn]] void runProbe(const char* probe, bool ownCopy) {
    struct sigaction refused {};
    refused.sa_sigaction = onRefusedCall;
    refused.sa_flags = SA_SIGINFO;
    ::sigemptyset(&refused.sa_mask);
    ::sigaction(SIGSYS, &refused, nullptr);
    host::watchFailureSites(probe);
    const std::string& program = filter::studentProgram(false);
    if (!program.empty() && !filter::install(program)) cannot("simlab: cannot load the probe's system-call filter");
    void* loaded = ::dlopen(probe, RTLD_NOW | RTLD_LOCAL);
    if (!loaded) cannot("simlab: cannot load the probe", ::dlerror());
    if (ownCopy) ::unlink(probe);
    using Entry = int (*)();
    const auto entry = reinterpret_cast<Entry>(::dlsym(loaded, "simlab_probe_entry"));
    if (!entry) cannot("simlab: the probe has no entry point");
    ::_exit(entry());
}

// The test's own copy of the probe, `probe` (the server's descriptor of it, which only the server's user may
// read), written into the test's folder as the test's user (the file system's user: setfsuid) and its alone. The
// probe on disk is thus no other user's to read, and one test's copy is no other test's.
bool copyProbe(int probe, const char* folder, uid_t uid) {
    char path[128] = {};
    std::size_t used = 0;
    append(path, sizeof path, used, folder);
    append(path, sizeof path, used, "/probe.so");
    ::syscall(SYS_setfsuid, uid);
    const int copy = ::open(path, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0400);
    ::syscall(SYS_setfsuid, 0);
    if (copy < 0) return false;
    bool ok = true;
    char buffer[65536];
    for (off_t at = 0;;) {
        const ssize_t got = ::pread(probe, buffer, sizeof buffer, at);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) {
            ok = got == 0;
            break;
        }
        for (ssize_t written = 0; written < got;) {
            const ssize_t n = ::write(copy, buffer + written, static_cast<std::size_t>(got - written));
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) return ::close(copy), false;
            written += n;
        }
        at += got;
    }
    return ::close(copy) == 0 && ok;
}

// In a server's forked child: the test's descriptors in place (output on 1 and 2, then 3, 4, 5), nothing else of
// the server's open, the test's limits, no capability left to regain, the test's user, a parent-death signal, and
// a folder of its own with its copy of the probe. Nothing of the student's is in this process yet.
void becomeTest(const host::StartTest& test, const int (&fds)[5], pid_t server, int probe) {
    sigset_t none;
    ::sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    int moved[5];
    for (int i = 0; i < 5; ++i) moved[i] = ::fcntl(fds[i], F_DUPFD, 16);
    ::close(moved[0]);  // the test's socket is the server's business
    ::dup2(moved[1], 1);
    ::dup2(moved[1], 2);
    ::dup2(moved[2], host::kEventFd);
    ::dup2(moved[3], host::kRequestFd);
    ::dup2(moved[4], host::kAnswerFd);
    host::setLimits(test.cpuSeconds, test.memoryBytes, test.fileBytes, test.tasks);
    // The test's folder, made as the test's user through the server's group, which alone may add to the server's
    // folder (root's, mode 0731): the test's user can pass through it to its own folder, and neither list nor add
    // to it, so nothing one test writes is where another can reach it.
    char folder[sizeof test.folder + 1] = {};
    std::memcpy(folder, test.folder, sizeof test.folder);
    if (test.uid == 0 || !folder[0] || std::strchr(folder, '/') || folder[0] == '.') {
        cannot("simlab: cannot enter the test's working directory");
    }
    ::syscall(SYS_setfsuid, test.uid);
    const bool made = ::mkdir(folder, 0700) == 0;
    ::syscall(SYS_setfsuid, 0);
    if (!made) cannot("simlab: cannot enter the test's working directory");
    if (!copyProbe(probe, folder, test.uid)) cannot("simlab: cannot copy the probe into the test's folder");
    ::close_range(host::kAnswerFd + 1, ~0U, 0);
    if (!host::leaveCapabilities()) cannot("simlab: cannot leave the server's capabilities behind");
    if (!host::becomeUser(test.uid)) cannot("simlab: cannot switch to the test's user");
    if (!host::holdsNoCapability() || ::prctl(PR_CAPBSET_READ, CAP_SETUID, 0, 0, 0) == 1) {
        cannot("simlab: cannot leave root's capabilities behind");
    }
    // As a program started for the test would be: its /proc files its own, dying with the server.
    ::prctl(PR_SET_DUMPABLE, 1, 0, 0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL, 0, 0, 0);
    if (::getppid() != server) ::_exit(127);
    char here[4096];
    if (::chdir(folder) != 0 || !::getcwd(here, sizeof here)) cannot("simlab: cannot enter the test's working directory");
    // Its files go to its folder: /tmp is no test's to write.
    ::setenv("HOME", here, 1);
    ::setenv("TMPDIR", here, 1);
}

// A test's folder, once its probe has ended, removed as the test's own user (the file system's user: setfsuid) -
// the server holds no capability over files, so nothing a test's process might swap into it while it goes (a
// link, say) lets this remove more than that user may - and no link followed: the folders the tests share are
// the space of those still running.
int removeEntry(const char* path, const struct stat*, int type, struct FTW*) {
    if (type == FTW_DP) (void)::rmdir(path);
    else (void)::unlink(path);
    return 0;  // what cannot go stays; the walk goes on
}
void removeFolder(const char* folder, uid_t uid) {
    if (uid == 0 || !folder[0] || std::strchr(folder, '/') || folder[0] == '.') return;
    ::syscall(SYS_setfsuid, uid);
    ::nftw(folder, removeEntry, 16, FTW_DEPTH | FTW_PHYS | FTW_MOUNT);
    ::syscall(SYS_setfsuid, 0);
}

// Serves the engine on kServerFd: a test's probe forked for each request, its start and its end told on the
// test's own socket. Returns only in a test's child, ready to load the probe; the server itself leaves when the
// engine closes its end.
void serveTests(int probe) {
    using host::StartTest;
    using host::TestEvent;
    const pid_t server = ::getpid();
    struct Running {
        pid_t pid;
        int pidfd, notify;
        uid_t uid;
        char folder[sizeof(StartTest::folder) + 1];
    };
    std::vector<Running> running;
    auto tell = [](int fd, TestEvent event) { (void)!::send(fd, &event, sizeof event, MSG_NOSIGNAL); };
    // How a test's probe ended, as the kernel says: its status, and the CPU time of it and what it waited for.
    auto endedEvent = [](pid_t pid, int status, const struct rusage& usage) {
        TestEvent ended;
        ended.kind = TestEvent::Ended;
        ended.pid = pid;
        ended.status = status;
        ended.cpuMicroseconds = (usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) * 1000000LL + usage.ru_utime.tv_usec +
                                usage.ru_stime.tv_usec;
        return ended;
    };
    for (;;) {
        std::vector<struct pollfd> watched = {{host::kServerFd, POLLIN, 0}};
        for (const Running& r : running) watched.push_back({r.pidfd, POLLIN, 0});
        if (::poll(watched.data(), watched.size(), -1) < 0) {
            if (errno == EINTR) continue;
            ::_exit(3);
        }
        for (std::size_t i = running.size(); i-- > 0;) {
            if (!(watched[i + 1].revents & (POLLIN | POLLHUP))) continue;
            int status = 0;
            struct rusage usage {};
            if (::wait4(running[i].pid, &status, WNOHANG, &usage) != running[i].pid) continue;
            tell(running[i].notify, endedEvent(running[i].pid, status, usage));
            ::close(running[i].notify);
            ::close(running[i].pidfd);
            removeFolder(running[i].folder, running[i].uid);
            running.erase(running.begin() + static_cast<std::ptrdiff_t>(i));
        }
        if (!(watched[0].revents & (POLLIN | POLLHUP | POLLERR))) continue;
        StartTest test;
        int fds[5] = {-1, -1, -1, -1, -1};
        alignas(struct cmsghdr) char control[CMSG_SPACE(sizeof fds)] = {};
        struct iovec part = {&test, sizeof test};
        struct msghdr m {};
        m.msg_iov = &part;
        m.msg_iovlen = 1;
        m.msg_control = control;
        m.msg_controllen = sizeof control;
        const ssize_t got = ::recvmsg(host::kServerFd, &m, MSG_CMSG_CLOEXEC);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) ::_exit(0);  // the engine is done: the tests still running die with the server
        const struct cmsghdr* c = CMSG_FIRSTHDR(&m);
        const bool whole = c && c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_RIGHTS &&
                           c->cmsg_len == CMSG_LEN(sizeof fds) && !(m.msg_flags & (MSG_CTRUNC | MSG_TRUNC));
        if (whole) std::memcpy(fds, CMSG_DATA(c), sizeof fds);
        if (!whole || got != static_cast<ssize_t>(sizeof test) || test.magic != StartTest{}.magic) {
            for (int fd : fds) {
                if (fd >= 0) ::close(fd);
            }
            continue;
        }
        const pid_t pid = ::fork();
        if (pid == 0) {
            becomeTest(test, fds, server, probe);
            return;
        }
        const int pidfd = pid > 0 ? static_cast<int>(::syscall(SYS_pidfd_open, pid, 0)) : -1;
        TestEvent said;
        said.kind = pid > 0 ? TestEvent::Started : TestEvent::Failed;
        said.pid = pid;
        said.status = pid > 0 ? 0 : errno;
        tell(fds[0], said);
        for (int i = 1; i < 5; ++i) ::close(fds[i]);
        if (pid > 0 && pidfd < 0) {  // no pidfd: this test is waited for at once
            int status = 0;
            struct rusage usage {};
            ::wait4(pid, &status, 0, &usage);
            tell(fds[0], endedEvent(pid, status, usage));
            char folder[sizeof test.folder + 1] = {};
            std::memcpy(folder, test.folder, sizeof test.folder);
            removeFolder(folder, test.uid);
        }
        if (pid > 0 && pidfd >= 0) {
            Running r{pid, pidfd, fds[0], test.uid, {}};
            std::memcpy(r.folder, test.folder, sizeof test.folder);
            running.push_back(r);
        } else {
            ::close(fds[0]);
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    const bool serve = argc == 3 && std::strcmp(argv[1], "--serve") == 0;
    const bool exec = argc >= 3 && std::strcmp(argv[1], "--exec") == 0;
    if (!serve && !exec && argc != 2) {
        std::fprintf(stderr, "usage: simlab-probe-host [--serve] PROBE.so | --exec PROGRAM [ARGUMENTS...] (simlab "
                             "starts it; it is not run by hand)\n");
        return 2;
    }
    if (exec) {
        if (!host::holdsNoCapability() || ::getuid() == 0 || ::geteuid() == 0) {
            cannot("simlab: a student's program runs as a user of its own, never as root or with a capability");
        }
        const std::string& program = filter::studentProgram(true);
        if (!program.empty() && !filter::install(program)) cannot("simlab: cannot load the program's system-call filter");
        ::execv(argv[2], argv + 2);
        cannot("simlab: cannot execute the program", ::strerrordesc_np(errno));
    }
    const char* probe = argv[argc - 1];
    // What a test's child will need, made before any fork: the filter's program and the calls' names.
    filter::prepareCallNames();
    if (filter::studentProgram(false).empty() && !filter::toolProgram().empty()) {
        cannot("simlab: cannot make the probe's system-call filter");
    }
    if (serve) {
        // Read once, as the server's user: each test's child copies it into its own folder.
        // (Kept above the descriptors a test's child puts in place.)
        const int opened = ::open(probe, O_RDONLY | O_CLOEXEC);
        const int image = opened < 0 ? -1 : ::fcntl(opened, F_DUPFD_CLOEXEC, 64);
        if (image < 0) cannot("simlab: cannot read the probe", ::strerrordesc_np(errno));
        ::close(opened);
        serveTests(image);  // returns in a test's child, whose folder holds its copy
        probe = "./probe.so";
    } else if (!host::holdsNoCapability() || ::getuid() == 0 || ::geteuid() == 0) {
        // Run alone, the host is already the test's user: it never loads a student's code with privilege.
        cannot("simlab: a probe runs as a user of its own, never as root or with a capability");
    }
    runProbe(probe, serve);
}
