// sandbox-try: tries, from inside simlab's sandbox, what a hostile submission would, and says what became of each
// try, one line each ("keyring: refused"). sandbox-check runs it in the sandbox and compares with what each rule
// promises. Where it can, a call is made with an argument the kernel itself would reject with another error
// (EFAULT, EINVAL, EBADF, ENOTTY), so that EPERM shows the system-call filter, not the kernel, refused it.
//
//   sandbox-try ACTION...   actions: calls (every filtered call, each line "call NAME: ..."), thread, session,
//                           tty, read:PATH, write:DIR,
//                           connect:PORT, signal:PID, daemon, memory:CHILDREN:MIB, disk:MIB[:DIR] (files of just
//                           under MIB each in its folder, or in DIR, up to 1 GiB), x32 (last: it may be killed)
#include <fcntl.h>
#include <linux/keyctl.h>
#include <mqueue.h>
#include <sched.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <sys/ipc.h>
#include <sys/mman.h>
#include <sys/msg.h>
#include <sys/prctl.h>
#include <sys/ptrace.h>
#include <sys/sem.h>
#include <sys/shm.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <netinet/in.h>
#include <arpa/inet.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace {

void say(const std::string& what, const std::string& result) {
    std::printf("%s: %s\n", what.c_str(), result.c_str());
    std::fflush(stdout);
}

// A call's outcome: refused by the filter (EPERM, or `filtered` for the calls that report another errno), or
// what else became of it. The call is made here, so that errno is read after it.
template <class Call>
std::string outcome(Call call, int filtered = EPERM) {
    errno = 0;
    const long rc = call();
    const int error = errno;
    if (rc >= 0) return "allowed";
    if (error == filtered) return "refused";
    return std::string("allowed (") + strerrorname_np(error) + ")";
}

void* const kBad = reinterpret_cast<void*>(1);  // a pointer the kernel cannot read: EFAULT, where it gets that far

long sys(long nr, long a = 0, long b = 0, long c = 0, long d = 0, long e = 0, long f = 0) {
    return ::syscall(nr, a, b, c, d, e, f);
}

