// The probe's entry point: answers the judge's requests, one line each, until the judge closes the channel.
//
// A probe is a shared object - this file, the registry, the lab's observations, the course's support code and the
// student's object - that simlab-probe-host loads as the test's own user, with no capability, under the students'
// system-call filter (grader/isolation/host/probe_host.cpp), and enters at simlab_probe_entry, the one symbol it
// exports.
//
// Descriptors, set up by the engine and the host: 3 carries events to the engine (running out of memory,
// std::terminate with what was in flight, where an exception of the student's was thrown), 4 brings requests from
// the judge, 5 takes answers to it. Student code
// shares this process and can write to any of them; whatever it writes is data the judge and the engine check,
// never a verdict.
#include <dlfcn.h>
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <new>
#include <nlohmann/json.hpp>
#include <string>
#include <typeinfo>
#include <vector>

#include "simlab/isolation/failure_sites.h"
#include "simlab/isolation/host_protocol.h"
#include "simlab/probe/probe.h"

namespace {

using simlab::isolation::host::kAnswerFd;
using simlab::isolation::host::kEventFd;
using simlab::isolation::host::kRequestFd;
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

// Where the exception `caught` was thrown, as the host's throw hook saw it (simlab/isolation/failure_sites.h): the
// probe's frames, innermost first; none where the host does not know (a floor has no host).
std::vector<std::uint64_t> thrownFrom(const std::exception& caught) {
    using simlab::isolation::kMaxFailureFrames;
    static const auto hook =
        reinterpret_cast<simlab::isolation::ThrownFrom>(::dlsym(RTLD_DEFAULT, simlab::isolation::kThrownFromSymbol));
    if (!hook) return {};
    std::uint64_t at[kMaxFailureFrames];
    const int count = hook(dynamic_cast<const void*>(&caught), at, kMaxFailureFrames);
    return count > 0 ? std::vector<std::uint64_t>(at, at + count) : std::vector<std::uint64_t>();
}

// std::terminate: say what was in flight and where it was thrown, then abort as C++ would.
void onTerminate() {
    nlohmann::json event = {{"event", "terminate"}};
    try {
        if (const std::exception_ptr active = std::current_exception()) {
            try {
                std::rethrow_exception(active);
            } catch (const std::exception& e) {
                event["type"] = simlab::probe::typeName(typeid(e));
                event["what"] = e.what();
                const std::vector<std::uint64_t> at = thrownFrom(e);
                if (!at.empty()) event["at"] = at;
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

// An exception of the student's code that became the answer: where it was thrown, told on the event channel for the
// engine to look up. Nothing where the host does not know.
void onStudentThrow(const std::exception& caught, const std::string& type) {
    try {
        const std::vector<std::uint64_t> at = thrownFrom(caught);
        if (at.empty()) return;
        const nlohmann::json event = {{"event", "threw"}, {"type", type}, {"at", at}};
        writeAll(kEventFd, event.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
    } catch (...) {
        // no memory left to say it: the answer still says what was thrown
    }
}

// The channel kept from programs the student's code might execute.
void keepChannel() {
    for (int fd : {kEventFd, kRequestFd, kAnswerFd}) ::fcntl(fd, F_SETFD, FD_CLOEXEC);
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

// Before the student's static initializers (the course's code alone may use priorities): handlers in place, and the
// channel kept.
__attribute__((constructor(101))) void prepare() {
    std::set_new_handler(onOutOfMemory);
    std::set_terminate(onTerminate);
    simlab::probe::reportThrows(onStudentThrow);
    keepChannel();
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int simlab_probe_entry() {
    simlab::probe::seal();
    std::string pending, request;
    while (readRequest(pending, request)) writeAll(kAnswerFd, simlab::probe::answer(request) + "\n");
    // The judge has what it asked for. Leave without running the student's static destructors or atexit
    // handlers (the host ends the process): what they might do no longer concerns the test.
    std::cout.flush();
    std::cerr.flush();
    std::fflush(nullptr);
    return 0;
}
