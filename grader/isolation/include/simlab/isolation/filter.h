// The system-call filters of the sandbox, as the BPF programs seccomp loads (built with libseccomp). Two of them:
//
//  - the tools' filter, for every sandboxed process that runs the course's code or a trusted tool (the compiler,
//    the linker, a judge, a probe's host before it loads the student's code): it refuses with EPERM what could
//    pass notes between students or reach past the sandbox, and allows the rest;
//  - the students' filter, for every process that holds code built from a student's file (a probe, once its host
//    has loaded the student's code; a program built from a student's file): an allow-list of what a simulation
//    needs - memory, threads, clocks, signals, files through the descriptors and folders the sandbox gives - with
//    the tools' refusals still answered EPERM, any ioctl but a terminal's questions answered ENOTTY, and every
//    other call stopping the process with SIGSYS, which the probe's host names (`callName`) on its event channel.
//
// Another architecture's calls end the process under both.
#pragma once

#include <string>
#include <vector>

namespace simlab::isolation::filter {

/// The tools' filter; empty where libseccomp does not know this machine.
const std::string& toolProgram();

/// The students' filter. `allowExec`: a program started by exec needs execve to start (and may then run others);
/// a probe's host installs it once it runs, and a probe never execs. Empty where libseccomp does not know this
/// machine.
const std::string& studentProgram(bool allowExec);

/// Loads `program` into the calling thread's process after PR_SET_NO_NEW_PRIVS, on top of any filter already
/// there (seccomp keeps the strictest answer of all). System calls only: safe between fork and exec. False if
/// the kernel refused it or `program` is empty.
bool install(const std::string& program);

/// The calls both filters answer EPERM, by name.
std::vector<std::string> refusedCalls();
/// The calls the students' filter allows outright (execve aside), by name.
std::vector<std::string> allowedCalls();

/// The name of system call `number` on this machine ("sched_setscheduler"), or nullptr. Async-signal-safe once
/// `prepareCallNames` has run (a probe's host calls it before it forks its tests).
const char* callName(long number);
void prepareCallNames();

}  // namespace simlab::isolation::filter
