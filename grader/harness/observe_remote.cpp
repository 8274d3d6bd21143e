// Observations over pipes to a probe of each test's own. At a test's first question the judge asks simlab, on the
// socket it holds at descriptor 6, for a probe; simlab starts one and hands the judge its ends of two pipes (by
// SCM_RIGHTS): one for requests, one for answers. At the test's end the judge closes them, and the probe, reading
// the end of its requests, exits.
#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>

#include "simlab/harness/observe.h"
#include "transport.h"

namespace simlab::observe::detail {

namespace {

constexpr int kSocketFd = 6;
constexpr std::size_t kDrainCap = 4096;

std::string gTest;
int gRequests = -1, gAnswers = -1;  // this test's probe, once it has one
std::string gPending;               // bytes read past the end of the last answer

// A probe that is gone must end a test with ProcessEnded, not kill the judge with SIGPIPE.
const bool gIgnoreSigpipe = [] {
    std::signal(SIGPIPE, SIG_IGN);
    return true;
}();

// Ask simlab for this test's probe and take its two descriptors.
void connect() {
    if (::fcntl(kSocketFd, F_GETFD) < 0) {
        throw std::runtime_error("this test asks a student's process for observations, which simlab check starts: "
                                 "run the tests through simlab check");
    }
    const std::string message = "probe " + gTest;
    if (::send(kSocketFd, message.data(), message.size(), MSG_NOSIGNAL) != static_cast<ssize_t>(message.size())) {
        throw ProcessEnded("simlab did not start the student's process");
    }
    char byte = 0;
    struct iovec part = {&byte, 1};
    alignas(struct cmsghdr) char control[CMSG_SPACE(2 * sizeof(int))];
    struct msghdr m {};
    m.msg_iov = &part;
    m.msg_iovlen = 1;
    m.msg_control = control;
    m.msg_controllen = sizeof control;
    ssize_t n;
    do {
        n = ::recvmsg(kSocketFd, &m, MSG_CMSG_CLOEXEC);
    } while (n < 0 && errno == EINTR);
    const struct cmsghdr* c = n > 0 ? CMSG_FIRSTHDR(&m) : nullptr;
    if (!c || c->cmsg_type != SCM_RIGHTS || c->cmsg_len != CMSG_LEN(2 * sizeof(int))) {
        throw ProcessEnded("simlab did not start the student's process");
    }
    int fds[2];
    std::memcpy(fds, CMSG_DATA(c), sizeof fds);
    gRequests = fds[0];
    gAnswers = fds[1];
}

}  // namespace

void beginTest(const std::string& test) {
    gTest = test;
    gPending.clear();
}

std::string exchange(const std::string& request, std::size_t limit) {
    if (gRequests < 0) connect();
    for (std::size_t sent = 0; sent < request.size();) {
        const ssize_t n = ::write(gRequests, request.data() + sent, request.size() - sent);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw ProcessEnded("the student's process ended before it was asked");
        sent += static_cast<std::size_t>(n);
    }
    char buffer[65536];
    for (;;) {
        const std::size_t end = gPending.find('\n');
        if (end != std::string::npos) {
            std::string line = gPending.substr(0, end);
            gPending.erase(0, end + 1);
            return line;
        }
        if (gPending.size() > limit) {
            throw BadReport("an answer longer than " + std::to_string(limit >> 20) + " MiB, the rubric's limit");
        }
        const ssize_t n = ::read(gAnswers, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            throw ProcessEnded(gPending.empty() ? "the student's process ended before it answered"
                                                : "the student's process ended in the middle of an answer");
        }
        gPending.append(buffer, static_cast<std::size_t>(n));
    }
}

std::string drain() {
    if (gRequests < 0) return "";
    ::close(gRequests);  // the probe reads the end of its requests and exits
    std::string extra = gPending.substr(0, kDrainCap);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    char buffer[4096];
    while (extra.size() < kDrainCap) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) break;
        struct pollfd p = {gAnswers, POLLIN, 0};
        if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) break;
        const ssize_t n = ::read(gAnswers, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        extra.append(buffer, std::min<std::size_t>(static_cast<std::size_t>(n), kDrainCap - extra.size()));
    }
    ::close(gAnswers);
    gRequests = gAnswers = -1;
    gPending.clear();
    return extra;
}

}  // namespace simlab::observe::detail
