#include "simlab/build/lab.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/common/text.h"
#include "simlab/isolation/process.h"

extern char** environ;

namespace simlab::engine {

namespace fs = std::filesystem;

namespace {

// A CMake bracket argument: nothing in it is read as CMake syntax.
std::string bracketed(const std::string& text) {
    if (text.find("]==]") != std::string::npos) throw UsageError("a path CMake cannot be given: " + printable(text));
    return "[==[" + text + "]==]";
}

// Where find_package(simlab) finds this simlab's package: an installation's lib/cmake/simlab, or its build folder.
std::string packageFolder(const Manifest& manifest) {
    return manifest.installed ? manifest.prefix + "/lib/cmake/simlab" : manifest.buildDir;
}

// Run a step of the lab's build (cmake, trusted) with its output appended to `log`; its last error line on failure.
void runStep(const std::vector<std::string>& argv, const std::string& dir, const std::string& log,
             const std::string& what) {
    std::ofstream out(log, std::ios::app);
    out << "$";
    for (const std::string& a : argv) out << " " << a;
    out << "\n" << std::flush;
    isolation::ProcessRequest request;
    request.argv = argv;
    for (char** variable = environ; *variable; ++variable) request.env.emplace_back(*variable);
    request.workDir = dir;
    request.limits.cpuSeconds = request.limits.wallSeconds = 3600;
    request.limits.memoryMiB = 1 << 16;
    request.limits.processes = 4096;
    request.limits.fileMiB = 1 << 12;
    request.limits.outputKiB = 1 << 20;
    request.keepOutput = 0;
    std::string firstError;
    request.onOutputLine = [&](const std::string& line) {
        out << line << '\n';
        if (firstError.empty() &&
            (line.find("error") != std::string::npos || line.find("Error") != std::string::npos)) {
            firstError = line;
        }
    };
    const isolation::ProcessResult result = isolation::runProcess(request);
    out.flush();
    if (!result.started) throw UsageError("cannot run " + argv.front() + ": " + result.error);
    if (!result.exitedCleanly()) {
        throw UsageError(what + " failed" + (firstError.empty() ? "" : ": " + printable(firstError.substr(0, 300))) +
                         " (all of it in " + log + ")");
    }
}

// `path` readable by others (a folder: all below it, its folders passable), and each folder from `top` down to it
// passable.
void lendToOthers(const std::string& path, const std::string& top) {
    std::error_code error;
    const auto lend = [&](const fs::path& p) {
        const bool folder = fs::is_directory(p, error);
        fs::permissions(p, folder ? fs::perms::others_read | fs::perms::others_exec : fs::perms::others_read,
                        fs::perm_options::add, error);
    };
    lend(path);
    if (fs::is_directory(path, error)) {
        for (auto it = fs::recursive_directory_iterator(path, error);
             !error && it != fs::recursive_directory_iterator(); it.increment(error)) {
            lend(it->path());
        }
    }
    for (fs::path up = fs::path(path).parent_path(); up.string().size() > top.size(); up = up.parent_path()) {
        fs::permissions(up, fs::perms::others_exec, fs::perm_options::add, error);
    }
}

}  // namespace

bool isLabFolder(const std::string& name) { return name == "." || name == ".." || name.find('/') != std::string::npos; }

std::string labBuildFolder(const Manifest& manifest, const std::string& dir) {
    const fs::path canonical = fs::canonical(dir);
    return manifest.cacheDir + "/labs/" + canonical.filename().string() + "-" +
           sha256Hex(canonical.string()).substr(0, 12);
}

std::vector<std::string> labsBuilt(const Manifest& manifest) {
    std::vector<std::string> labs;
    std::error_code error;
    for (auto it = fs::directory_iterator(manifest.cacheDir + "/labs", error); !error && it != fs::directory_iterator();
         it.increment(error)) {
        // Each build's CMakeLists.txt names its lab's folder (buildLab writes it), in brackets.
        std::ifstream in(it->path() / "project" / "CMakeLists.txt");
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const std::size_t at = text.find("simlab_add_lab([==[");
        const std::size_t end = at == std::string::npos ? at : text.find("]==])", at);
        if (end != std::string::npos) labs.push_back(text.substr(at + 19, end - at - 19));
    }
    return labs;
}

Assignment buildLab(const Manifest& manifest, const std::string& dir) {
    std::error_code error;
    if (!fs::is_directory(dir, error)) throw UsageError("no lab folder " + printable(dir));
    const fs::path lab = fs::canonical(dir);
    if (!fs::is_regular_file(lab / "CMakeLists.txt", error)) {
        throw UsageError(printable(lab.string()) +
                         " is not a lab's folder: it has no CMakeLists.txt calling "
                         "simlab_add_assignment (simlab assignment new makes one)");
    }
    if (manifest.kit.targets.empty()) {
        throw UsageError("this simlab (" + printable(manifest.path) +
                         ") was built without what a lab of one's own "
                         "builds against: build and install it again");
    }
    const std::string root = labBuildFolder(manifest, lab.string());
    // Private from the start, then passable (never listable) by others: without bubblewrap the compiler and the
    // linker run as throwaway users, who must reach the lab's contract, precompiled header and probe objects, and
    // those alone are lent to them after every build. The rest (the judge, the hidden tests' objects, what was
    // made of the solution, the log) is built private.
    fs::create_directories(fs::path(manifest.cacheDir).parent_path());
    for (const std::string& folder : {manifest.cacheDir, manifest.cacheDir + "/labs", root}) {
        createPrivateFolder(folder);
        fs::permissions(folder, fs::perms::owner_all | fs::perms::group_exec | fs::perms::others_exec);
    }
    // One build at a time: the shards of a class, or a cluster's tasks, may start on the lab together.
    const int lock = ::open((root + "/.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
    if (lock < 0 || ::flock(lock, LOCK_EX) != 0) throw UsageError("cannot lock " + root + "/.lock");
    struct Unlock {
        int fd;
        ~Unlock() { ::close(fd); }
    } unlock{lock};
    // Everything the build writes is its owner's alone (umask 077); what the sandbox's tools must read is lent below.
    struct Umask {
        mode_t old;
        ~Umask() { ::umask(old); }
    } umask{::umask(077)};
    const std::string project = root + "/project", build = root + "/build", log = root + "/build.log";
    fs::create_directories(project);
    const std::string lists = "# The lab in " + lab.string() + ", built against simlab " + manifest.version +
                              " (simlab/build/lab.h).\n"
                              "cmake_minimum_required(VERSION 3.25)\n"
                              "project(simlab_lab LANGUAGES CXX)\n"
                              "find_package(simlab " +
                              manifest.version + " EXACT REQUIRED CONFIG PATHS " + bracketed(packageFolder(manifest)) +
                              " NO_DEFAULT_PATH)\n"
                              "simlab_add_lab(" +
                              bracketed(lab.string()) + ")\n";
    std::string before;
    try {
        before = readFile(project + "/CMakeLists.txt");
    } catch (const std::exception&) {
    }
    if (before != lists) writeFileAtomically(project + "/CMakeLists.txt", lists);
    // The log may quote a hidden test's lines (a compiler's error): its owner's alone from the start.
    if (const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0600); fd >= 0) ::close(fd);
    ::chmod(log.c_str(), 0600);
    // Configured until it has generated a build system (a configure that failed leaves a cache and no Makefile).
    const bool first = !fs::exists(build + "/Makefile", error) && !fs::exists(build + "/build.ninja", error);
    if (first) {
        std::cerr << "simlab: building the lab in " << printable(lab.string()) << " against simlab " << manifest.version
                  << " (once; about a minute; the log: " << log << ")" << std::endl;
        runStep({manifest.cmake, "-S", project, "-B", build, "-DCMAKE_BUILD_TYPE=Release"}, root, log,
                "configuring the lab in " + printable(lab.string()));
    }
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    runStep({manifest.cmake, "--build", build, "-j", std::to_string(cores)}, root, log,
            "building the lab in " + printable(lab.string()));
    std::vector<Assignment> declared = loadLabManifest(build + "/simlab-lab.json");
    if (declared.size() != 1) {
        throw UsageError(printable(lab.string()) + " declares " + std::to_string(declared.size()) +
                         " assignments: a lab's folder declares one (simlab_add_assignment)");
    }
    // Lent to the compiler's and the linker's throwaway users: the contract, the precompiled header and the probe's
    // objects, and the folders on the way to them (passable, not listable). Nothing else of the build is theirs.
    const Assignment& a = declared.front();
    for (const std::string& secret : secretPaths(manifest, a)) {
        if (secret.rfind(root + "/", 0) == 0) closeToOthers(secret);  // a build made before it was built private
    }
    std::vector<std::string> lent = a.probeObjects;
    lent.insert(lent.end(), a.programObjects.begin(), a.programObjects.end());  // simlab build links the lab program
    lent.push_back(a.contractInclude);
    if (!a.precompiledHeader.empty()) lent.push_back(fs::path(a.precompiledHeader).parent_path().string());
    for (const std::string& path : lent) {
        if (path.rfind(root + "/", 0) == 0) lendToOthers(path, root);
    }
    return std::move(declared.front());
}

}  // namespace simlab::engine
