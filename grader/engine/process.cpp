#include "simlab/engine/process.h"

#include <dirent.h>
#include <fcntl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>

namespace simlab::engine {

namespace {

using Clock = std::chrono::steady_clock;

std::string randomToken() {
    std::random_device device;
    static const char* hex = "0123456789abcdef";
    std::string token;
    for (int i = 0; i < 32; ++i) token += hex[device() % 16];
    return token;
}

void setLimit(int resource, rlim_t value) {
    const struct rlimit limit = {value, value};
    ::setrlimit(resource, &limit);
}

// The child between fork and exec: only async-signal-safe calls, no allocation.
[[noreturn]] void becomeChild(const ProcessRequest& r, char* const* argv, char* const* envp, int outWrite,
                              int reportWrite, rlim_t tasks) {
    ::setpgid(0, 0);
    const int devNull = ::open("/dev/null", O_RDONLY);
    if (devNull >= 0) ::dup2(devNull, 0);
    ::dup2(outWrite, 1);
    ::dup2(outWrite, 2);
    if (reportWrite >= 0) ::dup2(reportWrite, 3);  // dup2 clears close-on-exec on the copy
    if (::chdir(r.workDir.c_str()) != 0) {
        const char message[] = "simlab: cannot enter the test's working directory\n";
        (void)!::write(2, message, sizeof message - 1);
        ::_exit(127);
    }
    const Limits& l = r.limits;
    const rlim_t cpu = static_cast<rlim_t>(std::ceil(l.cpuSeconds));
    const struct rlimit cpuLimit = {cpu, cpu + 1};  // SIGXCPU at the soft limit, SIGKILL a second later
    ::setrlimit(RLIMIT_CPU, &cpuLimit);
    setLimit(RLIMIT_AS, static_cast<rlim_t>(l.memoryMiB) << 20);
    setLimit(RLIMIT_FSIZE, static_cast<rlim_t>(l.fileMiB) << 20);
    if (tasks > 0) setLimit(RLIMIT_NPROC, tasks);
    setLimit(RLIMIT_CORE, 0);
    setLimit(RLIMIT_NOFILE, 256);
    ::execve(argv[0], argv, envp);
    const char message[] = "simlab: cannot execute the program\n";
    (void)!::write(2, message, sizeof message - 1);
    ::_exit(127);
}

// RLIMIT_NPROC caps every task (process or thread) of the user, not of one process tree. To let the child
// start `processes` more, count what the user runs now. Root is exempt from the limit: returns 0, "no limit".
rlim_t taskLimitFor(long processes) {
    const uid_t uid = ::getuid();
    if (uid == 0) return 0;
    rlim_t tasks = 0;
    if (DIR* proc = ::opendir("/proc")) {
        while (const struct dirent* entry = ::readdir(proc)) {
            if (entry->d_name[0] < '0' || entry->d_name[0] > '9') continue;
            std::ifstream status(std::string("/proc/") + entry->d_name + "/status");
            std::string key;
            long owner = -1, threads = 0;
            while (status >> key) {
                if (key == "Uid:") status >> owner;
                else if (key == "Threads:") status >> threads;
                std::getline(status, key);
            }
            if (owner == static_cast<long>(uid)) tasks += static_cast<rlim_t>(threads);
        }
        ::closedir(proc);
    }
    return tasks + static_cast<rlim_t>(processes);
}

void drain(int& fd, std::string* keep, std::size_t keepLimit, std::size_t* counted) {
    char buffer[65536];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n > 0) {
            if (counted) *counted += static_cast<std::size_t>(n);
            if (keep->size() < keepLimit) keep->append(buffer, std::min<std::size_t>(n, keepLimit - keep->size()));
            continue;
        }
        if (n < 0 && errno == EINTR) continue;
        if (n < 0 && errno == EAGAIN) return;
        ::close(fd);  // end of file, or an error we cannot recover from
        fd = -1;
        return;
    }
}

}  // namespace

std::string signalName(int signal) {
    if (const char* abbrev = ::sigabbrev_np(signal)) return std::string("SIG") + abbrev;
    return "signal " + std::to_string(signal);
}

std::vector<std::string> childEnvironment(const std::vector<std::string>& extra) {
    std::vector<std::string> env;
    for (const char* name : {"PATH", "HOME", "LANG", "TMPDIR"}) {
        if (const char* value = std::getenv(name)) env.push_back(std::string(name) + "=" + value);
    }
    env.insert(env.end(), extra.begin(), extra.end());
    return env;
}

