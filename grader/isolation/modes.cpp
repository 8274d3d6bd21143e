// The one place each mode's sandbox is built: what a sandboxed process sees of the filesystem (reach.h: the system,
// less simlab's places, what it is lent and its own folder), its namespaces and its capabilities under bubblewrap, its file rules
// under Landlock, its system-call filter, and which mode this machine allows.
#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include "internal.h"
#include "simlab/isolation/filter.h"
#include "simlab/isolation/reach.h"

namespace simlab::isolation {

namespace {

namespace fs = std::filesystem;

const char* const kSetpriv = "/usr/bin/setpriv";

// What the kernel shows in /proc that no test has business with - its memory, its log, the physical pages, the
// processor's memory ranges, the magic keys, the keyrings, the timers of every process - as Docker masks them.
// Where bubblewrap gives a process a /proc of its own, these are empty stand-ins; Landlock grants no part of /proc.
const char* const kProcFiles[] = {"/proc/kcore", "/proc/kmsg", "/proc/kpagecount", "/proc/kpageflags",
                                  "/proc/kpagecgroup", "/proc/mtrr", "/proc/sysrq-trigger", "/proc/keys",
                                  "/proc/key-users", "/proc/timer_list", "/proc/sched_debug", "/proc/latency_stats",
                                  "/proc/kallsyms", "/proc/vmallocinfo", "/proc/iomem", "/proc/ioports"};
const char* const kProcFolders[] = {"/proc/acpi", "/proc/scsi", "/proc/asound", "/proc/irq", "/proc/bus",
                                    "/proc/driver", "/proc/tty", "/proc/fs"};

bool isUnder(const std::string& path, const std::string& folder) {
    return path.size() > folder.size() && path.compare(0, folder.size(), folder) == 0 && path[folder.size()] == '/';
}

bool isOrUnder(const std::string& path, const std::string& folder) { return path == folder || isUnder(path, folder); }

// A path as the kernel resolves it (symbolic links followed) where it exists, else as written, made absolute.
std::string resolved(const std::string& path) {
    std::error_code error;
    const fs::path absolute = fs::absolute(path, error).lexically_normal();
    const fs::path real = fs::weakly_canonical(absolute, error);
    std::string text = (error ? absolute : real).string();
    while (text.size() > 1 && text.back() == '/') text.pop_back();
    return text;
}

bool inSystemFolder(const std::string& path) {
    return std::any_of(systemFolders().begin(), systemFolders().end(),
                       [&](const std::string& d) { return isOrUnder(path, d) || isOrUnder(path, resolved(d)); });
}

bool hidden(const std::string& path, const std::vector<std::string>& hiddenPaths) {
    return std::any_of(hiddenPaths.begin(), hiddenPaths.end(), [&](const std::string& h) { return isOrUnder(path, h); });
}

// What Landlock may grant of `folder` (a real path), hidden paths left out: the folder itself when nothing hidden
// lies in it, else each of its entries in turn (a link by what it leads to). Entries made after this are not
// granted, which costs a test nothing: the system does not change while it runs.
void grantable(const std::string& folder, const std::vector<std::string>& hiddenPaths, std::vector<std::string>& out,
               int depth = 0) {
    if (hidden(folder, hiddenPaths)) return;
    const bool holdsHidden =
        std::any_of(hiddenPaths.begin(), hiddenPaths.end(), [&](const std::string& h) { return isUnder(h, folder); });
    if (!holdsHidden || depth > 32) {
        out.push_back(folder);
        return;
    }
    DIR* dir = ::opendir(folder.c_str());
    if (!dir) return;
    std::vector<std::string> entries;
    while (const struct dirent* entry = ::readdir(dir)) {
        const std::string name = entry->d_name;
        if (name != "." && name != "..") entries.push_back(folder + "/" + name);
    }
    ::closedir(dir);
    for (const std::string& entry : entries) {
        struct stat info {};
        if (::lstat(entry.c_str(), &info) != 0) continue;
        if (S_ISLNK(info.st_mode)) {
            // A rule follows the link: what it leads to is what would be granted.
            const std::string target = resolved(entry);
            if (target != entry && !hidden(target, hiddenPaths) &&
                std::none_of(hiddenPaths.begin(), hiddenPaths.end(),
                             [&](const std::string& h) { return isUnder(h, target); })) {
                out.push_back(entry);
            }
            continue;
        }
        grantable(entry, hiddenPaths, out, depth + 1);
    }
}

// Landlock's readable system: each system folder, less what is hidden, worked out once per set of hidden paths
// (it lists folders).
std::vector<std::string> readableSystem(const std::vector<std::string>& hiddenPaths) {
    static std::mutex lock;
    static std::vector<std::string> madeFor, made;
    static bool done = false;
    std::lock_guard<std::mutex> guard(lock);
    if (done && madeFor == hiddenPaths) return made;
    made.clear();
    std::set<std::string> seen;
    for (const std::string& folder : systemFolders()) {
        const std::string real = resolved(folder);
        std::error_code error;
        if (!fs::is_directory(real, error) || !seen.insert(real).second) continue;
        grantable(real, hiddenPaths, made);
    }
    madeFor = hiddenPaths;
    done = true;
    return made;
}

}  // namespace

const std::string* filterFor(const ProcessRequest& r) {
    const std::string& program = r.studentCode ? filter::studentProgram(true) : filter::toolProgram();
    return program.empty() ? nullptr : &program;
}

// bubblewrap's arguments: the system's programs and libraries, read-only, with what simlab hides covered by empty
// stand-ins where the system holds it; what is lent at its own path; a private /tmp and /dev/shm of at most the
// file-size limit; the working directory, writable (or a scratch one); no network, no view of other processes; a
// /proc of its own with the kernel's own files masked. With `dropTo` (simlab is root), bubblewrap itself runs as
// root - so that it can lend paths below folders only root may enter - keeping for the command only what setpriv
// needs to make it the throwaway user `dropTo` with no capability at all. A probe's server (r.serveTests) stays
// root with CAP_SETUID, CAP_SETGID and CAP_SETPCAP alone, to start each test's child as a user of its own that
// drops them.
std::vector<std::string> bubblewrapArguments(const std::string& bwrap, const ProcessRequest& r, uid_t dropTo,
                                             bool seccomp) {
    const std::vector<std::string>& system = systemFolders();
    std::vector<std::string> a = {bwrap};
    if (dropTo || r.serveTests) {
        a.insert(a.end(), {"--unshare-pid", "--unshare-net", "--unshare-ipc", "--unshare-uts", "--unshare-cgroup-try"});
        // bubblewrap run as root would keep every capability root has: none but those the handing over needs -
        // to become another user, to empty the bounding set, and (for setpriv) to enter the user's own folder,
        // which bubblewrap does before setpriv runs; setpriv leaves the command none of them.
        a.insert(a.end(), {"--cap-drop", "ALL", "--cap-add", "CAP_SETUID", "--cap-add", "CAP_SETGID", "--cap-add",
                           "CAP_SETPCAP"});
        if (dropTo) a.insert(a.end(), {"--cap-add", "CAP_DAC_READ_SEARCH"});
    } else {
        a.insert(a.end(), {"--unshare-all", "--cap-drop", "ALL"});
    }
    // A session of its own, with no terminal (simlab's child has one already; this holds whatever bubblewrap does).
    a.insert(a.end(), {"--die-with-parent", "--new-session"});
    for (const std::string& dir : system) {
        std::error_code error;
        if (fs::is_symlink(dir, error)) a.insert(a.end(), {"--symlink", fs::read_symlink(dir, error).string(), dir});
        else if (fs::is_directory(dir, error)) a.insert(a.end(), {"--ro-bind", dir, dir});
    }
    // What simlab hides, where a system folder holds it: an empty folder (or file) in its place.
    const std::vector<std::string> hiddenPaths = outOfReach();
    std::vector<std::string> masked;
    for (const std::string& path : hiddenPaths) {
        std::error_code error;
        if (!inSystemFolder(path) || !fs::exists(path, error) || hidden(fs::path(path).parent_path(), masked)) continue;
        masked.push_back(path);
        if (fs::is_directory(path, error)) a.insert(a.end(), {"--perms", "0755", "--tmpfs", path});
        else a.insert(a.end(), {"--ro-bind", "/dev/null", path});
    }
    const std::string scratch = std::to_string(static_cast<unsigned long long>(r.limits.fileMiB) << 20);
    // The system's files outside its folders (reach.h), each where it is.
    a.insert(a.end(), {"--perms", "0755", "--dir", "/etc"});
    for (const std::string& file : systemFiles()) {
        if (!hidden(resolved(file), hiddenPaths)) a.insert(a.end(), {"--ro-bind-try", file, file});
    }
    a.insert(a.end(), {"--proc", "/proc", "--dev", "/dev"});
    for (const char* file : kProcFiles) {
        if (::access(file, F_OK) == 0) a.insert(a.end(), {"--ro-bind", "/dev/null", file});
    }
    for (const char* folder : kProcFolders) {
        struct stat info {};
        if (::stat(folder, &info) == 0 && S_ISDIR(info.st_mode)) a.insert(a.end(), {"--perms", "0555", "--tmpfs", folder});
    }
    if (r.serveTests) {
        // A server's tests write in their own folders alone (their TMPDIR): a shared /tmp would carry notes between
        // them.
        a.insert(a.end(), {"--perms", "0755", "--dir", "/dev/shm", "--perms", "0755", "--dir", "/tmp"});
    } else {
        a.insert(a.end(), {"--perms", "1777", "--size", scratch, "--tmpfs", "/dev/shm", "--perms", "1777", "--size",
                           scratch, "--tmpfs", "/tmp"});
    }
    // The folders leading to what is lent, made enterable (bubblewrap would make them for root alone).
    std::set<std::string> made;
    auto leadTo = [&](const std::string& path) {
        std::vector<std::string> folders;
        for (fs::path p = fs::path(path).parent_path(); p.has_relative_path(); p = p.parent_path()) folders.push_back(p);
        for (auto f = folders.rbegin(); f != folders.rend(); ++f) {
            // A system folder is there already, unless it lies in a hidden one (an installation in /usr/local).
            const bool isSystem = std::any_of(system.begin(), system.end(), [&](const std::string& d) {
                return isOrUnder(*f, d);
            }) && !hidden(*f, masked);
            if (isSystem || *f == "/tmp" || *f == "/dev" || *f == "/proc" || !made.insert(*f).second) continue;
            a.insert(a.end(), {"--perms", "0755", "--dir", *f});
        }
    };
    for (const std::string& path : r.readOnlyPaths) {
        leadTo(path);
        a.insert(a.end(), {"--ro-bind", path, path});
    }
    leadTo(r.workDir);
    // A server's folder: root's, where only its group (root's, which the server's tests make their folders with)
    // may add, and anyone may pass through.
    if (r.scratchWorkDir) {
        a.insert(a.end(), {"--perms", r.serveTests ? "0731" : "1777", "--size", scratch, "--tmpfs", r.workDir});
    } else {
        a.insert(a.end(), {"--bind", r.workDir, r.workDir});
    }
    if (seccomp) a.insert(a.end(), {"--seccomp", std::to_string(kSeccompFd)});
    a.insert(a.end(), {"--chdir", r.workDir, "--"});
    if (dropTo) {
        const std::string id = std::to_string(dropTo);
        a.insert(a.end(), {kSetpriv, "--reuid=" + id, "--regid=" + id, "--clear-groups", "--inh-caps=-all",
                           "--ambient-caps=-all", "--bounding-set=-all", "--"});
    }
    return a;
}

landlock::FileRules fileRulesFor(const ProcessRequest& r) {
    landlock::FileRules rules;
    const std::vector<std::string> hiddenPaths = outOfReach();
    rules.readable = readableSystem(hiddenPaths);
    for (const std::string& file : systemFiles()) {
        if (!hidden(resolved(file), hiddenPaths)) rules.readable.push_back(file);
    }
    rules.readable.insert(rules.readable.end(), r.readOnlyPaths.begin(), r.readOnlyPaths.end());
    rules.writable = {r.workDir};
    rules.devices = systemDevices();
    return rules;
}

const SandboxSupport& sandboxSupport() {
    static SandboxSupport support;
    static std::once_flag probed;
    std::call_once(probed, [] {
        support.ownUser = ::geteuid() == 0;
        support.filter = !filter::toolProgram().empty() && !filter::studentProgram(true).empty();
        const char* candidates[] = {"/usr/bin/bwrap", "/bin/bwrap", "/usr/local/bin/bwrap"};
        std::string bwrap;
        // SIMLAB_NO_BUBBLEWRAP=1 tries the fallback on a machine that has bubblewrap.
        const char* without = std::getenv("SIMLAB_NO_BUBBLEWRAP");
        for (const char* c : candidates) {
            if (!(without && std::string(without) == "1") && ::access(c, X_OK) == 0) {
                bwrap = c;
                break;
            }
        }
        support.rootBubblewrap = support.ownUser && ::access(kSetpriv, X_OK) == 0;
        // Each way is tried as tests will use it: as a throwaway user when we are root, in a folder of its own.
        auto works = [](Launch launch, const std::function<std::vector<std::string>(const ProcessRequest&)>& argvFor) {
            char dir[] = "/tmp/simlab-probe-XXXXXX";
            if (!::mkdtemp(dir)) return false;
            ProcessRequest probe;
            probe.workDir = dir;
            probe.env = childEnvironment();
            probe.limits.fileMiB = 1;
            launch.argv = argvFor(probe);
            launch.parent = ::getpid();
            if (launch.uid != 0 && ::chown(dir, launch.uid, launch.uid) != 0) launch.dropUser = false;
            const bool ok = launchProcess(probe, launch).exitedCleanly();
            ::rmdir(dir);
            if (launch.uid != 0) endProcessesOf(launch.uid);
            return ok;
        };
        if (!bwrap.empty()) {
            // As root, bubblewrap hands over to the user itself (or, without setpriv, runs as that user from the
            // start); as ourselves otherwise.
            Launch launch;
            launch.uid = support.ownUser ? freshUser() : 0;
            launch.dropUser = support.ownUser && !support.rootBubblewrap;
            const uid_t handOver = support.rootBubblewrap ? launch.uid : 0;
            support.bubblewrap = works(launch, [&](const ProcessRequest& probe) {
                std::vector<std::string> argv = bubblewrapArguments(bwrap, probe, handOver, false);
                argv.push_back("/bin/true");
                return argv;
            });
        }
        // SIMLAB_NO_LANDLOCK=1 tries the last fallback on a machine that has Landlock.
        const char* noLandlock = std::getenv("SIMLAB_NO_LANDLOCK");
        const bool noLandlockWanted = noLandlock && std::string(noLandlock) == "1";
        if (!support.bubblewrap && landlock::abi() > 0 && !noLandlockWanted) {
            Launch launch;
            launch.uid = support.ownUser ? freshUser() : 0;
            launch.dropUser = support.ownUser;
            ProcessRequest rules;
            rules.workDir = "/tmp";
            launch.filter = filterFor(rules);
            landlock::FileRules trial;
            trial.readable = systemFolders();
            trial.writable = {"/tmp"};
            launch.ruleset = landlock::makeRuleset(trial, nullptr);
            support.landlock = launch.ruleset >= 0 && works(launch, [](const ProcessRequest&) {
                return std::vector<std::string>{"/bin/true"};
            });
            if (launch.ruleset >= 0) ::close(launch.ruleset);
        }
        const std::string user = support.ownUser ? "a user of its own for each process" : "running as you";
        const std::string calls = support.filter ? ", system calls filtered" : "";
        if (support.bubblewrap) {
            support.bwrap = bwrap;
            support.mode = "bubblewrap";
            support.summary = "bubblewrap: a filesystem of its own, no network, its own processes; " + user + calls;
        } else if (support.landlock) {
            support.mode = "Landlock";
            support.summary = "Landlock: only the system and what the test is lent can be read, no network; " + user +
                              calls;
            // Why not bubblewrap, in the same line: in a container (Docker's defaults, a dev container, Codespaces)
            // the namespaces it needs are withheld.
            if (!bwrap.empty()) support.summary += " (bubblewrap cannot create namespaces here, as in most containers)";
        } else {
            support.mode = "limits only";
            support.summary = "limits only: CPU, memory, processes, output and files capped; " + user + calls;
            const bool noBubblewrap = without && std::string(without) == "1";
            const bool noLandlock = noLandlockWanted && landlock::abi() > 0;
            const std::string why =
                (noBubblewrap ? std::string("SIMLAB_NO_BUBBLEWRAP=1 leaves bubblewrap out")
                 : bwrap.empty() ? std::string("bubblewrap is not installed")
                                 : std::string("bubblewrap cannot create namespaces here (as in most containers)")) +
                (noLandlock ? " and SIMLAB_NO_LANDLOCK=1 leaves Landlock out" : " and this kernel offers no Landlock");
            support.warning = why + ": student code " +
                              (support.ownUser ? "can read every file other users can"
                                               : "runs as you and can read your files") +
                              " (install bubblewrap, or grade as root once simlab lock has closed its places)";
        }
    });
    return support;
}

std::vector<std::string> readableInSandbox(const std::vector<std::string>& paths, const std::vector<std::string>& lent) {
    // Each path, and of a folder its files too (up to 200 of each, named here: a folder others may pass through but
    // not list can still hold files they can open by name). A file found readable counts for its folder.
    std::vector<std::string> existing, tried;
    std::map<std::string, std::string> folderOf;
    for (const std::string& path : paths) {
        std::error_code error;
        if (path.empty() || !fs::exists(path, error)) continue;
        existing.push_back(path);
        tried.push_back(path);
        if (!fs::is_directory(path, error)) continue;
        int files = 0;
        for (auto it = fs::recursive_directory_iterator(path, fs::directory_options::skip_permission_denied, error);
             !error && it != fs::recursive_directory_iterator() && files < 200; it.increment(error)) {
            if (!it->is_regular_file(error)) continue;
            // A file asked about itself is answered for itself.
            if (std::find(paths.begin(), paths.end(), it->path().string()) != paths.end()) continue;
            tried.push_back(it->path().string());
            folderOf[it->path().string()] = path;
            ++files;
        }
    }
    if (existing.empty()) return {};
    char dir[] = "/tmp/simlab-audit-XXXXXX";
    if (!::mkdtemp(dir)) return {};
    // Opened, not merely looked at: access(2) would answer by the permissions alone, past Landlock.
    ProcessRequest request;
    request.argv = {"/bin/sh", "-c",
                    "for f; do if [ -d \"$f\" ]; then ls -- \"$f\" >/dev/null 2>&1 && echo \"$f\"; "
                    "else head -c 1 -- \"$f\" >/dev/null 2>&1 && echo \"$f\"; fi; done",
                    "simlab-audit"};
    request.argv.insert(request.argv.end(), tried.begin(), tried.end());
    request.env = childEnvironment({"LC_ALL=C"});
    request.workDir = dir;
    request.isolate = true;
    request.readOnlyPaths = lent;
    request.scratchWorkDir = true;
    request.limits.cpuSeconds = 10;
    request.limits.wallSeconds = 60;
    request.keepOutput = 1 << 20;
    const ProcessResult result = runProcess(request);
    std::error_code ignored;
    fs::remove_all(dir, ignored);
    std::vector<std::string> readable;
    std::istringstream lines(result.output);
    for (std::string line; std::getline(lines, line);) {
        const auto folder = folderOf.find(line);
        const std::string path = folder != folderOf.end() ? folder->second : line;
        if (std::find(existing.begin(), existing.end(), path) != existing.end() &&
            std::find(readable.begin(), readable.end(), path) == readable.end()) {
            readable.push_back(path);
        }
    }
    return readable;
}

}  // namespace simlab::isolation
