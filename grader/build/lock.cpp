#include "simlab/build/lock.h"

#include <pwd.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "simlab/build/build.h"
#include "simlab/build/lab.h"
#include "simlab/common/errors.h"
#include "simlab/common/text.h"
#include "simlab/isolation/reach.h"

namespace simlab::engine {

namespace fs = std::filesystem;

namespace {

bool isOrUnder(const std::string& path, const std::string& folder) {
    return path == folder ||
           (path.size() > folder.size() && path.compare(0, folder.size(), folder) == 0 && path[folder.size()] == '/');
}

std::string normal(const std::string& path) {
    std::error_code error;
    std::string p = fs::absolute(path, error).lexically_normal().string();
    while (p.size() > 1 && p.back() == '/') p.pop_back();
    return p;
}

// Why `path` could not be closed, in words a course's staff can act on.
[[noreturn]] void cannotClose(const std::string& path, int error) {
    std::string why = std::strerror(error);
    if (error == EROFS) {
        why = "it is on a read-only file system: copy it to a folder simlab may change";
    } else if (error == EPERM || error == EACCES) {
        struct stat info {};
        std::string owner = "another user";
        if (::lstat(path.c_str(), &info) == 0) {
            if (const passwd* user = ::getpwuid(info.st_uid)) owner = user->pw_name;
            else owner = "user " + std::to_string(info.st_uid);
        }
        why = "it is " + owner + "'s: run simlab lock as " + owner + " or as root";
    }
    throw UsageError("cannot close " + printable(path) + " to other users (" + why +
                     "): simlab keeps hidden tests from a test's code by these modes where neither bubblewrap nor "
                     "Landlock runs");
}

// Sets the bits others have on `path` (not a link) to `others` (of S_IRWXO), leaving the owner's and the group's.
bool setOthers(const std::string& path, const struct stat& info, mode_t others) {
    const mode_t mode = info.st_mode & 07777;
    const mode_t wanted = (mode & ~S_IRWXO) | others;
    if (wanted == mode) return false;
    if (::chmod(path.c_str(), wanted) != 0) cannotClose(path, errno);
    return true;
}

}  // namespace

std::vector<std::string> lentOfPlaces(const Manifest& manifest) {
    std::vector<std::string> lent;
    auto add = [&](const Assignment& a) {
        for (const std::string& p : lentToTools(manifest, a)) lent.push_back(normal(p));
    };
    for (const Assignment& a : manifest.assignments) add(a);
    for (const auto& lab : manifest.labs) add(*lab);
    // The labs built in this simlab's cache, named or not in this run.
    std::error_code error;
    for (auto it = fs::directory_iterator(manifest.cacheDir + "/labs", error); !error && it != fs::directory_iterator();
         it.increment(error)) {
        const std::string declared = it->path().string() + "/build/simlab-lab.json";
        if (!fs::is_regular_file(declared, error)) continue;
        try {
            for (const Assignment& a : loadLabManifest(declared)) add(a);
        } catch (const UsageError&) {
            // A build that failed half-way declares nothing: nothing of it is lent.
        }
    }
    std::sort(lent.begin(), lent.end());
    lent.erase(std::unique(lent.begin(), lent.end()), lent.end());
    return lent;
}

LockSummary lockPlaces(const Manifest& manifest, const std::vector<std::string>& more) {
    std::vector<std::string> places = {manifest.sourceDir, manifest.buildDir, manifest.cacheDir, manifest.sampleClass,
                                       fs::path(manifest.path).parent_path().string()};
    if (manifest.installed) {
        for (const char* place : {"/lib/simlab", "/share/simlab"}) places.push_back(manifest.prefix + place);
    }
    for (const Assignment& a : manifest.assignments) places.push_back(a.dir);
    for (const std::string& lab : labsBuilt(manifest)) places.push_back(lab);  // every lab it built, named or not
    LockSummary summary;
    std::error_code error;
    const std::size_t course = places.size();
    for (const std::string& path : more) {
        if (!fs::exists(path, error)) throw UsageError("no folder " + printable(path) + " to close");
        summary.places.push_back(path);
        places.push_back(path);
        // A lab's folder: its build in the cache too.
        if (fs::is_regular_file(fs::path(path) / "CMakeLists.txt", error)) {
            const std::string build = labBuildFolder(manifest, path);
            if (fs::exists(build, error)) places.push_back(build);
        }
    }
    const std::size_t extra = places.size() - course;
    // Each place once (one inside another is walked with it), those named first: a folder that cannot be closed is
    // said of the folder the user named before anything of the course's.
    std::vector<std::string> named;
    for (const std::string& place : places) {
        if (!place.empty()) named.push_back(normal(place));
    }
    std::rotate(named.begin(), named.end() - static_cast<std::ptrdiff_t>(std::min(named.size(), extra)), named.end());
    places.clear();
    for (const std::string& p : named) {
        const bool inside = std::any_of(named.begin(), named.end(), [&](const std::string& q) { return q != p && isOrUnder(p, q); });
        if (!inside && std::find(places.begin(), places.end(), p) == places.end()) places.push_back(p);
    }
    const std::vector<std::string> lent = lentOfPlaces(manifest);
    auto isLent = [&](const std::string& p) {
        return std::any_of(lent.begin(), lent.end(), [&](const std::string& l) { return isOrUnder(p, l); });
    };
    auto leadsToLent = [&](const std::string& p) {
        return std::any_of(lent.begin(), lent.end(), [&](const std::string& l) { return isOrUnder(l, p) && l != p; });
    };
    auto close = [&](const std::string& p) {
        struct stat info {};
        if (::lstat(p.c_str(), &info) != 0 || S_ISLNK(info.st_mode)) return;
        const bool folder = S_ISDIR(info.st_mode);
        if (isLent(p)) {
            // Readable (a program runnable, a folder listable and passable) by the tools' throwaway users.
            const mode_t exec = folder || (info.st_mode & S_IXUSR) ? S_IXOTH : 0;
            setOthers(p, info, S_IROTH | exec);
            ++summary.lent;
        } else if (folder && leadsToLent(p)) {
            setOthers(p, info, S_IXOTH);
            ++summary.lent;
        } else {
            if (setOthers(p, info, 0)) ++summary.closed;
        }
    };
    for (const std::string& place : places) {
        const std::string& root = place;
        if (!fs::exists(fs::symlink_status(root, error))) continue;
        close(root);
        if (!fs::is_directory(fs::symlink_status(root, error))) continue;
        for (auto it = fs::recursive_directory_iterator(root, error); !error && it != fs::recursive_directory_iterator();
             it.increment(error)) {
            close(it->path().string());
        }
        if (error) throw UsageError("cannot list what is in " + printable(root) + " to close it: " + error.message());
    }
    if (summary.places.empty()) summary.places = {manifest.installed ? manifest.prefix : manifest.sourceDir};
    return summary;
}

}  // namespace simlab::engine
