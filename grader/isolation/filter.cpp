#include "simlab/isolation/filter.h"

#include <linux/filter.h>
#include <linux/seccomp.h>
#include <sched.h>
#include <seccomp.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <mutex>

namespace simlab::isolation::filter {

namespace {

// Refused with EPERM by both filters, whatever their arguments: a program that tries one is told no and goes on.
const char* const kRefused[] = {
    // The kernel keyrings outlive a process: one test could leave a note there for the next.
    "add_key", "request_key", "keyctl",
    // Other processes: their memory, their descriptors, their details.
    "ptrace", "process_vm_readv", "process_vm_writev", "pidfd_getfd", "process_madvise", "kcmp",
    // Namespaces and mounts.
    "unshare", "setns", "mount", "umount2", "pivot_root", "chroot", "move_mount", "open_tree", "fsopen", "fsconfig",
    "fsmount", "fspick", "mount_setattr",
    // System V and POSIX IPC: named objects that outlive a process and are shared by every user of the machine.
    "msgget", "msgsnd", "msgrcv", "msgctl", "semget", "semop", "semtimedop", "semctl", "shmget", "shmat", "shmdt",
    "shmctl", "mq_open", "mq_unlink", "mq_timedsend", "mq_timedreceive", "mq_notify", "mq_getsetattr",
    // The network, and abstract sockets between students: a test talks to simlab over the pipes it is given.
    "socket",
    // Leaving the process group or the session: the whole group is ended when the test ends.
    "setsid", "setpgid",
    // The kernel's own interfaces.
    "perf_event_open", "bpf", "userfaultfd", "io_uring_setup", "io_uring_enter", "io_uring_register", "kexec_load",
    "kexec_file_load", "init_module", "finit_module", "delete_module", "swapon", "swapoff", "reboot", "acct",
    "syslog", "quotactl", "quotactl_fd", "lookup_dcookie", "vhangup", "iopl", "ioperm", "settimeofday",
    "clock_settime", "clock_adjtime", "adjtimex", "open_by_handle_at", "name_to_handle_at", "fanotify_init"};

// Also refused with EPERM by the students' filter: the rest of the socket interface (a probe holds no socket; its
// channels are pipes), the calls a process makes to change who it is - each a question a library may ask and take
// no for - and the disk claimed without writing it (fallocate: gigabytes in a moment, faster than a test's files
// can be looked at; written bytes cost CPU time, which the test's limit bounds).
const char* const kStudentRefused[] = {
    "socketpair", "connect", "bind", "listen", "accept", "accept4", "sendto", "recvfrom", "sendmsg", "recvmsg",
    "sendmmsg", "recvmmsg", "shutdown", "getsockname", "getpeername", "setsockopt", "getsockopt",
    "setuid", "setgid", "setreuid", "setregid", "setresuid", "setresgid", "setfsuid", "setfsgid", "setgroups",
    "capset", "sched_setscheduler", "sched_setparam", "sched_setattr", "setpriority", "ioprio_set",
    "sethostname", "setdomainname", "mknod", "mknodat", "personality", "fallocate"};

// Allowed by the students' filter: what simulations, the C and C++ runtimes and the loader use, traced from
// honest runs of every lab's solution and the corpus's honest submissions (and the sanitizers' runtimes): memory,
// threads, clocks, signals within the process's own user, files through what the sandbox lets it open.
const char* const kAllowed[] = {
    // Memory.
    "brk", "mmap", "munmap", "mremap", "mprotect", "madvise", "msync", "mincore", "mlock", "munlock", "membarrier",
    "get_mempolicy",
    // Files and descriptors (the sandbox decides which files there are).
    "read", "write", "readv", "writev", "pread64", "pwrite64", "preadv", "pwritev", "preadv2", "pwritev2", "open",
    "openat", "openat2", "creat", "close", "close_range", "lseek", "fstat", "stat", "lstat", "newfstatat", "statx",
    "access", "faccessat", "faccessat2", "readlink", "readlinkat", "getdents", "getdents64", "mkdir", "mkdirat",
    "unlink", "unlinkat", "rename", "renameat", "renameat2", "rmdir", "link", "linkat", "symlink", "symlinkat",
    "ftruncate", "truncate", "fsync", "fdatasync", "sync_file_range", "fcntl", "dup", "dup2", "dup3", "pipe",
    "pipe2", "getcwd", "chdir", "fchdir", "umask", "chmod", "fchmod", "fchmodat", "utimensat", "utime", "utimes",
    "futimesat", "statfs", "fstatfs", "fadvise64", "flock", "sendfile", "copy_file_range", "splice",
    "tee", "poll", "ppoll", "select", "pselect6", "epoll_create", "epoll_create1", "epoll_ctl",
    "epoll_wait", "epoll_pwait", "epoll_pwait2", "eventfd", "eventfd2", "timerfd_create", "timerfd_settime",
    "timerfd_gettime", "signalfd", "signalfd4", "readahead", "getxattr", "lgetxattr", "fgetxattr",
    // Processes and threads of its own (clone is below: without new namespaces).
    "fork", "vfork", "exit", "exit_group", "wait4", "waitid", "getpid", "getppid", "gettid", "getuid", "geteuid",
    "getgid", "getegid", "getgroups", "getresuid", "getresgid", "getpgrp", "getpgid", "getsid", "set_tid_address",
    "set_robust_list", "get_robust_list", "rseq", "futex", "futex_waitv", "sched_yield", "sched_getaffinity",
    "sched_setaffinity", "sched_getparam", "sched_getscheduler", "sched_getattr", "sched_get_priority_max",
    "sched_get_priority_min", "sched_rr_get_interval", "getpriority", "prctl", "arch_prctl", "capget",
    "pidfd_open", "pidfd_send_signal",
    // Signals.
    "rt_sigaction", "rt_sigprocmask", "rt_sigreturn", "rt_sigpending", "rt_sigtimedwait", "rt_sigsuspend",
    "rt_sigqueueinfo", "rt_tgsigqueueinfo", "kill", "tgkill", "tkill", "sigaltstack", "pause", "alarm",
    "setitimer", "getitimer", "timer_create", "timer_settime", "timer_gettime", "timer_getoverrun", "timer_delete",
    // Time, limits, the machine.
    "clock_gettime", "clock_getres", "clock_nanosleep", "nanosleep", "gettimeofday", "time", "times", "getrusage",
    "getrlimit", "setrlimit", "prlimit64", "uname", "sysinfo", "getrandom", "getcpu"};

// The questions a program asks of a descriptor that may be a terminal (isatty, the window's size) or a pipe (how
// much it holds), and close-on-exec and non-blocking flags: the ioctls the students' filter allows.
const std::uint64_t kAllowedIoctls[] = {TCGETS, TIOCGWINSZ, TIOCGPGRP, FIONREAD, FIONBIO, FIOCLEX, FIONCLEX};

// New namespaces, and a child made the caller's sibling (CLONE_PARENT: a child of its parent - a probe's server, or
// simlab - that no one of the test waits for).
constexpr std::uint64_t kRefusedCloneFlags[] = {CLONE_NEWUSER, CLONE_NEWNS,     CLONE_NEWPID,  CLONE_NEWNET,
                                                CLONE_NEWIPC,  CLONE_NEWUTS,    CLONE_NEWCGROUP, CLONE_NEWTIME,
                                                CLONE_PARENT};

std::string exported(scmp_filter_ctx ctx) {
    const int fd = static_cast<int>(::syscall(SYS_memfd_create, "simlab-seccomp", MFD_CLOEXEC));
    if (fd < 0) return "";
    std::string program;
    if (seccomp_export_bpf(ctx, fd) == 0 && ::lseek(fd, 0, SEEK_SET) == 0) {
        char buffer[4096];
        for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0;) program.append(buffer, static_cast<std::size_t>(n));
    }
    ::close(fd);
    if (program.size() % sizeof(struct sock_filter) != 0) return "";
    return program;
}

struct Context {
    scmp_filter_ctx ctx;
    explicit Context(std::uint32_t defaultAction) : ctx(seccomp_init(defaultAction)) {}
    ~Context() {
        if (ctx) seccomp_release(ctx);
    }
};

// What both filters share: another architecture's calls end the process; no PR_SET_NO_NEW_PRIVS from libseccomp
// (install sets it, and bubblewrap for its own child); the refusals, the terminal's dangerous ioctls among them;
// clone without a new namespace or CLONE_PARENT (clone3, whose flags a filter cannot read, says it does not exist,
// so that the C library falls back to clone).
bool addCommon(scmp_filter_ctx ctx, bool student) {
    bool ok = seccomp_attr_set(ctx, SCMP_FLTATR_ACT_BADARCH, SCMP_ACT_KILL_PROCESS) == 0;
    ok = ok && seccomp_attr_set(ctx, SCMP_FLTATR_CTL_NNP, 0) == 0;
    auto refuse = [&](const char* name) {
        const int nr = seccomp_syscall_resolve_name(name);
        if (nr != __NR_SCMP_ERROR) ok = ok && seccomp_rule_add(ctx, SCMP_ACT_ERRNO(EPERM), nr, 0) == 0;
    };
    for (const char* name : kRefused) refuse(name);
    if (student) {
        for (const char* name : kStudentRefused) refuse(name);
    }
    // The terminal: typing into its input queue, the Linux console's own requests, taking the console over. An
    // ioctl's request is 32 bits; the mask keeps a request with high bits set from slipping past.
    for (const std::uint64_t request : {TIOCSTI, TIOCLINUX, TIOCCONS}) {
        ok = ok && seccomp_rule_add(ctx, SCMP_ACT_ERRNO(EPERM), SCMP_SYS(ioctl), 1,
                                    SCMP_A1(SCMP_CMP_MASKED_EQ, 0xffffffffULL, request)) == 0;
    }
    ok = ok && seccomp_rule_add(ctx, SCMP_ACT_ERRNO(ENOSYS), SCMP_SYS(clone3), 0) == 0;
    std::uint64_t all = 0;
    for (const std::uint64_t flag : kRefusedCloneFlags) {
        all |= flag;
        ok = ok && seccomp_rule_add(ctx, SCMP_ACT_ERRNO(EPERM), SCMP_SYS(clone), 1,
                                    SCMP_A0(SCMP_CMP_MASKED_EQ, flag, flag)) == 0;
    }
    if (student) {
        ok = ok && seccomp_rule_add(ctx, SCMP_ACT_ALLOW, SCMP_SYS(clone), 1, SCMP_A0(SCMP_CMP_MASKED_EQ, all, 0)) == 0;
    }
    return ok;
}

std::string buildToolProgram() {
    Context c(SCMP_ACT_ALLOW);
    return c.ctx && addCommon(c.ctx, false) ? exported(c.ctx) : "";
}

std::string buildStudentProgram(bool allowExec) {
    Context c(SCMP_ACT_TRAP);
    if (!c.ctx || !addCommon(c.ctx, true)) return "";
    bool ok = true;
    for (const char* name : kAllowed) {
        const int nr = seccomp_syscall_resolve_name(name);
        if (nr != __NR_SCMP_ERROR) ok = ok && seccomp_rule_add(c.ctx, SCMP_ACT_ALLOW, nr, 0) == 0;
    }
    if (allowExec) {
        ok = ok && seccomp_rule_add(c.ctx, SCMP_ACT_ALLOW, SCMP_SYS(execve), 0) == 0;
        ok = ok && seccomp_rule_add(c.ctx, SCMP_ACT_ALLOW, SCMP_SYS(execveat), 0) == 0;
    }
    for (const std::uint64_t request : kAllowedIoctls) {
        ok = ok && seccomp_rule_add(c.ctx, SCMP_ACT_ALLOW, SCMP_SYS(ioctl), 1,
                                    SCMP_A1(SCMP_CMP_MASKED_EQ, 0xffffffffULL, request)) == 0;
    }
    return ok ? exported(c.ctx) : "";
}

// Names by number, for a SIGSYS handler: filled before any test is forked, then only read.
constexpr long kMaxCall = 1024;
std::array<const char*, kMaxCall> gNames{};

}  // namespace

