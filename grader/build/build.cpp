#include "simlab/build/build.h"
#include "simlab/common/errors.h"

#include <pwd.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <map>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <set>
#include <sstream>
#include <cstring>

#include "simlab/isolation/elf.h"
#include "simlab/common/files.h"
#include "simlab/isolation/process.h"
#include "simlab/common/text.h"

namespace fs = std::filesystem;

namespace simlab::engine {

namespace {

// Compilers and linkers are trusted, but what they read is not: limits stop an #include of /dev/zero or a
// constexpr evaluation that never ends. A lab's one file compiles in about 2 s of CPU time against the precompiled
// header and links in under 1 s: the limits leave ten times that and more. Their CPU time decides; the wall clock
// is a net for a machine under load.
Limits toolLimits() {
    Limits l;
    l.wallSeconds = 180;
    l.cpuSeconds = 30;
    l.memoryMiB = 4096;
    l.outputKiB = 1024;
    l.fileMiB = 64;  // an object is a few MiB: a .fill of 500 MiB in inline assembly stops here
    l.processes = 16;
    return l;
}

// Why a tool was stopped by one of the course's limits, in one line; empty when no limit stopped it. A stopped
// tool says nothing about the file's correctness: its outcome is not kept in the cache.
std::string stoppedByLimit(const char* tool, const isolation::ProcessResult& run, const Limits& limits) {
    char line[256];
    // Memory first, as for a test: when both limits were past at one poll, the CPU time includes the kernel's
    // work of handing out that memory.
    if (run.memoryLimit || run.output.find("out of memory") != std::string::npos ||
        run.output.find("virtual memory exhausted") != std::string::npos) {
        std::snprintf(line, sizeof line, "the %s was stopped: it needed more than the %ld MiB of memory the course "
                      "allows", tool, static_cast<long>(limits.memoryMiB));
    } else if (run.cpuTimeout) {
        std::snprintf(line, sizeof line, "the %s was stopped after %.0f s of CPU time, the course's limit for one "
                      "file (something evaluated at compile time that does not end: constexpr, templates?)",
                      tool, limits.cpuSeconds);
    } else if (run.wallTimeout) {
        std::snprintf(line, sizeof line, "the %s was stopped after %.0f s of wall-clock time", tool, limits.wallSeconds);
    } else if (run.outputLimit) {
        std::snprintf(line, sizeof line, "the %s was stopped: it printed more than %ld KiB", tool,
                      static_cast<long>(limits.outputKiB));
    } else if (run.diskLimit) {
        std::snprintf(line, sizeof line, "the %s was stopped: its files took more than %ld MiB", tool,
                      static_cast<long>(3 * limits.fileMiB));
    } else {
        return "";
    }
    return line;
}

// Tools run in the C locale, so messages quote with plain ASCII; part of the cache key, as it shapes the log.
const char* const kToolLocale = "LC_ALL=C";

// The lines that matter in a linker's complaint: what is undefined or defined twice.
std::string linkSummary(const std::string& log) {
    std::istringstream lines(log);
    std::set<std::string> seen;
    std::string line, summary;
    for (const char* marker : {"undefined reference to ", "multiple definition of "}) {
        lines.clear();
        lines.seekg(0);
        while (std::getline(lines, line)) {
            const auto at = line.find(marker);
            if (at == std::string::npos) continue;
            const std::string what = line.substr(at);
            if (seen.insert(what).second) summary += what + "\n";
        }
    }
    return summary.empty() ? log : summary;
}

// The folders a compile command reads headers from (-I and -isystem folders, and the folder of an -include) that
// the sandbox must lend it.
std::vector<std::string> includeFolders(const std::vector<std::string>& command) {
    std::vector<std::string> folders;
    for (std::size_t i = 0; i < command.size(); ++i) {
        const std::string& arg = command[i];
        if (arg.rfind("-I", 0) == 0 && arg.size() > 2) folders.push_back(arg.substr(2));
        if ((arg == "-isystem" || arg == "-I") && i + 1 < command.size()) folders.push_back(command[i + 1]);
        if ((arg == "-include" || arg == "-include-pch") && i + 1 < command.size()) {
            folders.push_back(fs::path(command[i + 1]).parent_path());
        }
    }
    // What every sandbox shows already (the system's folders, where nothing is hidden) is not lent.
    folders.erase(std::remove_if(folders.begin(), folders.end(),
                                 [&](const std::string& f) { return isolation::visibleInSandboxes(f); }),
                  folders.end());
    return folders;
}


// Every input the linker reads for the course's side of a probe (the C runtime's pieces among them) and every
// shared library the result loads: the trace of a trial link that leaves the student's symbols undefined.
std::vector<std::string> courseFiles(const Manifest& manifest, const Assignment& assignment) {
    TempDir trial("simlab-symbols-");
    isolation::ProcessRequest request;
    request.argv = manifest.link;
    request.argv.insert(request.argv.end(), {"-o", trial.path() + "/probe", "-Wl,--no-as-needed", "-Wl,--trace",
                                             "-Wl,--unresolved-symbols=ignore-all"});
    request.argv.insert(request.argv.end(), assignment.probeObjects.begin(), assignment.probeObjects.end());
    request.argv.insert(request.argv.end(), manifest.probeLibraries.begin(), manifest.probeLibraries.end());
    request.env = isolation::childEnvironment({kToolLocale});
    request.workDir = trial.path();
    request.limits = toolLimits();
    request.keepOutput = 1 << 20;
    const isolation::ProcessResult linked = isolation::runProcess(request);
    if (!linked.exitedCleanly()) throw std::runtime_error("cannot link the course's probe: " + linked.output);
    std::set<std::string> files;
    std::istringstream lines(linked.output);
    for (std::string line; std::getline(lines, line);) {
        if (!line.empty() && line[0] == '/') files.insert(line.substr(0, line.find(' ')));
    }
    request.argv = {"/usr/bin/ldd", trial.path() + "/probe"};
    const isolation::ProcessResult loaded = isolation::runProcess(request);
    std::istringstream libraries(loaded.output);
    for (std::string line; std::getline(libraries, line);) {
        const std::size_t arrow = line.find("=> /"), slash = line.find_first_not_of(" \t");
        std::string path = arrow != std::string::npos ? line.substr(arrow + 3) : slash != std::string::npos && line[slash] == '/' ? line.substr(slash) : "";
        path = path.substr(0, path.find(' '));
        if (!path.empty()) files.insert(path);
    }
    return {files.begin(), files.end()};
}

}  // namespace

Builder::Builder(const Manifest& manifest) : manifest_(manifest), cacheDir_(manifest.cacheDir + "/objects") {
    // Made once, here, before any job writes into it: each folder of the path in turn, one another simlab made
    // meanwhile taken as made (create_directories may report such a race as a failure, and a job would then find
    // no folder to write its object into). Every student's source and object is kept in it: simlab's alone (the
    // linker gets a copy of the one it needs).
    fs::path made;
    for (const fs::path& part : fs::absolute(cacheDir_).lexically_normal()) {
        made /= part;
        if (::mkdir(made.c_str(), 0755) != 0 && errno != EEXIST) {
            throw std::runtime_error("cannot make the object cache's folder " + made.string() + ": " +
                                     std::strerror(errno));
        }
    }
    std::error_code ignored;
    if (!fs::is_directory(cacheDir_, ignored))
        throw std::runtime_error("the object cache " + cacheDir_ + " is not a folder");
    fs::permissions(cacheDir_, fs::perms::owner_all, ignored);
    if (!manifest.installed) checkPrecompiledHeader();  // before anything is built or said to be
    trimObjectCache(cacheDir_);
}

std::uintmax_t objectCacheCap() {
    if (const char* mib = std::getenv("SIMLAB_CACHE_MIB"); mib && *mib) {
        char* end = nullptr;
        const double value = std::strtod(mib, &end);
        if (end && *end == '\0' && value >= 1 && value <= 1e7) return static_cast<std::uintmax_t>(value) << 20;
        throw UsageError("SIMLAB_CACHE_MIB is '" + printable(mib) + "': a size in MiB, 1 or more");
    }
    return std::uintmax_t(2048) << 20;
}

void trimObjectCache(const std::string& dir) {
    // An entry is a key's files (<key>.o, .cpp, .log, .failed); its last use is its source's time, renewed at
    // each hit. Entries used in the last hour stay whatever the size: another simlab may be reading them.
    struct Entry {
        std::uintmax_t bytes = 0;
        fs::file_time_type used = fs::file_time_type::min();
        std::vector<fs::path> files;
    };
    std::map<std::string, Entry> entries;
    std::uintmax_t total = 0;
    std::error_code error;
    for (fs::directory_iterator it(dir, error), end; !error && it != end; it.increment(error)) {
        if (!it->is_regular_file(error)) continue;
        const std::string name = it->path().filename().string();
        Entry& e = entries[name.substr(0, name.find('.'))];
        const std::uintmax_t bytes = it->file_size(error);
        if (error) continue;
        e.bytes += bytes;
        total += bytes;
        e.used = std::max(e.used, it->last_write_time(error));
        e.files.push_back(it->path());
    }
    const std::uintmax_t cap = objectCacheCap();
    if (total <= cap) return;
    std::vector<const Entry*> oldest;
    for (const auto& [key, e] : entries) oldest.push_back(&e);
    std::sort(oldest.begin(), oldest.end(), [](const Entry* a, const Entry* b) { return a->used < b->used; });
    const fs::file_time_type recent = fs::file_time_type::clock::now() - std::chrono::hours(1);
    for (const Entry* e : oldest) {
        if (total <= cap / 10 * 8 || e->used > recent) break;  // down to 80 %, so that it is not trimmed each run
        for (const fs::path& file : e->files) fs::remove(file, error);
        total -= e->bytes;
    }
}

namespace {

// The precompiled header files a compile command reads (GCC's -include X reads X.gch; clang's -include-pch X).
std::vector<std::string> precompiledHeaders(const std::vector<std::string>& compile) {
    std::vector<std::string> files;
    for (std::size_t i = 0; i + 1 < compile.size(); ++i) {
        if (compile[i] == "-include") files.push_back(compile[i + 1] + ".gch");
        if (compile[i] == "-include-pch") files.push_back(compile[i + 1]);
    }
    return files;
}

// The contract's headers, every file below its folder, in name order.
std::vector<std::string> contractHeaders(const Assignment& assignment) {
    std::error_code error;
    std::vector<std::string> headers;
    for (auto it = fs::recursive_directory_iterator(assignment.contractInclude, error);
         it != fs::recursive_directory_iterator(); it.increment(error)) {
        if (it->is_regular_file(error)) headers.push_back(it->path().string());
    }
    std::sort(headers.begin(), headers.end());
    return headers;
}

}  // namespace

std::string Builder::objectKey(const Assignment& assignment, const std::string& fileName,
                               const std::string& sourceText) const {
    ensurePrecompiledHeader(manifest_, assignment);
    Hash h;
    // The file's name is the compiler's too: its messages and every __FILE__ (a SIMLAB_TODO's "not done yet
    // (NewtonsApple.cpp:40)") carry it, so the same bytes under another name are another object.
    h.add(fileName).add(sourceText).add(manifest_.version).add(kToolLocale).add(assignment.contractInclude);
    for (const std::string& part : assignment.compile) h.add(part);
    for (const std::string& file : precompiledHeaders(assignment.compile)) h.addFileStamp(file);
    for (const std::string& header : contractHeaders(assignment)) h.addFileStamp(header);
    return h.hex();
}

std::string Builder::graderKey(const Assignment& assignment) const {
    Hash h;
    h.add(objectKey(assignment, "", ""));
    for (const std::string& part : manifest_.link) h.add(part);
    for (const std::string& file : assignment.probeObjects) h.addFileStamp(file);
    for (const std::string& file : manifest_.probeLibraries) h.addFileStamp(file);
    for (const std::string& flag : manifest_.probeLink) h.add(flag);
    h.addFileStamp(assignment.judge);
    return h.hex();
}

std::string Builder::gradingKey(const Assignment& assignment) const {
    const auto portable = [&](std::string text) {
        // The build folder first: it may lie inside the source folder.
        for (const auto& [folder, name] : {std::pair<std::string, std::string>{manifest_.buildDir, "<build>"},
                                           std::pair<std::string, std::string>{manifest_.sourceDir, "<source>"}}) {
            if (folder.empty()) continue;
            for (std::size_t at = text.find(folder); at != std::string::npos; at = text.find(folder, at + name.size())) {
                text.replace(at, folder.size(), name);
            }
        }
        return text;
    };
    ensurePrecompiledHeader(manifest_, assignment);
    Hash h;
    h.add(manifest_.version).add(kToolLocale);
    for (const std::string& part : assignment.compile) h.add(portable(part));
    for (const std::string& file : precompiledHeaders(assignment.compile)) h.addFileContent(file);
    for (const std::string& header : contractHeaders(assignment)) {
        h.add(fs::path(header).lexically_relative(assignment.contractInclude).string()).addFileContent(header);
    }
    for (const std::string& part : manifest_.link) h.add(portable(part));
    for (const std::string& file : assignment.probeObjects) h.addFileContent(file);
    for (const std::string& file : manifest_.probeLibraries) h.addFileContent(file);
    for (const std::string& flag : manifest_.probeLink) h.add(portable(flag));
    h.addFileContent(assignment.judge);
    return h.hex();
}

const isolation::CourseSymbols& Builder::courseSymbols(const Assignment& assignment) const {
    static std::mutex lock;
    static std::map<std::string, isolation::CourseSymbols> known;
    const std::string key = graderKey(assignment);
    std::lock_guard<std::mutex> guard(lock);
    if (const auto found = known.find(key); found != known.end()) return found->second;
    isolation::CourseSymbols& symbols = known[key];
    // Kept by the build's key, with the build where it may be written (it depends on the build alone, and a new
    // $SIMLAB_CACHE, as each class may have, would read every course library again), else in the cache beside the
    // objects' folder.
    const std::string name = "/course-symbols-" + key + ".txt";
    std::vector<std::string> folders = {manifest_.cacheDir};
    if (!manifest_.installed && manifest_.buildDir + "/cache" != manifest_.cacheDir) {
        folders.insert(folders.begin(), manifest_.buildDir + "/cache");
    }
    std::string cached;
    for (const std::string& folder : folders) {
        if (fs::exists(folder + name)) cached = folder + name;
    }
    if (!cached.empty()) {
        // One line per symbol: six flags (defined, strong, inObjects, inLibraries, required, referenced), a tab,
        // the name, a tab, where it is from.
        std::istringstream lines(readFile(cached));
        for (std::string line; std::getline(lines, line);) {
            const std::size_t tab = line.find('\t', 7);
            if (line.size() < 8 || line[6] != '\t' || tab == std::string::npos) continue;
            isolation::CourseSymbol& s = symbols[line.substr(7, tab - 7)];
            s.defined = line[0] == '1';
            s.strong = line[1] == '1';
            s.inObjects = line[2] == '1';
            s.inLibraries = line[3] == '1';
            s.required = line[4] == '1';
            s.referenced = line[5] == '1';
            s.from = line.substr(tab + 1);
        }
        return symbols;
    }
    std::set<std::string> objectsNeed;  // strong references in the course's objects
    for (const std::string& file : courseFiles(manifest_, assignment)) {
        isolation::ElfObject elf;
        try {
            elf = isolation::readElfFile(file);
        } catch (const std::exception&) {
            continue;  // a linker script (libc.so is one), not code
        }
        const bool ours = std::find(assignment.probeObjects.begin(), assignment.probeObjects.end(), file) !=
                          assignment.probeObjects.end();
        const std::string from = ours ? "course" : fs::path(file).filename().string();
        for (const isolation::ElfSymbol& s : elf.defined) {
            isolation::CourseSymbol& entry = symbols[s.name];
            if (!entry.defined || (s.strong && !entry.strong)) entry.from = from;
            entry.defined = true;
            entry.strong = entry.strong || s.strong;
            (ours ? entry.inObjects : entry.inLibraries) = true;
        }
        for (const isolation::ElfSymbol& s : elf.undefined) {
            symbols[s.name].referenced = true;
            if (ours && s.strong) objectsNeed.insert(s.name);
        }
    }
    for (auto& [name, s] : symbols) s.required = !s.defined && objectsNeed.count(name);
    std::string text;
    for (const auto& [name, s] : symbols) {
        text += std::string(1, s.defined ? '1' : '0') + (s.strong ? '1' : '0') + (s.inObjects ? '1' : '0') +
                (s.inLibraries ? '1' : '0') + (s.required ? '1' : '0') + (s.referenced ? '1' : '0') + "\t" + name +
                "\t" + s.from + "\n";
    }
    for (const std::string& folder : folders) {
        try {
            std::error_code ignored;
            fs::create_directories(folder, ignored);
            writePrivateAtomically(folder + name, text);
            break;
        } catch (const std::exception&) {
            if (folder == folders.back()) throw;  // the cache is simlab's own: it must take it
        }
    }
    return symbols;
}

BuildResult Builder::compile(const Assignment& assignment, const std::string& name, const std::string& text,
                             const std::string& workDir, std::string* object) const {
    BuildResult result;
    result.stage = "compile";
    const std::string key = objectKey(assignment, name, text);
    const std::string cached = cacheDir_ + "/" + key + ".o";
    const std::string cachedLog = cacheDir_ + "/" + key + ".log";
    const std::string cachedFailure = cacheDir_ + "/" + key + ".failed";
    const std::string cachedSource = cacheDir_ + "/" + key + ".cpp";
    *object = cached;
    // The key is a strong hash; the source kept beside the object makes sure all the same that it is this file's.
    const bool same = fs::exists(cachedSource) && readFile(cachedSource) == text;
    if (same && (fs::exists(cached) || fs::exists(cachedFailure))) {
        std::error_code ignored;
        fs::last_write_time(cachedSource, fs::file_time_type::clock::now(), ignored);  // used now (trimObjectCache)
        result.cached = true;
        result.ok = fs::exists(cached);
        const std::string log = fs::exists(cachedLog) ? readFile(cachedLog) : "";
        (result.ok ? result.warnings : result.log) = log;
        return result;
    }

    const std::string output = workDir + "/" + key + ".o";
    const isolation::ProcessResult run = runCompiler(assignment, name, text, workDir, output);
    result.compileSeconds = run.wallSeconds;
    if (run.interrupted) {
        result.interrupted = true;
        return result;
    }
    const std::string limit = stoppedByLimit("compiler", run, toolLimits());
    result.ok = limit.empty() && run.exitedCleanly() && fs::exists(output);
    std::string log = run.started ? run.output : run.error;
    if (!limit.empty()) {
        log = limit + "\n" + log;
        result.stoppedByLimit = true;
    } else if (!result.ok && run.signal) {
        log = "the compiler crashed (" + isolation::signalName(run.signal) + ")\n" + log;
    }

    // Keep the outcome in the cache, then publish the object (a copy simlab owns, not the sandbox user's file). A
    // compile error is kept too (the same file fails the same way); a compiler stopped by a limit is not: that
    // says nothing of the file, and a quieter machine may finish it.
    const bool genuineError = run.started && run.signal == 0 && run.exitCode > 0 && limit.empty();
    if (result.ok || genuineError) {
        writeFileAtomically(cachedLog, log);
        writeFileAtomically(cachedSource, text);
    }
    if (result.ok) {
        writeFileAtomically(cached, readFile(output));
        result.warnings = log;
    } else {
        if (genuineError) writeFileAtomically(cachedFailure, "");
        result.log = log;
    }
    return result;
}

isolation::ProcessResult Builder::runCompiler(const Assignment& assignment, const std::string& name, const std::string& text,
                                   const std::string& workDir, const std::string& output) const {
    // Compile a copy under the submission's own file name, so messages read "NewtonsApple.cpp:12:5: error".
    writeFileAtomically(workDir + "/" + name, text);
    isolation::ProcessRequest request;
    request.argv = assignment.compile;
    request.argv.insert(request.argv.end(), {"-I" + assignment.contractInclude, "-c", name, "-o", output});
    request.env = {"PATH=/usr/bin:/bin", "HOME=" + workDir, "TMPDIR=/tmp", kToolLocale};
    request.workDir = workDir;
    request.limits = toolLimits();
    request.keepOutput = 64 * 1024;
    // The compiler reads what the student's #include and .incbin lines name, and its messages come back in their
    // report: it runs as the sandbox user and sees the system, the contract's headers and the precompiled header -
    // nothing of the course's tests, rubrics or solutions, of other students', or of simlab's build tree.
    request.isolate = true;
    request.readOnlyPaths = includeFolders(assignment.compile);
    request.readOnlyPaths.push_back(assignment.contractInclude);
    return isolation::runProcess(request);
}

void Builder::checkPrecompiledHeader() const {
    static std::once_flag once;
    static std::string changed;
    std::call_once(once, [&] {
        // Each assignment's header. What it was made from, by content, as the build recorded it
        // (cmake/PchInputs.cmake): a file touched since (its inode changed after the record) is read again and
        // compared.
        std::set<std::string> checked;
        for (const Assignment& assignment : manifest_.assignments) {
            for (const std::string& pch : precompiledHeaders(assignment.compile)) {
                struct stat recorded {};
                if (!checked.insert(pch).second || ::stat((pch + ".inputs").c_str(), &recorded) != 0) continue;
                std::istringstream lines(readFile(pch + ".inputs"));
                for (std::string line; std::getline(lines, line) && changed.empty();) {
                    const std::size_t space = line.find(' ');
                    if (space != 64) continue;
                    const std::string path = line.substr(space + 1);
                    struct stat now {};
                    if (::stat(path.c_str(), &now) != 0) {
                        changed = path + " has gone";
                    } else if (now.st_ctim.tv_sec > recorded.st_mtim.tv_sec ||
                               (now.st_ctim.tv_sec == recorded.st_mtim.tv_sec &&
                                now.st_ctim.tv_nsec > recorded.st_mtim.tv_nsec)) {
                        if (sha256Hex(readFile(path)) != line.substr(0, 64)) changed = path + " has changed";
                    }
                }
                if (!changed.empty()) return;
            }
        }
    });
    if (!changed.empty()) {
        throw SetupError(changed + " since simlab was built (a package upgrade?): simlab's precompiled header for "
                         "student files was made from it, and the compiler would refuse every file that includes it; "
                         "rebuild simlab (cmake --build " + manifest_.buildDir + ", or scripts/setup), then grade again");
    }
}

void ensurePrecompiledHeader(const Manifest& manifest, const Assignment& a) {
    const std::vector<std::string> made = precompiledHeaders(a.compile);
    if (!manifest.installed || a.precompiledHeader.empty() || made.empty()) return;
    static std::mutex lock;
    static std::set<std::string> ready;
    std::lock_guard<std::mutex> guard(lock);
    const std::string& output = made.front();
    if (ready.count(output)) return;
    std::vector<std::string> argv = manifest.compile;
    argv.insert(argv.end(), a.precompileFlags.begin(), a.precompileFlags.end());
    argv.insert(argv.end(), {"-I" + a.contractInclude, "-x", "c++-header", a.precompiledHeader});
    // What it was made for: this prefix, the command (a new compiler or flag makes it again) and the headers it is
    // made from (an installation over this one makes it again).
    const std::string installedDir = manifest.buildDir + "/pch";
    std::string stamp = manifest.prefix + "\n";
    for (const std::string& part : argv) stamp += part + "\n";
    std::error_code error;
    std::vector<std::string> headers = contractHeaders(a);
    for (fs::directory_iterator it(installedDir, error), end; !error && it != end; it.increment(error)) {
        if (it->path().extension() == ".h") headers.push_back(it->path().string());
    }
    std::sort(headers.begin(), headers.end());
    // By content, and by time and inode too: clang validates a header whose time changed by its content, but then
    // takes it for another file, so that its #pragma once no longer holds and the student's include of it is a
    // redefinition. An installation over this one with the same headers touches them all (cli/install).
    for (const std::string& header : headers) {
        struct stat st {};
        if (::stat(header.c_str(), &st) != 0) st = {};
        stamp += sha256Hex(readFile(header)) + " " + std::to_string(st.st_ino) + " " +
                 std::to_string(st.st_mtim.tv_sec) + "." + std::to_string(st.st_mtim.tv_nsec) + " " + header + "\n";
    }
    if (!fs::exists(output, error) || !fs::exists(output + ".made-for", error) ||
        readFile(output + ".made-for") != stamp) {
        const fs::path dir = fs::path(a.precompiledHeader).parent_path();
        fs::create_directories(dir, error);
        // Readable by the compiler's sandbox user, like the installed headers it is made from.
        fs::permissions(dir, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                 fs::perms::others_read | fs::perms::others_exec, error);
        if (dir != fs::path(installedDir)) {  // made in the user's cache: its headers go there too
            for (fs::directory_iterator it(installedDir, error), end; !error && it != end; it.increment(error)) {
                if (it->path().extension() == ".h") {
                    fs::copy_file(it->path(), dir / it->path().filename(), fs::copy_options::overwrite_existing);
                }
            }
        }
        std::cerr << "simlab: making " << a.id << "'s precompiled header for this installation, once ("
                  << printable(output) << ", about 10 s)" << std::endl;
        const std::string partial = output + ".part-" + std::to_string(::getpid());
        argv.insert(argv.end(), {"-o", partial});
        try {
            isolation::runTool(argv, dir.string());
        } catch (const std::runtime_error& e) {
            fs::remove(partial, error);
            throw SetupError("the precompiled header of " + a.id + " could not be made: " + e.what());
        }
        fs::rename(partial, output);
        writeFileAtomically(output + ".made-for", stamp);
    }
    ready.insert(output);
}

void Builder::link(const std::vector<std::string>& inputs, const std::vector<std::string>& flags,
                   const std::string& output, BuildResult& result) const {
    // The linker works in a folder of its own, which its sandbox user owns for the link: it reads the student's
    // object from there (the cache is simlab's alone), and what it made is copied out by simlab.
    TempDir work("simlab-link-");
    const std::string student = work.path() + "/student.o", made = work.path() + "/program";
    std::vector<std::string> linked;
    for (const std::string& input : inputs) {
        const bool cached = input.rfind(cacheDir_ + "/", 0) == 0;
        if (cached) writeFileAtomically(student, readFile(input));
        linked.push_back(cached ? student : input);
    }
    isolation::ProcessRequest request;
    request.argv = manifest_.link;
    request.argv.insert(request.argv.end(), {"-o", made});
    request.argv.insert(request.argv.end(), linked.begin(), linked.end());
    request.argv.insert(request.argv.end(), flags.begin(), flags.end());
    request.env = {"PATH=/usr/bin:/bin", "TMPDIR=/tmp", kToolLocale};
    request.workDir = work.path();
    request.limits = toolLimits();
    // The linker reads the student's object too: it runs in the sandbox as well, lent its inputs one by one, and
    // with no plugin (the link compiles nothing: see the manifest's link command).
    request.isolate = true;
    for (const std::string& input : linked) {
        if (!isolation::visibleInSandboxes(input) && input != student) request.readOnlyPaths.push_back(input);
    }
    for (const std::string& flag : flags) {
        const std::size_t file = flag.find("--version-script=");
        if (file != std::string::npos) request.readOnlyPaths.push_back(flag.substr(file + 17));
    }
    const isolation::ProcessResult run = isolation::runProcess(request);
    result.linkSeconds = run.wallSeconds;
    if (run.interrupted) {
        result.ok = false;
        result.interrupted = true;
        return;
    }
    const std::string limit = stoppedByLimit("linker", run, request.limits);
    result.ok = limit.empty() && run.exitedCleanly() && fs::exists(made);
    if (!result.ok) {
        result.stage = "link";
        result.stoppedByLimit = !limit.empty();
        result.log = limit.empty() ? linkSummary(run.started ? run.output : run.error) : limit + "\n";
        return;
    }
    // A copy simlab owns, not the sandbox user's file.
    writeFileAtomically(output, readFile(made));
    fs::permissions(output, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                fs::perms::others_read | fs::perms::others_exec);
    result.binary = output;
}

bool Builder::refusedObject(const Assignment& assignment, const std::string& object, const std::string& name,
                            BuildResult& result) const {
    const std::vector<std::string> problems = isolation::forbiddenCode(object, name, courseSymbols(assignment));
    if (problems.empty()) return false;
    result.ok = false;
    result.stage = "check";
    for (const std::string& p : problems) result.log += p + "\n";
    return true;
}

std::string judgeNotYours(const Assignment& assignment) {
    if (assignment.judge.empty() || ::access(assignment.judge.c_str(), R_OK) == 0 || errno != EACCES) return "";
    std::string owner = "its owner";
    struct stat info {};
    if (::stat(assignment.judge.c_str(), &info) == 0) {
        if (const passwd* user = ::getpwuid(info.st_uid)) owner = user->pw_name;
    }
    return assignment.id + "'s judge (" + printable(assignment.judge) + ") is for " + owner +
           " alone to read: this simlab's judges are closed to other users (scripts/lock-course); check and grade as " +
           owner + " (sudo), or with a simlab built as yourself";
}

std::vector<std::string> lentToTools(const Manifest& manifest, const Assignment& assignment) {
    std::vector<std::string> lent = includeFolders(assignment.compile);
    lent.push_back(assignment.contractInclude);
    lent.insert(lent.end(), assignment.probeObjects.begin(), assignment.probeObjects.end());
    lent.insert(lent.end(), assignment.programObjects.begin(), assignment.programObjects.end());
    lent.insert(lent.end(), manifest.probeLibraries.begin(), manifest.probeLibraries.end());
    for (const std::string& flag : manifest.probeLink) {
        const std::size_t file = flag.find("--version-script=");
        if (file != std::string::npos) lent.push_back(flag.substr(file + 17));
    }
    lent.push_back(manifest.probeHost);
    lent.erase(std::remove_if(lent.begin(), lent.end(),
                              [](const std::string& p) { return p.empty() || isolation::visibleInSandboxes(p); }),
               lent.end());
    return lent;
}

std::string sandboxCannotReach(const Manifest& manifest, const Assignment& assignment) {
    const isolation::SandboxSupport& sandbox = isolation::sandboxSupport();
    // bubblewrap run as root lends each path whatever folder it lies below; as any other user, tools run as it.
    if (!sandbox.ownUser || (sandbox.bubblewrap && sandbox.rootBubblewrap)) return "";
    std::vector<std::string> needed = lentToTools(manifest, assignment);
    needed.erase(std::remove_if(needed.begin(), needed.end(),
                                [](const std::string& p) {
                                    std::error_code error;
                                    return p.rfind("/usr/", 0) == 0 || !fs::exists(p, error);
                                }),
                 needed.end());
    const std::vector<std::string> readable = isolation::readableInSandbox(needed, needed);
    for (const std::string& path : needed) {
        if (std::find(readable.begin(), readable.end(), path) != readable.end()) continue;
        // The first folder on the way that others may not pass through; else the path itself is closed.
        const fs::path absolute = fs::absolute(path).lexically_normal();
        fs::path closed, walked;
        for (const fs::path& part : absolute.parent_path()) {
            walked /= part;
            struct stat info {};
            if (::stat(walked.c_str(), &info) == 0 && !(info.st_mode & S_IXOTH)) {
                closed = walked;
                break;
            }
        }
        const std::string fix = closed.empty() ? "chmod -R o+rX " + printable(path)
                                               : "chmod o+x " + printable(closed.string());
        return "in this sandbox (" + sandbox.mode + ") the tools run as throwaway users, who cannot reach " +
               printable(path) + (closed.empty() ? "" : " (" + printable(closed.string()) + " is closed to others)") +
               ", so nothing can be built: " + fix + ", or install bubblewrap";
    }
    return "";
}

BuildResult Builder::buildProbe(const Assignment& assignment, const std::string& name, const std::string& text,
                                const std::string& workDir, const std::string& binary, bool checkObject) const {
    std::string object;
    BuildResult result = compile(assignment, name, text, workDir, &object);
    if (result.ok) result.object = object;
    if (!result.ok || (checkObject && refusedObject(assignment, object, name, result))) return result;
    // The course's objects first and whole: an inline function both define keeps the course's copy, and a
    // definition of anything the course defines is an error rather than a replacement.
    std::vector<std::string> inputs = assignment.probeObjects;
    inputs.push_back(object);
    inputs.insert(inputs.end(), manifest_.probeLibraries.begin(), manifest_.probeLibraries.end());
    link(inputs, manifest_.probeLink, binary, result);
    return result;
}

BuildResult Builder::buildLinked(const Assignment& assignment, const std::string& name, const std::string& text,
                                 const std::string& output, const std::vector<std::string>& objects,
                                 const std::vector<std::string>& libraries, bool checkObject) const {
    const fs::path target = fs::absolute(output);
    TempDir work("simlab-build-");
    std::string object;
    BuildResult result = compile(assignment, name, text, work.path(), &object);
    if (!result.ok || (checkObject && refusedObject(assignment, object, name, result))) return result;
    std::vector<std::string> inputs = {object};
    inputs.insert(inputs.end(), objects.begin(), objects.end());
    inputs.insert(inputs.end(), libraries.begin(), libraries.end());
    link(inputs, {}, target.string(), result);
    return result;
}

BuildResult Builder::buildProgram(const Assignment& assignment, const std::string& name, const std::string& text,
                                  const std::string& output) const {
    return buildLinked(assignment, name, text, output, assignment.programObjects, manifest_.programLibraries, false);
}

BuildResult Builder::buildStudy(const Assignment& assignment, const std::string& name, const std::string& text,
                                const std::string& output) const {
    return buildLinked(assignment, name, text, output, assignment.studyObjects, manifest_.studyLibraries, true);
}

}  // namespace simlab::engine
