// Where a test's student code was when it failed: what the probe's process tells the engine of it, as data.
//
// A probe's host (host/failure_sites.cpp, course code) sets three watches before it loads the probe: handlers for
// the signals that end a process (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGTRAP, SIGABRT; and SIGSYS, the filter's),
// a sampler of the process's CPU time from half the test's limit on, and a hook on every C++ throw. Each walks the
// stack with the C++ runtime's unwinder (over the unwind tables every object carries, through Simbody's frames as
// through the student's) and keeps the frames that lie in the probe, innermost first, as addresses in the probe's
// file (of the instruction that faulted, or of the call a frame made). The probe's process tells them on its event
// channel, one line each:
//
//     {"event":"crash","signal":11,"at":[21344,22107]}      a signal is about to end the process
//     {"event":"sample","cpu":2600000,"at":[21344,22107]}   where it was after each tenth of a second of CPU time
//                                                           (the process's CPU time then, in microseconds)
//     {"event":"threw","type":"std::runtime_error","at":[...]}   the course's code caught the student's exception
//     {"event":"terminate",...,"at":[...]}                  where the exception std::terminate ended was thrown
//
// The student's code shares that process and can write anything there, and replace the handlers, so a line says
// nothing the engine must believe: an address is looked up in the probe's line tables by a tool in the sandbox that
// reads the probe as a file and never runs it, only a frame in the student's own file is named, and only beside the
// outcome the kernel gave (the signal that ended the process, the CPU time it used). A student who lies points at
// another line of their own file; one who replaces a handler gets the outcome with no place.
#pragma once

#include <cstdint>

namespace simlab::isolation {

/// The most frames of the probe a line tells.
constexpr int kMaxFailureFrames = 16;

/// The largest address a line may tell: a probe is far smaller.
constexpr std::uint64_t kMaxFailureAddress = std::uint64_t{1} << 40;

/// The function a probe's host exports for the probe's course code: where the exception `object` (the thrown
/// object's address) was thrown, as up to `capacity` addresses in the probe, innermost first, into `at`; returns
/// how many (0: not known, say because it was not thrown on this thread since).
///     int simlab_thrown_from(const void* object, std::uint64_t* at, int capacity);
constexpr const char* kThrownFromSymbol = "simlab_thrown_from";
using ThrownFrom = int (*)(const void* object, std::uint64_t* at, int capacity);

}  // namespace simlab::isolation
