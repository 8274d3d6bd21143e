// The probe's main: answers the judge's requests, one line each, until the judge closes the channel.
//
// Descriptors, set up by the engine: 3 carries events to the engine (running out of memory, std::terminate with
// what was in flight), 4 brings requests from the judge, 5 takes answers to it. Student code shares this process
// and can write to any of them; whatever it writes is data the judge and the engine check, never a verdict.
//
// Started with --serve, the program is a probe's server instead (engine::TestServer): from the course's first
// constructor, before any of the student's code - static initializers included - has run, it forks each test's
// probe on the engine's request; the probe becomes the test's own user, then goes on to the student's static
// initializers and main. The server itself never runs the student's code.
#include <fcntl.h>
#include <linux/capability.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iostream>
#include <new>
#include <nlohmann/json.hpp>
#include <string>
#include <typeinfo>
#include <vector>

#include "simlab/probe.h"
#include "simlab/test_process.h"

namespace {

constexpr int kEventFd = 3, kRequestFd = 4, kAnswerFd = 5;
constexpr std::size_t kRequestLimit = 1 << 20;  // the judge's requests are small

void writeAll(int fd, const std::string& text) {
    for (std::size_t sent = 0; sent < text.size();) {
        const ssize_t n = ::write(fd, text.data() + sent, text.size() - sent);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return;
        sent += static_cast<std::size_t>(n);
    }
}

// Out of memory: say so, then stop. No allocation here.
void onOutOfMemory() {
    static const char line[] = "{\"event\":\"memory\"}\n";
    (void)!::write(kEventFd, line, sizeof line - 1);
    std::_Exit(137);
}

// std::terminate: say what was in flight, then abort as C++ would.
void onTerminate() {
    nlohmann::json event = {{"event", "terminate"}};
    try {
        if (const std::exception_ptr active = std::current_exception()) {
            try {
                std::rethrow_exception(active);
            } catch (const std::exception& e) {
                event["type"] = simlab::probe::typeName(typeid(e));
                event["what"] = e.what();
            } catch (...) {
                event["type"] = "something that is not a std::exception";
            }
        }
        writeAll(kEventFd, event.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
    } catch (...) {
        static const char line[] = "{\"event\":\"terminate\"}\n";
        (void)!::write(kEventFd, line, sizeof line - 1);
    }
    std::abort();
}

// The channel kept from programs the student's code might execute.
void keepChannel() {
    for (int fd : {kEventFd, kRequestFd, kAnswerFd}) ::fcntl(fd, F_SETFD, FD_CLOEXEC);
}


// ---- the server ------------------------------------------------------------------------------------------------

// A test's probe that cannot become what the test needs says so where the engine reads it, and goes.
[[noreturn]] void cannot(const char* what) {
    (void)!::write(2, what, std::strlen(what));
    ::_exit(127);
}

// In the forked child: the test's descriptors in place (output on 1 and 2, then 3, 4, 5), nothing else of the
// server's open, the test's limits, the test's user (every capability goes with root), a parent-death signal,
// and a folder of its own. Nothing of the student's has run in this process, and nothing runs before all of this
// is done.
void becomeTest(const simlab::test_process::StartTest& test, const int (&fds)[5], pid_t server) {
    sigset_t none;
    ::sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    int moved[5];
    for (int i = 0; i < 5; ++i) moved[i] = ::fcntl(fds[i], F_DUPFD, 16);
    ::close(moved[0]);  // the test's socket is the server's business
    ::dup2(moved[1], 1);
    ::dup2(moved[1], 2);
    ::dup2(moved[2], kEventFd);
    ::dup2(moved[3], kRequestFd);
    ::dup2(moved[4], kAnswerFd);
    ::close_range(kAnswerFd + 1, ~0U, 0);
    simlab::test_process::setLimits(test.cpuSeconds, test.memoryBytes, test.fileBytes, test.tasks);
    // The test's folder, made as the test's user through the server's group, which alone may add to the server's
    // folder (root's, mode 0731): the test's user can pass through it to its own folder, and neither list nor add to
    // it, so nothing one test writes is where another can reach it.
    char folder[sizeof test.folder + 1] = {};
    std::memcpy(folder, test.folder, sizeof test.folder);
    if (test.uid == 0 || !folder[0] || std::strchr(folder, '/') || folder[0] == '.') {
        cannot("simlab: cannot enter the test's working directory\n");
    }
    ::syscall(SYS_setfsuid, test.uid);
    const bool made = ::mkdir(folder, 0700) == 0;
    ::syscall(SYS_setfsuid, 0);
    if (!made) cannot("simlab: cannot enter the test's working directory\n");
    if (!simlab::test_process::becomeUser(test.uid)) cannot("simlab: cannot switch to the test's user\n");
    struct __user_cap_header_struct header = {_LINUX_CAPABILITY_VERSION_3, 0};
    struct __user_cap_data_struct caps[2] = {};
    if (::syscall(SYS_capget, &header, caps) != 0 || caps[0].effective || caps[0].permitted || caps[1].effective ||
        caps[1].permitted) {
        cannot("simlab: cannot leave root's capabilities behind\n");
    }
    // As a program started for the test would be: its /proc files its own, dying with the server.
    ::prctl(PR_SET_DUMPABLE, 1, 0, 0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL, 0, 0, 0);
    if (::getppid() != server) ::_exit(127);
    char here[4096];
    if (::chdir(folder) != 0 || !::getcwd(here, sizeof here)) cannot("simlab: cannot enter the test's working directory\n");
    // Its files go to its folder: /tmp is no test's to write.
    ::setenv("HOME", here, 1);
    ::setenv("TMPDIR", here, 1);
    keepChannel();
}

// Serves the engine on kServerFd: a test's probe forked for each request, its start and its end told on the
// test's own socket. Returns only in a test's probe, ready to answer; the server itself leaves when the engine
// closes its end.
void serveTests() {
    using simlab::test_process::StartTest;
    using simlab::test_process::TestEvent;
    const pid_t server = ::getpid();
    struct Running {
        pid_t pid;
        int pidfd, notify;
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
        std::vector<struct pollfd> watched = {{simlab::test_process::kServerFd, POLLIN, 0}};
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
        const ssize_t got = ::recvmsg(simlab::test_process::kServerFd, &m, MSG_CMSG_CLOEXEC);
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
            becomeTest(test, fds, server);
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
        }
        if (pid > 0 && pidfd >= 0) {
            running.push_back({pid, pidfd, fds[0]});
        } else {
            ::close(fds[0]);
        }
    }
}

// One request line; false at the end of the channel.
bool readRequest(std::string& pending, std::string& line) {
    char buffer[4096];
    for (;;) {
        const std::size_t end = pending.find('\n');
        if (end != std::string::npos) {
            line = pending.substr(0, end);
            pending.erase(0, end + 1);
            return true;
        }
        if (pending.size() > kRequestLimit) return false;
        const ssize_t n = ::read(kRequestFd, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        pending.append(buffer, static_cast<std::size_t>(n));
    }
}

// Before any static initializer of the student's (the course's code alone may use priorities; the libraries are
// initialized by now): handlers in place, and the channel kept. A server serves from here, so that none of the
// student's code - not even a static initializer - ever runs in it: each test's probe returns from serveTests and
// goes on to them, as the test's user.
__attribute__((constructor(101))) void prepare(int argc, char** argv, char**) {
    std::set_new_handler(onOutOfMemory);
    std::set_terminate(onTerminate);
    if (argc == 2 && argv && std::strcmp(argv[1], "--serve") == 0) serveTests();
    keepChannel();
}

}  // namespace

int main() {
    simlab::probe::seal();
    std::string pending, request;
    while (readRequest(pending, request)) writeAll(kAnswerFd, simlab::probe::answer(request) + "\n");
    // The judge has what it asked for. Leave without running the student's static destructors or atexit
    // handlers: what they might do no longer concerns the test.
    std::cout.flush();
    std::cerr.flush();
    std::fflush(nullptr);
    ::_exit(0);
}
