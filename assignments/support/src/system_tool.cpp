#include "simlab/system_tool.h"

#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>

extern char** environ;

namespace simlab {

namespace {

constexpr std::size_t kMaxErrors = 64u << 10;  // bytes of a tool's stderr kept

/// A file descriptor closed when it goes out of scope.
struct Fd {
    int fd = -1;
    Fd() = default;
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
    ~Fd() { close(); }
    void close() {
        if (fd >= 0) ::close(fd);
        fd = -1;
    }
};

/// The child process, killed (if it still runs) and reaped when it goes out of scope.
struct Child {
    pid_t pid = -1;
    Child() = default;
    Child(const Child&) = delete;
    Child& operator=(const Child&) = delete;
    ~Child() {
        if (pid > 0) {
            ::kill(pid, SIGKILL);
            wait();
        }
    }
    int wait() {
        int status = 0;
        while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
        pid = -1;
        return status;
    }
};

/// SIGPIPE blocked in this thread while it lives, so that writing to a pipe the tool has closed is EPIPE instead
/// of the end of the program. A SIGPIPE raised meanwhile (it goes to the writing thread) is consumed before the
/// mask is restored; one that was already pending stays pending. No process-wide signal disposition changes.
class SigpipeBlocked {
public:
    SigpipeBlocked() {
        sigemptyset(&pipe_);
        sigaddset(&pipe_, SIGPIPE);
        sigset_t pending;
        sigpending(&pending);
        wasPending_ = sigismember(&pending, SIGPIPE) == 1;
        pthread_sigmask(SIG_BLOCK, &pipe_, &old_);
    }
    SigpipeBlocked(const SigpipeBlocked&) = delete;
    SigpipeBlocked& operator=(const SigpipeBlocked&) = delete;
    ~SigpipeBlocked() {
        if (!wasPending_) {
            const timespec zero{0, 0};
            while (sigtimedwait(&pipe_, nullptr, &zero) < 0 && errno == EINTR) {
            }
        }
        pthread_sigmask(SIG_SETMASK, &old_, nullptr);
    }

private:
    sigset_t pipe_, old_;
    bool wasPending_ = false;
};

void makePipe(const std::string& tool, Fd& readEnd, Fd& writeEnd) {
    int ends[2];
    if (pipe2(ends, O_CLOEXEC) != 0) {
        throw std::runtime_error(tool + " failed: cannot make a pipe: " + std::strerror(errno));
    }
    readEnd.fd = ends[0];
    writeEnd.fd = ends[1];
}

void setNonBlocking(int fd) { fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK); }

/// Read what is there; false at end of file. What would go past `cap` bytes is dropped, and `overflow` set.
bool drain(int fd, std::string& into, std::size_t cap, bool& overflow) {
    char buffer[65536];
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n == 0) return false;
    if (n < 0) return errno == EAGAIN || errno == EINTR;
    const std::size_t room = cap - std::min(cap, into.size());
    into.append(buffer, std::min(room, static_cast<std::size_t>(n)));
    if (static_cast<std::size_t>(n) > room) overflow = true;
    return true;
}

/// Spawn argv with its stdin, stdout and stderr on the given pipe ends (no shell). The child gets an empty signal
/// mask and the default SIGPIPE action whatever the caller has.
void spawn(Child& child, const std::vector<std::string>& argv, int in, int out, int err) {
    posix_spawn_file_actions_t actions;
    posix_spawnattr_t attributes;
    posix_spawn_file_actions_init(&actions);
    posix_spawnattr_init(&attributes);
    posix_spawn_file_actions_adddup2(&actions, in, 0);
    posix_spawn_file_actions_adddup2(&actions, out, 1);
    posix_spawn_file_actions_adddup2(&actions, err, 2);
    sigset_t none, pipeSignal;
    sigemptyset(&none);
    sigemptyset(&pipeSignal);
    sigaddset(&pipeSignal, SIGPIPE);
    posix_spawnattr_setsigmask(&attributes, &none);
    posix_spawnattr_setsigdefault(&attributes, &pipeSignal);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    std::vector<std::string> copies = argv;
    std::vector<char*> pointers;
    for (std::string& a : copies) pointers.push_back(a.data());
    pointers.push_back(nullptr);
    const int error = posix_spawnp(&child.pid, argv[0].c_str(), &actions, &attributes, pointers.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    if (error != 0) child.pid = -1;
    if (error == ENOENT) throw SystemToolMissing(argv[0] + " is not installed");
    if (error != 0) throw std::runtime_error(argv[0] + " failed: cannot start it: " + std::strerror(error));
}

}  // namespace