// setsid or setpgid from a fresh child, which unlike the sandbox's first process is no group leader.
std::string fromChild(int which) {
    const pid_t child = ::fork();
    if (child == 0) {
        const long rc = which == 0 ? ::setsid() : ::setpgid(0, 0);
        ::_exit(rc >= 0 ? 0 : errno == EPERM ? 1 : 2);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    if (!WIFEXITED(status)) return "child died";
    return WEXITSTATUS(status) == 0 ? "allowed" : WEXITSTATUS(status) == 1 ? "refused" : "allowed (other error)";
}

void calls() {
    const long bad = reinterpret_cast<long>(kBad);
    say("call add_key", outcome([&] { return sys(SYS_add_key, bad, bad, 0, 0, 0); }));
    say("call request_key", outcome([&] { return sys(SYS_request_key, bad, bad, 0, 0); }));
    say("call keyctl", outcome([&] { return sys(SYS_keyctl, 99999, 0, 0, 0, 0); }));
    say("call ptrace", outcome([&] { return sys(SYS_ptrace, 99999, 0, 0, 0); }));
    say("call process_vm_readv", outcome([&] { return sys(SYS_process_vm_readv, ::getpid(), bad, 1, bad, 1, 0); }));
    say("call process_vm_writev", outcome([&] { return sys(SYS_process_vm_writev, ::getpid(), bad, 1, bad, 1, 0); }));
    say("call pidfd_getfd", outcome([&] { return sys(SYS_pidfd_getfd, -1, 0, 0); }));
    say("call kcmp", outcome([&] { return sys(SYS_kcmp, -1, -1, 99, 0, 0); }));
    say("call unshare", outcome([&] { return sys(SYS_unshare, 0x1); }));  // not a namespace flag: EINVAL unfiltered
    say("call setns", outcome([&] { return sys(SYS_setns, -1, 0); }));
    say("call mount", outcome([&] { return sys(SYS_mount, bad, bad, bad, 0, 0); }));
    say("call umount2", outcome([&] { return sys(SYS_umount2, bad, 0); }));
    say("call pivot_root", outcome([&] { return sys(SYS_pivot_root, bad, bad); }));
    say("call chroot", outcome([&] { return sys(SYS_chroot, bad); }));
    say("call open_tree", outcome([&] { return sys(SYS_open_tree, -1, bad, 0); }));
    say("call fsopen", outcome([&] { return sys(SYS_fsopen, bad, 0); }));
    // With CLONE_THREAD but not CLONE_SIGHAND the kernel itself says EINVAL, and no process is made either way.
    say("call clone with a new network", outcome([&] { return sys(SYS_clone, CLONE_NEWNET | CLONE_THREAD, 0, 0, 0, 0); }));
    say("call clone with a new user", outcome([&] { return sys(SYS_clone, CLONE_NEWUSER | CLONE_THREAD, 0, 0, 0, 0); }));
    say("call clone3", outcome([&] { return sys(SYS_clone3, 0, 0); }, ENOSYS));
    say("call msgctl", outcome([&] { return sys(SYS_msgctl, -1, IPC_STAT, 0); }));
    say("call semget", outcome([&] { return sys(SYS_semget, IPC_PRIVATE, -1, 0); }));
    say("call shmget", outcome([&] { return sys(SYS_shmget, IPC_PRIVATE, 0, 0); }));
    say("call mq_open", outcome([&] { return sys(SYS_mq_open, bad, 0, 0, 0); }));
    say("call socket inet", outcome([&] { return sys(SYS_socket, -1, SOCK_STREAM, 0); }));
    say("call socket unix", outcome([&] { return sys(SYS_socket, AF_UNIX, -1, 0); }));
    say("call setsid", fromChild(0));
    say("call setpgid", fromChild(1));
    say("call perf_event_open", outcome([&] { return sys(SYS_perf_event_open, bad, 0, -1, -1, 0); }));
    say("call bpf", outcome([&] { return sys(SYS_bpf, 99999, 0, 0); }));
    say("call userfaultfd", outcome([&] { return sys(SYS_userfaultfd, 0x7fffffff); }));
    say("call io_uring_setup", outcome([&] { return sys(SYS_io_uring_setup, 0, bad); }));
    say("call reboot", outcome([&] { return sys(SYS_reboot, 0, 0, 0, 0); }));
    say("call syslog", outcome([&] { return sys(SYS_syslog, 9999, 0, 0); }));
    say("call settimeofday", outcome([&] { return sys(SYS_settimeofday, bad, 0); }));
    say("call clock_settime", outcome([&] { return sys(SYS_clock_settime, -1, bad); }));
    say("call adjtimex", outcome([&] { return sys(SYS_adjtimex, bad); }));
    say("call name_to_handle_at", outcome([&] { return sys(SYS_name_to_handle_at, -1, bad, bad, bad, 0); }));
    say("call fanotify_init", outcome([&] { return sys(SYS_fanotify_init, 0x7fffffff, 0); }));
    // The terminal's input queue, from the process's own standard input (/dev/null: ENOTTY unfiltered), and the
    // same request with high bits set, which the kernel ignores and a careless filter would let through.
    char c = 'x';
    say("call ioctl TIOCSTI", outcome([&] { return sys(SYS_ioctl, 0, TIOCSTI, reinterpret_cast<long>(&c)); }));
    say("call ioctl TIOCSTI high bits",
        outcome([&] { return sys(SYS_ioctl, 0, static_cast<long>(TIOCSTI | (1UL << 32)), reinterpret_cast<long>(&c)); }));
    say("call ioctl TIOCLINUX", outcome([&] { return sys(SYS_ioctl, 0, TIOCLINUX, reinterpret_cast<long>(&c)); }));
    say("call ioctl TIOCCONS", outcome([&] { return sys(SYS_ioctl, 0, TIOCCONS, 0); }));
}

}  // namespace