ProcessResult runProcess(const ProcessRequest& r) {
    ProcessResult result;
    const std::string token = r.reportChannel ? randomToken() : "";

    // Everything the child needs is prepared before fork.
    std::vector<std::string> envStrings = r.env;
    if (r.reportChannel) {
        envStrings.push_back("SIMLAB_REPORT_FD=3");
        envStrings.push_back("SIMLAB_REPORT_TOKEN=" + token);
    }
    std::vector<char*> argv, envp;
    for (const std::string& a : r.argv) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    for (const std::string& e : envStrings) envp.push_back(const_cast<char*>(e.c_str()));
    envp.push_back(nullptr);

    int out[2] = {-1, -1}, report[2] = {-1, -1};
    if (::pipe2(out, O_CLOEXEC) != 0 || (r.reportChannel && ::pipe2(report, O_CLOEXEC) != 0)) {
        result.error = std::string("cannot create a pipe: ") + std::strerror(errno);
        for (int fd : {out[0], out[1], report[0], report[1]}) {
            if (fd >= 0) ::close(fd);
        }
        return result;
    }

    const rlim_t tasks = taskLimitFor(r.limits.processes);
    const auto start = Clock::now();
    const pid_t pid = ::fork();
    if (pid < 0) {
        result.error = std::string("cannot start a process: ") + std::strerror(errno);
        for (int fd : {out[0], out[1], report[0], report[1]}) {
            if (fd >= 0) ::close(fd);
        }
        return result;
    }
    if (pid == 0) becomeChild(r, argv.data(), envp.data(), out[1], report[1], tasks);

    ::setpgid(pid, pid);  // also done by the child; whichever runs first wins the race harmlessly
    result.started = true;
    ::close(out[1]);
    if (report[1] >= 0) ::close(report[1]);
    int outRead = out[0], reportRead = report[0];
    for (int fd : {outRead, reportRead}) {
        if (fd >= 0) ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
    }

    const auto deadline = start + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(r.limits.wallSeconds));
    const std::size_t outputLimit = static_cast<std::size_t>(r.limits.outputKiB) * 1024;
    std::string reportBuffer;
    bool reaped = false, killed = false;
    int status = 0;
    struct rusage usage {};
    auto killGroup = [&] {
        ::kill(-pid, SIGKILL);
        killed = true;
    };
    Clock::time_point reapedAt;

    for (;;) {
        struct pollfd fds[2];
        nfds_t n = 0;
        if (outRead >= 0) fds[n++] = {outRead, POLLIN, 0};
        if (reportRead >= 0) fds[n++] = {reportRead, POLLIN, 0};
        if (n > 0) ::poll(fds, n, 50);
        else if (!reaped) ::usleep(20000);

        if (outRead >= 0) drain(outRead, &result.output, r.keepOutput, &result.outputBytes);
        if (reportRead >= 0) drain(reportRead, &reportBuffer, 4 << 20, nullptr);

        if (!killed && result.outputBytes > outputLimit) {
            result.outputLimit = true;
            killGroup();
        }
        if (!reaped) {
            const pid_t done = ::wait4(pid, &status, WNOHANG, &usage);
            if (done == pid) {
                reaped = true;
                reapedAt = Clock::now();
                result.wallSeconds = std::chrono::duration<double>(reapedAt - start).count();
                ::kill(-pid, SIGKILL);  // whatever it left behind in its group
            }
        }
        if (!reaped && !killed && Clock::now() >= deadline) {
            result.wallTimeout = true;
            killGroup();
        }
        // Done when the child is gone and its pipes are closed, or shortly after it is gone if something it
        // started (and moved out of its group) still holds them.
        if (reaped && ((outRead < 0 && reportRead < 0) || Clock::now() - reapedAt > std::chrono::milliseconds(500))) {
            break;
        }
    }
    for (int fd : {outRead, reportRead}) {
        if (fd >= 0) ::close(fd);
    }

    result.cpuSeconds = usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
                        1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    if (WIFEXITED(status)) result.exitCode = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
    if (result.signal == SIGXCPU ||
        (result.signal == SIGKILL && !killed && result.cpuSeconds >= std::ceil(r.limits.cpuSeconds))) {
        result.cpuTimeout = true;
    }
    if (result.exitCode == 127 && result.output.rfind("simlab: cannot", 0) == 0) {
        result.started = false;
        result.error = result.output.substr(0, result.output.find('\n'));
    }

    // Report lines count only with the token this run handed out.
    std::size_t begin = 0;
    while (r.reportChannel && begin < reportBuffer.size()) {
        std::size_t end = reportBuffer.find('\n', begin);
        if (end == std::string::npos) break;  // a line cut short by a crash is not a report
        const std::string line = reportBuffer.substr(begin, end - begin);
        if (line.size() > token.size() && line.compare(0, token.size(), token) == 0 && line[token.size()] == ' ') {
            result.reports.push_back(line.substr(token.size() + 1));
        }
        begin = end + 1;
    }
    return result;
}

}  // namespace simlab::engine