const std::string& toolProgram() {
    static const std::string program = buildToolProgram();
    return program;
}

const std::string& studentProgram(bool allowExec) {
    static const std::string withExec = buildStudentProgram(true), withoutExec = buildStudentProgram(false);
    return allowExec ? withExec : withoutExec;
}

bool install(const std::string& program) {
    if (program.empty()) return false;
    if (::prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0) return false;
    struct sock_fprog filter;
    filter.len = static_cast<unsigned short>(program.size() / sizeof(struct sock_filter));
    filter.filter = reinterpret_cast<struct sock_filter*>(const_cast<char*>(program.data()));
    return ::prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &filter, 0, 0) == 0;
}

std::vector<std::string> refusedCalls() {
    std::vector<std::string> calls(std::begin(kRefused), std::end(kRefused));
    calls.insert(calls.end(), std::begin(kStudentRefused), std::end(kStudentRefused));
    return calls;
}

std::vector<std::string> allowedCalls() { return {std::begin(kAllowed), std::end(kAllowed)}; }

void prepareCallNames() {
    static std::once_flag once;
    std::call_once(once, [] {
        const std::uint32_t arch = seccomp_arch_native();
        for (long nr = 0; nr < kMaxCall; ++nr) {
            // Each name is a string libseccomp allocates; they are kept for the life of the process.
            gNames[static_cast<std::size_t>(nr)] = seccomp_syscall_resolve_num_arch(arch, static_cast<int>(nr));
        }
    });
}

const char* callName(long number) {
    return number >= 0 && number < kMaxCall ? gNames[static_cast<std::size_t>(number)] : nullptr;
}

}  // namespace simlab::isolation::filter