std::string SystemToolRun::reason() const {
    const std::size_t start = errors.find_first_not_of(" \t\r\n");
    if (start != std::string::npos) return errors.substr(start, errors.find('\n', start) - start);
    return exited ? "exit status " + std::to_string(status) : "killed by signal " + std::to_string(status);
}

SystemToolRun runSystemTool(const std::vector<std::string>& argv, const std::string& input, int seconds,
                            std::size_t maxOutput) {
    if (argv.empty()) throw std::invalid_argument("runSystemTool: no program");
    const std::string& tool = argv[0];
    Fd inRead, inWrite, outRead, outWrite, errRead, errWrite;
    makePipe(tool, inRead, inWrite);
    makePipe(tool, outRead, outWrite);
    makePipe(tool, errRead, errWrite);
    Child child;
    spawn(child, argv, inRead.fd, outWrite.fd, errWrite.fd);
    inRead.close();
    outWrite.close();
    errWrite.close();

    SystemToolRun run;
    bool outputOverflow = false, errorsOverflow = false;
    std::size_t written = 0;
    {
        const SigpipeBlocked guard;
        setNonBlocking(inWrite.fd);
        setNonBlocking(outRead.fd);
        setNonBlocking(errRead.fd);
        if (input.empty()) inWrite.close();
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
        // Until the tool has read all (or stopped reading: EPIPE) and closed its outputs.
        while (inWrite.fd >= 0 || outRead.fd >= 0 || errRead.fd >= 0) {
            pollfd fds[3] = {{inWrite.fd, POLLOUT, 0}, {outRead.fd, POLLIN, 0}, {errRead.fd, POLLIN, 0}};
            if (std::chrono::steady_clock::now() > deadline) {
                throw std::runtime_error(tool + " failed: it took longer than " + std::to_string(seconds) + " s");
            }
            if (poll(fds, 3, 1000) < 0 && errno != EINTR) {
                throw std::runtime_error(tool + " failed: " + std::strerror(errno));
            }
            if (inWrite.fd >= 0 && (fds[0].revents & (POLLOUT | POLLERR | POLLHUP))) {
                const ssize_t n = ::write(inWrite.fd, input.data() + written, input.size() - written);
                if (n > 0) written += static_cast<std::size_t>(n);
                // Done, or the tool stopped reading (EPIPE: it has failed and says why on stderr).
                if (written == input.size() || (n < 0 && errno != EAGAIN && errno != EINTR)) inWrite.close();
            }
            if (outRead.fd >= 0 && fds[1].revents && !drain(outRead.fd, run.output, maxOutput, outputOverflow)) {
                outRead.close();
            }
            if (errRead.fd >= 0 && fds[2].revents && !drain(errRead.fd, run.errors, kMaxErrors, errorsOverflow)) {
                errRead.close();
            }
            if (outputOverflow) {
                throw std::runtime_error(tool + " failed: its output is larger than " +
                                         std::to_string(maxOutput >> 20) + " MiB");
            }
        }
    }
    const int status = child.wait();
    run.exited = WIFEXITED(status);
    run.status = run.exited ? WEXITSTATUS(status) : WTERMSIG(status);
    return run;
}

}  // namespace simlab
