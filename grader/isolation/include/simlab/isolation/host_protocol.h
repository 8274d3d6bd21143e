// How a sandboxed process is made what it runs as - its limits, its user, no capability - and the messages between
// the engine and a probe's host serving a submission's tests (simlab-probe-host --serve). Shared by the engine,
// which sets up each process it starts between fork and exec, and by the host, which forks each test from one
// started program.
//
// Everything here is a system call and nothing else: safe between vfork (or fork) and exec, and in a child of a
// process that may have had other threads.
#pragma once

#include <linux/capability.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>

// Built with AddressSanitizer (SIMLAB_SANITIZE), by GCC or by clang.
#if defined(__SANITIZE_ADDRESS__)
#define SIMLAB_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SIMLAB_ADDRESS_SANITIZER 1
#endif
#endif

namespace simlab::isolation::host {

/// Empties the calling process's capability bounding set, ambient set and inheritable set, keeping CAP_SETUID and
/// CAP_SETGID in its permitted and effective sets (for becomeUser, which then clears them): nothing it runs, or
/// anything that runs it, can gain a capability again. Needs CAP_SETPCAP to empty the bounding set (root has it;
/// so does a probe's server); without it the bounding set is left as it is. False if the kernel refused.
inline bool leaveCapabilities() {
    const bool mayDrop = ::prctl(PR_CAPBSET_READ, CAP_SETPCAP, 0, 0, 0) == 1;
    for (int cap = 0; mayDrop && cap <= 63; ++cap) ::prctl(PR_CAPBSET_DROP, cap, 0, 0, 0);
    ::prctl(PR_CAP_AMBIENT, PR_CAP_AMBIENT_CLEAR_ALL, 0, 0, 0);
    struct __user_cap_header_struct header = {_LINUX_CAPABILITY_VERSION_3, 0};
    struct __user_cap_data_struct caps[2] = {};
    if (::syscall(SYS_capget, &header, caps) != 0) return false;
    const std::uint32_t keep = (1U << CAP_SETUID) | (1U << CAP_SETGID);
    caps[0].effective &= keep;
    caps[0].permitted &= keep;
    caps[0].inheritable = 0;
    caps[1].effective = caps[1].permitted = caps[1].inheritable = 0;
    return ::syscall(SYS_capset, &header, caps) == 0;
}

/// True when the calling process holds no capability at all: none effective, permitted, inheritable or ambient.
inline bool holdsNoCapability() {
    struct __user_cap_header_struct header = {_LINUX_CAPABILITY_VERSION_3, 0};
    struct __user_cap_data_struct caps[2] = {};
    if (::syscall(SYS_capget, &header, caps) != 0) return false;
    for (const auto& c : caps) {
        if (c.effective || c.permitted || c.inheritable) return false;
    }
    for (int cap = 0; cap <= 63; ++cap) {
        if (::prctl(PR_CAP_AMBIENT, PR_CAP_AMBIENT_IS_SET, cap, 0, 0) == 1) return false;
    }
    return true;
}

/// Makes the calling process `uid` (and group `uid`, with no supplementary groups) by the system calls themselves:
/// the C library's wrappers would change the ids of every thread of the process. A process that was root loses
/// every capability as it does (no id of it stays 0). False if the kernel refused.
inline bool becomeUser(uid_t uid) {
#if defined(SYS_setresuid32)  // where the plain calls take 16-bit ids (32-bit x86 and ARM)
    return ::syscall(SYS_setgroups32, 0, nullptr) == 0 && ::syscall(SYS_setresgid32, uid, uid, uid) == 0 &&
           ::syscall(SYS_setresuid32, uid, uid, uid) == 0;
#else
    return ::syscall(SYS_setgroups, 0, nullptr) == 0 && ::syscall(SYS_setresgid, uid, uid, uid) == 0 &&
           ::syscall(SYS_setresuid, uid, uid, uid) == 0;
#endif
}

/// A test's limits, each process's own: the CPU time (SIGXCPU at the limit plus two seconds, so that the engine,
/// which adds up the test's processes and names the outcome, stops it first; SIGKILL a second later), the address
/// space, the size of a file, the tasks of its user (0: left alone), no core files, 256 descriptors.
inline void setLimits(double cpuSeconds, std::uint64_t memoryBytes, std::uint64_t fileBytes, std::uint64_t tasks) {
    auto set = [](int resource, rlim_t value) {
        const struct rlimit limit = {value, value};
        ::setrlimit(resource, &limit);
    };
    const rlim_t cpu = static_cast<rlim_t>(std::ceil(cpuSeconds)) + 2;
    const struct rlimit cpuLimit = {cpu, cpu + 1};
    ::setrlimit(RLIMIT_CPU, &cpuLimit);
#if defined(SIMLAB_ADDRESS_SANITIZER)
    // A sanitizer build (SIMLAB_SANITIZE) maps terabytes of shadow memory at start: its address space cannot be
    // limited. The engine's own account of the memory a test's processes hold still stops a test that takes more.
    (void)memoryBytes;
#else
    set(RLIMIT_AS, static_cast<rlim_t>(memoryBytes));
#endif
    set(RLIMIT_FSIZE, static_cast<rlim_t>(fileBytes));
    if (tasks > 0) set(RLIMIT_NPROC, static_cast<rlim_t>(tasks));
    set(RLIMIT_CORE, 0);
    set(RLIMIT_NOFILE, 256);
}

/// A probe's server reads its requests on this descriptor.
constexpr int kServerFd = 7;

/// A probe's descriptors: 3 carries events to the engine (running out of memory, std::terminate with what was in
/// flight, a system call the filter refused), 4 brings the judge's requests, 5 takes the answers to it.
constexpr int kEventFd = 3, kRequestFd = 4, kAnswerFd = 5;

/// "Start a test's probe": what the engine sends the server on kServerFd, with five descriptors (SCM_RIGHTS): the
/// test's own socket to the engine (the server answers there), its output (descriptors 1 and 2 of the probe), its
/// event channel (3), the judge's requests (4) and the answers to the judge (5).
struct StartTest {
    std::uint32_t magic = 0x73696d6c;  ///< "siml": a message of this protocol
    std::uint32_t uid = 0;             ///< the test's user, never used before: the probe becomes it
    double cpuSeconds = 0;
    std::uint64_t memoryBytes = 0, fileBytes = 0, tasks = 0;
    char folder[48] = {};              ///< the test's own folder, made by the probe (as its user) in the server's,
                                       ///< its HOME and TMPDIR
};
constexpr int kStartTestFds = 5;

/// What the server says of a test's probe, on the test's socket: that it started (its process id in the server's
/// view), that it could not (`error`, an errno), and, once it is gone, how it ended and the CPU time it and the
/// children it waited for used.
struct TestEvent {
    enum Kind : std::uint32_t { Started = 1, Failed = 2, Ended = 3 };
    std::uint32_t kind = 0;
    std::int32_t pid = 0;
    std::int32_t status = 0;  ///< Ended: as waitpid gives it; Failed: the errno
    std::int32_t pad = 0;
    std::int64_t cpuMicroseconds = 0;
};

}  // namespace simlab::isolation::host
