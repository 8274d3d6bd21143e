#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <random>
#include <set>

#include "internal.h"
#include "simlab/isolation/host_protocol.h"

namespace simlab::isolation {

namespace {

bool isNumber(const char* name) {
    if (!*name) return false;
    for (const char* c = name; *c; ++c) {
        if (*c < '0' || *c > '9') return false;
    }
    return true;
}

// What a small /proc file holds now (up to 16 KiB: every file read here is far smaller), read with one open and
// one or two reads. /proc is read many times a second while tests run: no stream, no locale, no allocation but
// the string.
std::string readProcFile(const char* path) {
    std::string text;
    const int fd = ::open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return text;
    char buffer[16384];
    std::size_t used = 0;
    for (;;) {
        const ssize_t n = ::read(fd, buffer + used, sizeof buffer - used);
        if (n > 0) {
            used += static_cast<std::size_t>(n);
            if (used < sizeof buffer) continue;
        } else if (n < 0 && errno == EINTR) {
            continue;
        }
        break;
    }
    ::close(fd);
    text.assign(buffer, used);
    return text;
}

// The number after `key` (a line's start, such as "Uid:") in a /proc status text, or -1.
long statusField(const std::string& status, const char* key) {
    const std::size_t length = std::strlen(key);
    for (std::size_t at = 0; at < status.size();) {
        if (status.compare(at, length, key) == 0) return std::strtol(status.c_str() + at + length, nullptr, 10);
        const std::size_t next = status.find('\n', at);
        if (next == std::string::npos) break;
        at = next + 1;
    }
    return -1;
}

// "/proc/<pid>/<file>", in a buffer of the caller's.
const char* procPath(char (&path)[320], const char* pid, const char* file) {
    std::snprintf(path, sizeof path, "/proc/%s/%s", pid, file);
    return path;
}

// The real user id of process `pid` (from its status, which shows it even for a process that made itself
// non-dumpable, whose /proc folder then belongs to root), or -1.
long realUserOf(const char* pid) {
    char path[320];
    return statusField(readProcFile(procPath(path, pid, "status")), "Uid:");
}

// False for a kernel thread (or a zombie), which has no program: /proc/<pid>/exe leads nowhere. Most of the
// folders that belong to root are kernel threads', and this answers without the kernel writing out a status.
bool mayRunAsOther(int procFd, const char* pid) {
    char path[320], target[8];
    std::snprintf(path, sizeof path, "%s/exe", pid);
    return ::readlinkat(procFd, path, target, sizeof target) >= 0 || errno != ENOENT;
}

// A process's state ('Z' for a zombie) from its stat line, or '?'.
char stateIn(const std::string& stat) {
    const std::size_t close = stat.rfind(')');
    return close != std::string::npos && close + 2 < stat.size() ? stat[close + 2] : '?';
}

// Calls `visit(pid)` (the pid as its /proc folder names it) for each process that runs as `uid`, found by one pass
// over /proc: its folder belongs to the process's user, or to root for one that made itself non-dumpable, whose
// status then tells.
template <typename Visit>
void visitProcessesOf(uid_t uid, Visit visit) {
    DIR* proc = ::opendir("/proc");
    if (!proc) return;
    const int procFd = ::dirfd(proc);
    while (const struct dirent* entry = ::readdir(proc)) {
        if (!isNumber(entry->d_name)) continue;
        struct stat info {};
        if (::fstatat(procFd, entry->d_name, &info, 0) != 0) continue;
        if (info.st_uid == uid || (info.st_uid == 0 && mayRunAsOther(procFd, entry->d_name) &&
                                   realUserOf(entry->d_name) == static_cast<long>(uid))) {
            visit(entry->d_name);
        }
    }
    ::closedir(proc);
}

// Processes that run as `uid`, with their state ('Z' for a zombie).
std::vector<std::pair<pid_t, char>> processesOf(uid_t uid) {
    std::vector<std::pair<pid_t, char>> found;
    visitProcessesOf(uid, [&](const char* pid) {
        char path[320];
        const char state = stateIn(readProcFile(procPath(path, pid, "stat")));
        found.emplace_back(static_cast<pid_t>(std::strtol(pid, nullptr, 10)), state);
    });
    return found;
}

// A process's CPU time (its own and its reaped children's, in s) and its resident anonymous memory (KiB): what it
// allocated, not the shared libraries every process maps, which would count once per process of a test.
struct ProcessStat {
    bool alive = false;
    double cpuSeconds = 0;
    long residentKiB = 0;
};

ProcessStat statOf(pid_t pid) {
    static const double ticksPerSecond = static_cast<double>(::sysconf(_SC_CLK_TCK));
    ProcessStat s;
    char id[24], path[320];
    std::snprintf(id, sizeof id, "%d", static_cast<int>(pid));
    const std::string line = readProcFile(procPath(path, id, "stat"));
    const std::size_t close = line.rfind(')');
    if (close == std::string::npos || close + 2 >= line.size()) return s;
    // The fields after the command's closing parenthesis: state is field 3, utime 14 ... cstime 17.
    const char* at = line.c_str() + close + 2;
    double ticks = 0;
    for (int index = 3; index <= 17 && *at; ++index) {
        char* end = nullptr;
        const double value = std::strtod(at, &end);
        if (index >= 14) ticks += value;
        at = std::strchr(at, ' ');
        if (!at) break;
        ++at;
    }
    s.alive = true;
    s.cpuSeconds = ticks / ticksPerSecond;
    const std::string status = readProcFile(procPath(path, id, "status"));
    for (const char* key : {"RssAnon:", "RssShmem:"}) s.residentKiB += std::max(0L, statusField(status, key));
    return s;
}

}  // namespace

uid_t freshUser() {
    static std::mutex lock;
    static std::set<uid_t> given;
    static std::mt19937_64 random{std::random_device{}()};
    const char* base = std::getenv("SIMLAB_SANDBOX_UID_BASE");
    const std::uint64_t first = base ? std::strtoull(base, nullptr, 10) : 2000000000ULL;
    constexpr std::uint64_t kRange = 1ULL << 27;  // below 2^31 from the default base: safe for every tool
    std::lock_guard<std::mutex> guard(lock);
    for (;;) {
        const uid_t uid = static_cast<uid_t>(first + random() % kRange);
        if (given.count(uid) || !processesOf(uid).empty()) continue;
        given.insert(uid);
        return uid;
    }
}

int endProcessesOf(uid_t uid) {
    int left = 0;
    for (int round = 0; round < 10; ++round) {
        // The helper borrows simlab's memory until it exits (vfork), with every signal blocked: it changes its ids
        // by the system calls themselves (the C library's wrappers would change those of every thread of simlab).
        sigset_t all, mask;
        ::sigfillset(&all);
        ::pthread_sigmask(SIG_SETMASK, &all, &mask);
        const pid_t helper = ::vfork();
        if (helper == 0) {
            // Nothing simlab holds stays open in it (a program being written, say, would be busy meanwhile).
            ::close_range(3, ~0U, 0);
            // As that user, signal every process it may signal: exactly that user's, wherever they are. A few
            // times over: a child whose fork was under way during one signal is listed by the next. (A zombie can
            // be signalled too, so "no process left" is never the answer while one waits to be reaped: the rounds
            // below count what is left, zombies aside.)
            if (!host::becomeUser(uid)) ::_exit(2);
            for (int i = 0; i < 8; ++i) {
                if (::kill(-1, SIGKILL) != 0) ::_exit(errno == ESRCH ? 0 : 3);
            }
            ::_exit(1);
        }
        ::pthread_sigmask(SIG_SETMASK, &mask, nullptr);
        if (helper < 0) return -1;
        int status = 0;
        while (::waitpid(helper, &status, __WALL) < 0 && errno == EINTR) {
        }
        // No process of the user answered a signal, not even a zombie: nothing is left, and nothing can start one.
        if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return 0;
        // What is left but zombies (which their parents, or simlab as the subreaper, reap).
        left = 0;
        for (const auto& [pid, state] : processesOf(uid)) left += state != 'Z' && state != 'X';
        if (left == 0) return 0;
        ::usleep(2000 << std::min(round, 6));  // a killed process may take a moment to be gone
    }
    return left;
}

namespace {

// The bytes on disk of the files `pid` holds open, by a descriptor or a mapping, that no folder names any more
// (unlinked: a test's files that no look at its folders finds), each file once in `seen`.
std::uintmax_t unlinkedBytesOf(pid_t pid, std::set<std::pair<dev_t, ino_t>>& seen) {
    std::uintmax_t bytes = 0;
    const std::string proc = "/proc/" + std::to_string(pid);
    auto count = [&](const std::string& link) {
        struct stat info {};
        if (::stat(link.c_str(), &info) != 0 || !S_ISREG(info.st_mode) || info.st_nlink != 0) return;
        if (seen.insert({info.st_dev, info.st_ino}).second) bytes += static_cast<std::uintmax_t>(info.st_blocks) * 512;
    };
    for (const char* kind : {"/fd", "/map_files"}) {
        DIR* d = ::opendir((proc + kind).c_str());
        if (!d) continue;
        int entries = 0;
        while (const struct dirent* e = ::readdir(d)) {
            if (e->d_name[0] == '.' || ++entries > 4096) continue;
            count(proc + kind + "/" + e->d_name);
        }
        ::closedir(d);
    }
    return bytes;
}

}  // namespace

Usage usageOf(pid_t root, uid_t uid) {
    std::set<pid_t> members;
    std::vector<pid_t> pending = {root};
    while (!pending.empty() && members.size() < 8192) {
        const pid_t pid = pending.back();
        pending.pop_back();
        if (!members.insert(pid).second) continue;
        const std::string dir = "/proc/" + std::to_string(pid) + "/task";
        if (DIR* tasks = ::opendir(dir.c_str())) {
            while (const struct dirent* task = ::readdir(tasks)) {
                if (task->d_name[0] == '.') continue;
                const std::string children = readProcFile((dir + "/" + task->d_name + "/children").c_str());
                for (const char* at = children.c_str(); *at;) {
                    char* end = nullptr;
                    const long child = std::strtol(at, &end, 10);
                    if (end == at) break;
                    pending.push_back(static_cast<pid_t>(child));
                    at = end;
                }
            }
            ::closedir(tasks);
        }
    }
    if (uid != 0) {
        for (const auto& [pid, state] : processesOf(uid)) members.insert(pid);
    }
    Usage usage;
    std::set<std::pair<dev_t, ino_t>> unlinked;
    for (const pid_t pid : members) {
        const ProcessStat s = statOf(pid);
        if (!s.alive) continue;
        ++usage.processes;
        usage.cpuSeconds += s.cpuSeconds;
        usage.residentKiB += s.residentKiB;
        usage.unlinkedBytes += unlinkedBytesOf(pid, unlinked);
    }
    return usage;
}

long tasksOf(uid_t uid) {
    long tasks = 0;
    visitProcessesOf(uid, [&](const char* pid) {
        char path[320];
        tasks += std::max(0L, statusField(readProcFile(procPath(path, pid, "status")), "Threads:"));
    });
    return tasks;
}

long peakResidentOf(pid_t pid) {
    char id[24], path[320];
    std::snprintf(id, sizeof id, "%d", static_cast<int>(pid));
    return std::max(0L, statusField(readProcFile(procPath(path, id, "status")), "VmHWM:"));
}

std::uintmax_t folderBytes(const std::string& path, std::uintmax_t stopAt) {
    // Folder by folder through descriptors, never through a link: a test may swap one of its folders for a link
    // while it is looked at, and what the link leads to is not its.
    std::uintmax_t bytes = 0;
    int entries = 0;
    std::vector<int> pending;
    const int top = ::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (top >= 0) pending.push_back(top);
    while (!pending.empty()) {
        const int fd = pending.back();
        pending.pop_back();
        DIR* d = ::fdopendir(fd);
        if (!d) {
            ::close(fd);
            continue;
        }
        while (const struct dirent* e = ::readdir(d)) {
            if (e->d_name[0] == '.' && (e->d_name[1] == 0 || (e->d_name[1] == '.' && e->d_name[2] == 0))) continue;
            struct stat info {};
            if (++entries > 20000 || bytes > stopAt) {
                bytes = std::max(bytes, stopAt + 1);
                break;
            }
            if (::fstatat(::dirfd(d), e->d_name, &info, AT_SYMLINK_NOFOLLOW) != 0) continue;
            bytes += static_cast<std::uintmax_t>(info.st_blocks) * 512;
            if (S_ISDIR(info.st_mode)) {
                const int below = ::openat(::dirfd(d), e->d_name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
                if (below >= 0) pending.push_back(below);
            }
        }
        ::closedir(d);
        if (bytes > stopAt) break;
    }
    for (const int fd : pending) ::close(fd);
    return bytes;
}

// Hands `path` (and what is in it) to `uid`, shut to everyone else: the sandbox user owns its working directory
// and what it is lent for the run, and no other sandbox user can enter them. Handed back to root (uid 0) after.
bool handTo(const std::string& path, uid_t uid) {
    namespace fs = std::filesystem;
    std::error_code error;
    auto give = [&](const fs::path& p) {
        struct stat info {};
        if (::lstat(p.c_str(), &info) != 0 || S_ISLNK(info.st_mode)) return true;
        return ::lchown(p.c_str(), uid, uid) == 0 && ::chmod(p.c_str(), info.st_mode & 0700) == 0;
    };
    if (!give(path)) return false;
    if (!fs::is_directory(path, error)) return true;
    for (auto it = fs::recursive_directory_iterator(path, error); !error && it != fs::recursive_directory_iterator();
         it.increment(error)) {
        if (!give(it->path())) return false;
    }
    return !error;
}

namespace {

// The machine's shared temporary folders, which every user may write where no file rules keep a process out.
const char* const kSharedTemporary[] = {"/tmp", "/var/tmp", "/dev/shm", "/run/lock"};

// Calls `each` with every entry of a shared temporary folder that `uid` owns: at their tops, and at the tops of the
// folders there that every user may write into (a sticky folder such as /tmp/.X11-unix).
template <typename Each>
void forFilesOf(uid_t uid, const Each& each) {
    for (const char* shared : kSharedTemporary) {
        std::vector<std::string> folders = {shared};
        for (std::size_t i = 0; i < folders.size(); ++i) {
            DIR* d = ::opendir(folders[i].c_str());
            if (!d) continue;
            std::vector<std::string> entries;
            while (const struct dirent* e = ::readdir(d)) {
                if (e->d_name[0] == '.' && (e->d_name[1] == 0 || (e->d_name[1] == '.' && e->d_name[2] == 0))) continue;
                entries.push_back(folders[i] + "/" + e->d_name);
            }
            ::closedir(d);
            for (const std::string& p : entries) {
                struct stat info {};
                if (::lstat(p.c_str(), &info) != 0) continue;
                if (info.st_uid == uid) {
                    if (!each(p, info)) return;
                } else if (i == 0 && S_ISDIR(info.st_mode) && (info.st_mode & S_IWOTH)) {
                    folders.push_back(p);
                }
            }
        }
    }
}

}  // namespace

std::uintmax_t sharedTemporaryBytes(uid_t uid, std::uintmax_t stopAt) {
    std::uintmax_t bytes = 0;
    forFilesOf(uid, [&](const std::string& p, const struct stat& info) {
        bytes += S_ISDIR(info.st_mode) ? folderBytes(p, stopAt) : static_cast<std::uintmax_t>(info.st_blocks) * 512;
        return bytes <= stopAt;
    });
    return bytes;
}

// Without bubblewrap or Landlock a sandbox user could write to the machine's shared temporary folders: what it
// left there goes with it.
void removeFilesOf(uid_t uid) {
    std::vector<std::string> found;
    forFilesOf(uid, [&](const std::string& p, const struct stat&) {
        found.push_back(p);
        return true;
    });
    for (const std::string& p : found) {
        std::error_code error;
        std::filesystem::remove_all(p, error);
    }
}

}  // namespace simlab::isolation
