// A submission's probe server (TestServer): simlab-probe-host started once in the sandbox, asked on a socket to
// fork each test's probe, which it watches as it watches any sandboxed run.
#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "internal.h"
#include "simlab/isolation/host_protocol.h"

namespace simlab::isolation {

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
    folder_ = server.workDir;
    server.passFds.push_back({host::kServerFd, ends[1]});
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
bool nextEvent(int fd, host::TestEvent& event, Clock::time_point deadline) {
    for (;;) {
        struct pollfd p = {fd, POLLIN, 0};
        const int n = ::poll(&p, 1, 100);
        if (n > 0) {
            const ssize_t got = ::recv(fd, &event, sizeof event, 0);
            if (got < 0 && errno == EINTR) continue;
            return got == static_cast<ssize_t>(sizeof event);
        }
        if (n < 0 && errno != EINTR) return false;
        if (Clock::now() >= deadline || interrupted()) return false;
    }
}

}  // namespace

std::optional<ProcessResult> TestServer::run(ProcessRequest& t) {
    ProcessResult result;
    if (control_ < 0) return std::nullopt;
    if (interrupted()) {
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
        if (target == host::kRequestFd) requests = fd;
        if (target == host::kAnswerFd) answers = fd;
    }
    if (requests < 0 || answers < 0 || t.passFds.size() != 2 ||
        ::socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, notify) != 0 || ::pipe2(out, O_CLOEXEC) != 0 ||
        ::pipe2(report, O_CLOEXEC) != 0) {
        closeOurs();
        return std::nullopt;  // runProcess starts it as a program of its own
    }
    const uid_t uid = freshUser();
    host::StartTest ask;
    ask.uid = uid;
    ask.cpuSeconds = t.limits.cpuSeconds;
    ask.memoryBytes = static_cast<std::uint64_t>(t.limits.memoryMiB) << 20;
    ask.fileBytes = static_cast<std::uint64_t>(t.limits.fileMiB) << 20;
    ask.tasks = static_cast<std::uint64_t>(std::max(1L, t.limits.processes));
    {
        std::lock_guard<std::mutex> guard(lock_);
        std::snprintf(ask.folder, sizeof ask.folder, "test%d", ++tests_);
    }
    static_assert(host::kStartTestFds == 5, "the server takes five descriptors with a test");
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
    host::TestEvent event;
    if (!nextEvent(notify[0], event, start + std::chrono::seconds(60)) || event.kind != host::TestEvent::Started) {
        // The server could not fork, or is gone: the caller starts the probe as a program of its own, with the
        // judge's pipes it still holds.
        closeOurs();
        endProcessesOf(uid);
        return std::nullopt;
    }
    for (const auto& fd : t.passFds) ::close(fd.second);
    t.passFds.clear();
    result.started = true;
    Watched w;
    w.out = out[0];
    w.report = report[0];
    w.wake = notify[0];
    out[0] = report[0] = notify[0] = -1;
    for (int fd : {w.out, w.report}) ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
    // The server's word on the probe's end: the kernel's status of it, and its CPU time. A server gone with its test
    // ended it.
    w.ended = [&](int& status, double& cpuSeconds, long&) {
        if (w.wake < 0) return false;
        struct pollfd e = {w.wake, POLLIN, 0};
        if (::poll(&e, 1, 0) <= 0) return false;
        host::TestEvent said;
        const ssize_t got = ::recv(w.wake, &said, sizeof said, MSG_DONTWAIT);
        if (got < 0 && (errno == EAGAIN || errno == EINTR)) return false;
        const bool told = got == static_cast<ssize_t>(sizeof said) && said.kind == host::TestEvent::Ended;
        if (got > 0 && !told) return false;  // not an end: wait for the next message
        ::close(w.wake);
        w.wake = -1;
        status = told ? said.status : SIGKILL;
        if (told) cpuSeconds = 1e-6 * static_cast<double>(said.cpuMicroseconds);
        return true;
    };
    w.kill = [uid] { endProcessesOf(uid); };
    w.usage = [uid] { return usageOf(0, uid); };
    // Without bubblewrap the test's folder, in the server's, is on a disk: its size is watched.
    if (!sandboxSupport().bubblewrap) w.folder = folder_ + "/" + ask.folder;
    supervise(t, w, start, result);
    if (w.wake >= 0) ::close(w.wake);
    result.leftBehind = endProcessesOf(uid);
    return result;
}

}  // namespace simlab::isolation