int main(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        const std::string action = argv[i];
        const std::size_t colon = action.find(':');
        const std::string name = action.substr(0, colon), arg = colon == std::string::npos ? "" : action.substr(colon + 1);
        if (name == "calls") {
            calls();
        } else if (name == "thread") {
            int ran = 0;
            std::thread([&] { ran = 1; }).join();
            say("thread", ran ? "ran" : "did not run");
        } else if (name == "session") {
            say("session", ::getsid(0) == ::getpid() ? "its own" : "led by another of its processes");
        } else if (name == "tty") {
            const int fd = ::open("/dev/tty", O_RDWR | O_NOCTTY);
            say("open /dev/tty", fd >= 0 ? "opened" : std::string("refused (") + strerrorname_np(errno) + ")");
        } else if (name == "read") {
            const int fd = ::open(arg.c_str(), O_RDONLY);
            char byte;
            say("read " + arg, fd >= 0 && ::read(fd, &byte, 1) >= 0 ? "readable" : "unreadable");
        } else if (name == "write") {
            const std::string file = arg + "/simlab-sandbox-try-" + std::to_string(::getpid());
            const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
            say("write " + arg, fd >= 0 ? "writable" : "unwritable");
        } else if (name == "connect") {
            const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
            sockaddr_in to{};
            to.sin_family = AF_INET;
            to.sin_port = htons(static_cast<uint16_t>(std::atoi(arg.c_str())));
            to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
            say("connect " + arg, fd >= 0 && ::connect(fd, reinterpret_cast<sockaddr*>(&to), sizeof to) == 0
                                      ? "connected" : "refused");
        } else if (name == "signal") {
            say("signal " + arg, ::kill(std::atoi(arg.c_str()), 0) == 0 ? "allowed" : "refused");
        } else if (name == "daemon") {
            // A grandchild that leaves the tree (its parent exits) and sleeps: it must not outlive the test.
            const pid_t child = ::fork();
            if (child == 0) {
                if (::fork() == 0) {
                    ::prctl(PR_SET_NAME, "sbx-daemon");
                    ::setsid();  // refused by the filter; tried all the same
                    for (;;) ::pause();
                }
                ::_exit(0);
            }
            ::waitpid(child, nullptr, 0);
            say("daemon", "left");
        } else if (name == "memory") {
            // CHILDREN processes, each holding MIB MiB, together: the test's memory is theirs added up.
            const int children = std::atoi(arg.c_str());
            const std::size_t mib = std::strtoul(arg.substr(arg.find(':') + 1).c_str(), nullptr, 10);
            for (int k = 0; k < children; ++k) {
                if (::fork() == 0) {
                    // Touched page by page through a volatile pointer, so that no compiler drops the writes.
                    volatile char* block = static_cast<char*>(std::malloc(mib << 20));
                    for (std::size_t at = 0; block && at < (mib << 20); at += 4096) block[at] = 1;
                    for (;;) ::pause();
                }
            }
            ::sleep(3);  // the poll looks every 50 ms
            say("memory", "held for 3 s");
        } else if (name == "disk") {
            // Files each under the file-size limit, as many as will go: the folder's space is the test's.
            const std::size_t colon = arg.find(':');
            const std::size_t each = (std::strtoul(arg.substr(0, colon).c_str(), nullptr, 10) << 20) - 4096;
            const std::string where =
                colon == std::string::npos ? "" : arg.substr(colon + 1) + "/sandbox-try-" + std::to_string(::getpid()) + "-";
            std::vector<char> block(1 << 20, 'x');
            std::size_t written = 0;
            for (int k = 0; written < (std::size_t{1} << 30); ++k) {
                const int fd = ::open((where + "fill-" + std::to_string(k)).c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
                if (fd < 0) break;
                std::size_t in = 0;
                while (in < each) {
                    const ssize_t n = ::write(fd, block.data(), std::min(block.size(), each - in));
                    if (n <= 0) break;
                    in += static_cast<std::size_t>(n);
                }
                ::close(fd);
                written += in;
                if (in < each) break;
            }
            say("disk", "wrote " + std::to_string(written >> 20) + " MiB");
        } else if (name == "x32") {
            std::printf("x32: ");
            std::fflush(stdout);
            const long rc = ::syscall(0x40000000L | SYS_getpid);
            std::printf("%s\n", rc >= 0 ? "allowed" : "refused");
        } else {
            say(action, "unknown action");
        }
    }
    return 0;
}
