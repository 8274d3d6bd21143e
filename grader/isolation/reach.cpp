// What a sandboxed process may read (reach.h): the system, simlab's places, and the audit of the places where
// files are kept apart by their modes alone.
#include "simlab/isolation/reach.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <sys/xattr.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "internal.h"
#include "simlab/isolation/host_protocol.h"

namespace simlab::isolation {

namespace {

namespace fs = std::filesystem;

bool isUnder(const std::string& path, const std::string& folder) {
    if (folder == "/") return path.size() > 1 && path[0] == '/';
    return path.size() > folder.size() && path.compare(0, folder.size(), folder) == 0 && path[folder.size()] == '/';
}

bool isOrUnder(const std::string& path, const std::string& folder) { return path == folder || isUnder(path, folder); }

bool underAny(const std::string& path, const std::vector<std::string>& folders) {
    return std::any_of(folders.begin(), folders.end(), [&](const std::string& f) { return isOrUnder(path, f); });
}

std::string withoutTrailingSlash(std::string path) {
    while (path.size() > 1 && path.back() == '/') path.pop_back();
    return path;
}

// A path made absolute and normal, as written (links not followed).
std::string normal(const std::string& path) {
    std::error_code error;
    return withoutTrailingSlash(fs::absolute(path, error).lexically_normal().string());
}

// A path as the kernel resolves it (links followed) where it exists, else as written, made absolute.
std::string resolved(const std::string& path) {
    std::error_code error;
    const fs::path absolute = fs::absolute(path, error).lexically_normal();
    const fs::path real = fs::weakly_canonical(absolute, error);
    return withoutTrailingSlash((error ? absolute : real).string());
}

std::mutex gPlacesLock;
std::vector<std::string> gPlaces;

bool inSystemFolder(const std::string& path) {
    return std::any_of(systemFolders().begin(), systemFolders().end(),
                       [&](const std::string& d) { return isOrUnder(path, d) || isOrUnder(path, resolved(d)); });
}

constexpr std::size_t kWalkBound = 500000;  // entries under the places, a net for a place that holds a disk

// Every regular file under every place, as root (or simlab's user) lists them, but those under `kept`: names a
// throwaway user could not list are tried all the same, since it may open what it cannot list. Links are not
// followed: what one leads to is tried where it lies, if that is a place. As root, a folder others may not pass
// through hides all below it from a user with no group, whatever their modes: it is not walked (what a student
// left in a closed class folder, however many files, costs nothing). A walk past the bound marks `exposure`.
std::vector<std::string> filesUnderPlaces(const std::vector<std::string>& kept, bool asRoot, Exposure& exposure) {
    auto closedToOthers = [&](const std::string& path, const struct stat& info) {
        // An access list may name users and groups: a folder that has one is walked.
        return asRoot && S_ISDIR(info.st_mode) && (info.st_mode & S_IXOTH) == 0 &&
               ::lgetxattr(path.c_str(), "system.posix_acl_access", nullptr, 0) < 0;
    };
    std::vector<std::string> files;
    std::size_t entries = 0;
    for (const std::string& place : places()) {
        struct stat info {};
        if (::lstat(place.c_str(), &info) != 0) continue;
        if (S_ISREG(info.st_mode)) {
            if (!underAny(place, kept)) files.push_back(place);
            continue;
        }
        if (!S_ISDIR(info.st_mode) || closedToOthers(place, info)) continue;
        std::error_code error;
        for (auto it = fs::recursive_directory_iterator(place, fs::directory_options::skip_permission_denied, error);
             !error && it != fs::recursive_directory_iterator(); it.increment(error)) {
            if (++entries > kWalkBound) {
                exposure.bounded = true;
                exposure.boundedIn = place;
                break;
            }
            const std::string path = it->path().string();
            if (underAny(path, kept)) {
                if (it->is_directory(error) && !it->is_symlink(error)) it.disable_recursion_pending();
                continue;
            }
            struct stat entry {};
            if (::lstat(path.c_str(), &entry) != 0) continue;
            if (closedToOthers(path, entry)) it.disable_recursion_pending();
            else if (S_ISREG(entry.st_mode)) files.push_back(path);
        }
        if (exposure.bounded) break;
    }
    return files;
}

}  // namespace

const std::vector<std::string>& systemFolders() {
    static const std::vector<std::string> folders = {"/usr", "/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32"};
    return folders;
}

const std::vector<std::string>& systemFiles() {
    static const std::vector<std::string> files = {"/etc/ld.so.cache", "/etc/alternatives", "/etc/fonts",
                                                   "/etc/localtime"};
    return files;
}

const std::vector<std::string>& notTheSystems() {
    static const std::vector<std::string> folders = {"/usr/local"};
    return folders;
}

std::vector<std::string> outOfReach() {
    std::vector<std::string> all = places();
    all.insert(all.end(), notTheSystems().begin(), notTheSystems().end());
    std::sort(all.begin(), all.end());
    return all;
}

const std::vector<std::string>& systemDevices() {
    static const std::vector<std::string> devices = {"/dev/null", "/dev/zero", "/dev/urandom", "/dev/random"};
    return devices;
}

void addPlaces(const std::vector<std::string>& paths) {
    std::lock_guard<std::mutex> guard(gPlacesLock);
    for (const std::string& path : paths) {
        if (path.empty()) continue;
        for (const std::string& p : {resolved(path), normal(path)}) {
            // Never a system folder itself, nor a folder that holds one: the sandbox is made of them.
            const bool holdsSystem = std::any_of(systemFolders().begin(), systemFolders().end(),
                                                 [&](const std::string& d) { return isOrUnder(d, p); });
            if (p == "/" || holdsSystem || std::find(gPlaces.begin(), gPlaces.end(), p) != gPlaces.end()) continue;
            gPlaces.push_back(p);
        }
    }
    std::sort(gPlaces.begin(), gPlaces.end());
}

std::vector<std::string> places() {
    std::lock_guard<std::mutex> guard(gPlacesLock);
    return gPlaces;
}

std::string placeOf(const std::string& path) {
    const std::vector<std::string> all = places();
    for (const std::string& form : {normal(path), resolved(path)}) {
        for (const std::string& place : all) {
            if (isOrUnder(form, place)) return place;
        }
    }
    return "";
}

bool visibleInSandboxes(const std::string& path) {
    return inSystemFolder(resolved(path)) && placeOf(path).empty() && !underAny(normal(path), notTheSystems()) &&
           !underAny(resolved(path), notTheSystems());
}

bool withinReach(const std::string& path, const std::vector<std::string>& lent, const std::string& workDir) {
    const std::string p = normal(path);
    std::vector<std::string> own;
    for (const std::string& l : lent) own.push_back(normal(l));
    if (!workDir.empty()) own.push_back(normal(workDir));
    if (underAny(p, own)) return true;
    if (!placeOf(p).empty() || underAny(p, notTheSystems())) return false;
    return underAny(p, systemFolders()) || underAny(p, systemFiles()) || underAny(p, systemDevices());
}

Exposure exposedPlaces(const std::vector<std::string>& lent) {
    Exposure exposure;
    std::vector<std::string> kept;
    for (const std::string& l : lent) {
        if (!l.empty()) {
            kept.push_back(normal(l));
            kept.push_back(resolved(l));
        }
    }
    const bool asRoot = ::geteuid() == 0;
    std::vector<std::string> files = filesUnderPlaces(kept, asRoot, exposure);
    std::sort(files.begin(), files.end());
    files.erase(std::unique(files.begin(), files.end()), files.end());
    exposure.tried = files.size();
    // A place's folder nothing lent lies below must not be passable either: what simlab writes there later (a
    // class's grades, as it grades) would be any test's to read, whatever the files' modes.
    std::vector<std::string> folders;
    for (const std::string& place : places()) {
        struct stat info {};
        if (::lstat(place.c_str(), &info) != 0 || !S_ISDIR(info.st_mode)) continue;
        if (std::none_of(kept.begin(), kept.end(), [&](const std::string& l) { return isOrUnder(l, place); })) {
            folders.push_back(place + "/.simlab-passage");
        }
    }
    const std::size_t fileCount = files.size();
    files.insert(files.end(), folders.begin(), folders.end());
    if (files.empty()) return exposure;

    // Tried in a child that is what a test's process is: as root, a user never used before, with no group and no
    // capability; otherwise simlab's own user. Only system calls after the fork: this process may have threads.
    std::vector<char> opened(files.size(), 0);
    int results[2];
    if (::pipe2(results, O_CLOEXEC) != 0) {
        exposure.error = std::string("cannot try the files: ") + std::strerror(errno);
        return exposure;
    }
    const uid_t uid = asRoot ? freshUser() : 0;
    pid_t child = -1;
    {
        // Registered before the reaper of orphans can see it exit.
        std::lock_guard<std::mutex> guard(childrenLock());
        child = ::fork();
        if (child > 0) registerChild(child);
    }
    if (child == 0) {
        ::close(results[0]);
        if (asRoot && !host::becomeUser(uid)) ::_exit(3);
        if (::geteuid() == 0) ::_exit(3);
        char chunk[4096];
        std::size_t used = 0;
        for (std::size_t i = 0; i < files.size(); ++i) {
            const int fd = ::open(files[i].c_str(), O_RDONLY | O_NONBLOCK | O_NOFOLLOW | O_NOCTTY | O_CLOEXEC);
            // A file that opens; a folder whose names a lookup reaches (a name not there is ENOENT, not EACCES).
            chunk[used++] = i < fileCount ? fd >= 0 : fd >= 0 || errno == ENOENT;
            if (fd >= 0) ::close(fd);
            if (used == sizeof chunk) {
                if (::write(results[1], chunk, used) != static_cast<ssize_t>(used)) ::_exit(4);
                used = 0;
            }
        }
        if (used > 0 && ::write(results[1], chunk, used) != static_cast<ssize_t>(used)) ::_exit(4);
        ::_exit(0);
    }
    ::close(results[1]);
    std::size_t got = 0;
    while (child > 0 && got < opened.size()) {
        const ssize_t n = ::read(results[0], opened.data() + got, opened.size() - got);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        got += static_cast<std::size_t>(n);
    }
    ::close(results[0]);
    int status = 0;
    while (child > 0 && ::waitpid(child, &status, 0) < 0 && errno == EINTR) {
    }
    if (child > 0) forgetChild(child);
    if (asRoot) endProcessesOf(uid);
    if (child <= 0 || got != opened.size() || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        exposure.error = "cannot try the files as a throwaway user (" +
                         std::string(child <= 0 ? std::strerror(errno) : "the trying process failed") + ")";
        return exposure;
    }
    for (std::size_t i = 0; i < files.size(); ++i) {
        if (!opened[i]) continue;
        if (i >= fileCount) {
            exposure.passable.push_back(files[i].substr(0, files[i].size() - std::strlen("/.simlab-passage")));
            continue;
        }
        ++exposure.readableCount;
        exposure.readable.push_back(files[i]);
    }
    return exposure;
}

}  // namespace simlab::isolation
