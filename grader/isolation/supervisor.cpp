// The one supervisor of every sandboxed run, whether simlab started the process itself (launchProcess) or a
// probe's server forked it (TestServer::run): its output, its report channel, its processes' CPU time and memory
// together, the wall clock, an interruption, and the orphans simlab reaps.
#include <poll.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <mutex>
#include <set>

#include "internal.h"

namespace simlab::isolation {

namespace {

// Children being waited for, each by the thread that started it. Everything else that ends up our child is an
// orphan: simlab is a subreaper, so processes that bubblewrap (or student code) leaves behind are reparented to
// it rather than to init, which on some machines never reaps them, and their zombies would count against the
// sandbox user's process limit.
std::mutex gChildrenLock;
std::set<pid_t> gChildren;

// The complete lines of a report channel: a line cut short by a crash is not a report.
std::vector<std::string> reportLines(const std::string& buffer) {
    std::vector<std::string> lines;
    for (std::size_t begin = 0; begin < buffer.size();) {
        const std::size_t end = buffer.find('\n', begin);
        if (end == std::string::npos) break;
        lines.push_back(buffer.substr(begin, end - begin));
        begin = end + 1;
    }
    return lines;
}

// What a run's processes use together, against its limits: the CPU time (the most seen so far) and memory are
// kept in `result`, and the limit passed first is marked there. True if one was passed: the caller ends them.
bool overLimits(const Usage& usage, const Limits& limits, double& treeCpu, long& peakResidentKiB,
                ProcessResult& result) {
    treeCpu = std::max(treeCpu, usage.cpuSeconds);
    peakResidentKiB = std::max(peakResidentKiB, usage.residentKiB);
    // Both are judged at every poll, and both are recorded when both are past: processes that fill memory are
    // charged the kernel's page zeroing as CPU time, so on a busy machine the two limits can be crossed between
    // the same two polls, and the verdict (memory first) must not depend on the order they are checked in.
    if (treeCpu > limits.cpuSeconds) result.cpuTimeout = true;
    if (usage.residentKiB > static_cast<long>(limits.memoryMiB) * 1024) result.memoryLimit = true;
    return result.cpuTimeout || result.memoryLimit;
}

// How the process ended (`status`, as waitpid gives it), in `result`: its exit status or signal, a CPU limit the
// kernel enforced (SIGXCPU, or a SIGKILL simlab did not send once the CPU time reached the limit), and a start
// that failed in the child ("simlab: cannot ...", status 127); then its report channel's lines.
void concludeResult(int status, bool killed, const ProcessRequest& r, const std::string& reportBuffer,
                    ProcessResult& result) {
    if (WIFEXITED(status)) result.exitCode = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
    if (!result.memoryLimit && (result.signal == SIGXCPU ||
                                (result.signal == SIGKILL && !killed && result.cpuSeconds >= std::ceil(r.limits.cpuSeconds)))) {
        result.cpuTimeout = true;
    }
    if (result.exitCode == 127 && result.output.rfind("simlab: cannot", 0) == 0) {
        result.started = false;
        result.error = result.output.substr(0, result.output.find('\n'));
    }
    if (r.reportChannel) result.reports = reportLines(reportBuffer);
}

// Reads what `fd` holds now into `keep` (up to keepLimit), counting it; with `lines`, also hands each complete
// line to it (`partial` holds the start of the next).
void drain(int& fd, std::string* keep, std::size_t keepLimit, std::size_t* counted,
           const std::function<void(const std::string&)>* lines = nullptr, std::string* partial = nullptr) {
    char buffer[65536];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n > 0) {
            if (counted) *counted += static_cast<std::size_t>(n);
            if (keep->size() < keepLimit) keep->append(buffer, std::min<std::size_t>(n, keepLimit - keep->size()));
            if (lines && *lines) {
                for (ssize_t i = 0; i < n; ++i) {
                    if (buffer[i] != '\n') {
                        if (partial->size() < (1u << 20)) partial->push_back(buffer[i]);
                        continue;
                    }
                    (*lines)(*partial);
                    partial->clear();
                }
            }
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

void becomeSubreaper() {
    static std::once_flag once;
    std::call_once(once, [] { ::prctl(PR_SET_CHILD_SUBREAPER, 1); });
}

void reapOrphans() {
    std::lock_guard<std::mutex> guard(gChildrenLock);
    for (;;) {
        siginfo_t info{};
        if (::waitid(P_ALL, 0, &info, WEXITED | WNOHANG | WNOWAIT) != 0 || info.si_pid == 0) return;
        if (gChildren.count(info.si_pid)) return;  // its thread reaps it; the next call gets past it
        ::waitpid(info.si_pid, nullptr, WNOHANG);
    }
}

std::mutex& childrenLock() { return gChildrenLock; }

void registerChild(pid_t pid) { gChildren.insert(pid); }  // under childrenLock()

void forgetChild(pid_t pid) {
    std::lock_guard<std::mutex> guard(gChildrenLock);
    gChildren.erase(pid);
}

void supervise(const ProcessRequest& r, Watched& w, Clock::time_point start, ProcessResult& result) {
    // Limits are checked when rubrics and options are read; a day is far more than any of them allows.
    const auto deadline = start + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(std::min(r.limits.wallSeconds, 86400.0)));
    const std::size_t outputLimit = static_cast<std::size_t>(r.limits.outputKiB) * 1024;
    std::string reportBuffer, partialLine;
    bool ended = false, killed = false;
    int status = 0;
    double endedCpu = -1, treeCpu = 0;
    long endedRss = 0, peakResidentKiB = 0, ownPeakKiB = 0;
    auto killAll = [&] {
        w.kill();
        killed = true;
    };
    Clock::time_point endedAt;
    // The run's processes are added up every 100 ms (each process's own limits hold in between): a look at every
    // process of its user, so not more often than that.
    Clock::time_point nextCheck = start + std::chrono::milliseconds(50);
    for (;;) {
        struct pollfd fds[3];
        nfds_t n = 0;
        if (w.out >= 0) fds[n++] = {w.out, POLLIN, 0};
        if (w.report >= 0) fds[n++] = {w.report, POLLIN, 0};
        if (w.wake >= 0 && !ended) fds[n++] = {w.wake, POLLIN, 0};
        if (n > 0) ::poll(fds, n, 50);
        else if (!ended) ::usleep(20000);

        if (w.out >= 0) drain(w.out, &result.output, r.keepOutput, &result.outputBytes, &r.onOutputLine, &partialLine);
        if (w.report >= 0) drain(w.report, &reportBuffer, 1 << 20, nullptr);
        if (!killed && result.outputBytes > outputLimit) {
            result.outputLimit = true;
            killAll();
        }
        reapOrphans();
        if (!ended && w.ended(status, endedCpu, endedRss)) {
            ended = true;
            endedAt = Clock::now();
            result.wallSeconds = std::chrono::duration<double>(endedAt - start).count();
            if (!killed) w.kill();  // whatever it left behind
        }
        // The run's processes together: their CPU time and their memory are the run's.
        if (!ended && !killed && Clock::now() >= nextCheck) {
            nextCheck = Clock::now() + std::chrono::milliseconds(100);
            if (w.ownPeak) ownPeakKiB = std::max(ownPeakKiB, w.ownPeak());
            const Usage usage = w.usage();
            if (overLimits(usage, r.limits, treeCpu, peakResidentKiB, result)) killAll();
            if (!killed && r.stalled && r.stalled(treeCpu)) {
                result.wallTimeout = true;
                killAll();
            }
            const std::uintmax_t diskCap = 3 * (static_cast<std::uintmax_t>(r.limits.fileMiB) << 20);
            std::uintmax_t written = w.folder.empty() ? 0 : folderBytes(w.folder, diskCap) + usage.unlinkedBytes;
            if (w.sharedUser != 0 && written <= diskCap) written += sharedTemporaryBytes(w.sharedUser, diskCap - written);
            if (!killed && written > diskCap) {
                result.diskLimit = true;
                killAll();
            }
        }
        if (!ended && !killed && Clock::now() >= deadline) {
            result.wallTimeout = true;
            killAll();
        }
        if (!ended && !killed && interrupted()) {
            result.interrupted = true;
            killAll();
        }
        // Done when the process is gone and its pipes are closed, or shortly after it is gone if something it
        // started (and moved out of its reach) still holds them.
        if (ended && ((w.out < 0 && w.report < 0) || Clock::now() - endedAt > std::chrono::milliseconds(500))) break;
    }
    for (int* fd : {&w.out, &w.report}) {
        if (*fd >= 0) ::close(*fd);
        *fd = -1;
    }
    if (r.onOutputLine && !partialLine.empty()) r.onOutputLine(partialLine);
    reapOrphans();
    result.cpuSeconds = std::max(endedCpu, treeCpu);
    result.maxRssKiB = std::max(endedRss, peakResidentKiB);
    result.ownPeakKiB = ownPeakKiB;
    concludeResult(status, killed, r, reportBuffer, result);
}

}  // namespace simlab::isolation
