// How a test's process is made what it runs as: its limits, its user, and the message that asks a probe's server
// to start one. Shared by the engine, which sets up each process it starts between fork and exec, and by the
// probe's server (probe_main.cpp), which forks each test's probe from one started program.
//
// Everything here is a system call and nothing else: safe between vfork (or fork) and exec, and in a child of a
// process that may have had other threads.
#pragma once

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>

namespace simlab::test_process {

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
#if defined(__SANITIZE_ADDRESS__)
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

}  // namespace simlab::test_process
