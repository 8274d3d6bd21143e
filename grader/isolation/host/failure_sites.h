// The probe's host's watches on where a test's student code fails (simlab/isolation/failure_sites.h says what they
// tell, and why the engine treats it as data).
#pragma once

namespace simlab::isolation::host {

/// Before the probe at `probe` (the path the host loads it by) is loaded, in the test's own process: handlers for
/// the signals that end a process, a sampler of its CPU time from half the test's limit (as setLimits set it) and
/// the throw hook, each telling the probe's frames on the event channel. Only system calls and the C++ runtime's
/// unwinder once set up; nothing of the student's is loaded yet.
void watchFailureSites(const char* probe);

/// Tells where the calling thread is, as a crash of `signal`, from a handler of the host's own (the refused system
/// call's). Async-signal-safe; nothing before watchFailureSites.
void tellFailureSite(int signal);

/// From a handler of `signal`: the signal's own end, as if no handler had been there (the engine reads the signal
/// from the kernel). Async-signal-safe. A fault that comes back as the handler returns ends the process the same way.
void endAs(int signal);

}  // namespace simlab::isolation::host
