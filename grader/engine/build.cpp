#include "simlab/engine/build.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>

#include "simlab/engine/files.h"
#include "simlab/engine/process.h"

namespace fs = std::filesystem;

namespace simlab::engine {

namespace {

// Compilers and linkers are trusted, but what they read is not: limits stop an #include of /dev/zero.
Limits toolLimits() {
    Limits l;
    l.wallSeconds = 120;
    l.cpuSeconds = 120;
    l.memoryMiB = 4096;
    l.outputKiB = 1024;
    l.fileMiB = 512;
    l.processes = 16;
    return l;
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

// The folders a compile command reads headers from: -I and -isystem folders, and the folder of an -include.
std::vector<std::string> includeFolders(const std::vector<std::string>& command) {
    std::vector<std::string> folders;
    for (std::size_t i = 0; i < command.size(); ++i) {
        const std::string& arg = command[i];
        if (arg.rfind("-I", 0) == 0 && arg.size() > 2) folders.push_back(arg.substr(2));
        if ((arg == "-isystem" || arg == "-I") && i + 1 < command.size()) folders.push_back(command[i + 1]);
        if (arg == "-include" && i + 1 < command.size()) folders.push_back(fs::path(command[i + 1]).parent_path());
    }
    // Folders under /usr are in the sandbox already.
    folders.erase(std::remove_if(folders.begin(), folders.end(),
                                 [](const std::string& f) { return f.rfind("/usr/", 0) == 0; }),
                  folders.end());
    return folders;
}

}  // namespace

std::string firstLines(const std::string& text, int maxLines) {
    std::istringstream in(text);
    std::string line, out;
    int count = 0, more = 0;
    while (std::getline(in, line)) {
        if (count < maxLines) {
            out += line + "\n";
            ++count;
        } else {
            ++more;
        }
    }
    if (more > 0) out += "... (" + std::to_string(more) + " more lines)\n";
    return out;
}

Builder::Builder(const Manifest& manifest) : manifest_(manifest), cacheDir_(manifest.buildDir + "/cache/objects") {
    if (const char* dir = std::getenv("SIMLAB_CACHE"); dir && *dir) cacheDir_ = dir;
    std::error_code ignored;
    fs::create_directories(cacheDir_, ignored);
}

std::string Builder::objectKey(const std::string& sourceText) const {
    Hash h;
    h.add(sourceText).add(manifest_.version).add(kToolLocale);
    for (const std::string& part : manifest_.compile) h.add(part);
    for (std::size_t i = 0; i + 1 < manifest_.compile.size(); ++i) {
        if (manifest_.compile[i] == "-include") h.addFileStamp(manifest_.compile[i + 1] + ".gch");
    }
    return h.hex();
}

std::string Builder::graderKey(const Assignment& assignment) const {
    Hash h;
    h.add(objectKey(""));
    for (const std::string& part : manifest_.link) h.add(part);
    for (const std::string& file : assignment.graderObjects) h.addFileStamp(file);
    for (const std::string& file : manifest_.graderLibraries) h.addFileStamp(file);
    return h.hex();
}

BuildResult Builder::compile(const std::string& source, const std::string& workDir, std::string* object) const {
    BuildResult result;
    result.stage = "compile";
    const std::string text = readFile(source);
    const std::string key = objectKey(text);
    const std::string cached = cacheDir_ + "/" + key + ".o";
    const std::string cachedLog = cacheDir_ + "/" + key + ".log";
    const std::string cachedFailure = cacheDir_ + "/" + key + ".failed";
    *object = cached;
    if (fs::exists(cached) || fs::exists(cachedFailure)) {
        result.cached = true;
        result.ok = fs::exists(cached);
        const std::string log = fs::exists(cachedLog) ? readFile(cachedLog) : "";
        (result.ok ? result.warnings : result.log) = log;
        return result;
    }

    // Compile a copy under the submission's own file name, so messages read "NewtonsApple.cpp:12:5: error".
    const std::string name = fs::path(source).filename().string();
    const std::string copy = workDir + "/" + name;
    writeFileAtomically(copy, text);
    const std::string output = workDir + "/" + key + ".o";
    ProcessRequest request;
    request.argv = manifest_.compile;
    request.argv.insert(request.argv.end(), {"-c", name, "-o", output});
    request.env = childEnvironment({kToolLocale});
    request.workDir = workDir;
    request.limits = toolLimits();
    request.keepOutput = 64 * 1024;
    // The compiler reads what the student's #include lines name, and its messages come back in their report: it
    // sees only the system and the include folders on its command line, nothing of other students' or simlab's.
    request.isolate = true;
    request.ownUser = false;
    request.readOnlyPaths = includeFolders(manifest_.compile);
    const ProcessResult run = runProcess(request);
    result.compileSeconds = run.wallSeconds;
    result.ok = run.exitedCleanly() && fs::exists(output);
    std::string log = run.started ? run.output : run.error;
    if (run.wallTimeout || run.cpuTimeout) log = "the compiler was stopped after " + std::to_string(static_cast<int>(request.limits.wallSeconds)) + " s\n" + log;
    else if (!result.ok && run.signal) log = "the compiler crashed (" + signalName(run.signal) + ")\n" + log;

    // Keep the outcome in the cache, then publish the object. A compile error is kept too (the same file fails
    // the same way); a compiler stopped by a limit is not, since a quieter machine may finish it.
    const bool genuineError = run.started && run.signal == 0 && run.exitCode > 0 && !run.wallTimeout;
    if (result.ok || genuineError) writeFileAtomically(cachedLog, log);
    if (result.ok) {
        std::error_code error;
        fs::rename(output, cached, error);
        if (error) fs::copy_file(output, cached, fs::copy_options::overwrite_existing, error);
        if (error) *object = output;
        result.warnings = log;
    } else {
        if (genuineError) writeFileAtomically(cachedFailure, "");
        result.log = log;
    }
    return result;
}

void Builder::link(const std::vector<std::string>& inputs, const std::string& output, BuildResult& result) const {
    ProcessRequest request;
    request.argv = manifest_.link;
    request.argv.insert(request.argv.end(), {"-o", output});
    request.argv.insert(request.argv.end(), inputs.begin(), inputs.end());
    request.env = childEnvironment({kToolLocale});
    request.workDir = fs::path(output).parent_path().string();
    request.limits = toolLimits();
    const ProcessResult run = runProcess(request);
    result.linkSeconds = run.wallSeconds;
    result.ok = run.exitedCleanly() && fs::exists(output);
    if (!result.ok) {
        result.stage = "link";
        result.log = linkSummary(run.started ? run.output : run.error);
    } else {
        result.binary = output;
    }
}

BuildResult Builder::buildGrader(const Assignment& assignment, const std::string& source, const std::string& workDir,
                                 const std::string& binary) const {
    std::string object;
    BuildResult result = compile(source, workDir, &object);
    if (!result.ok) return result;
    std::vector<std::string> inputs = {object};
    inputs.insert(inputs.end(), assignment.graderObjects.begin(), assignment.graderObjects.end());
    inputs.insert(inputs.end(), manifest_.graderLibraries.begin(), manifest_.graderLibraries.end());
    link(inputs, binary, result);
    return result;
}

BuildResult Builder::buildProgram(const Assignment& assignment, const std::string& source,
                                  const std::string& output) const {
    const fs::path target = fs::absolute(output);
    TempDir work("simlab-build-");
    std::string object;
    BuildResult result = compile(source, work.path(), &object);
    if (!result.ok) return result;
    std::vector<std::string> inputs = {object};
    inputs.insert(inputs.end(), assignment.programObjects.begin(), assignment.programObjects.end());
    inputs.insert(inputs.end(), manifest_.programLibraries.begin(), manifest_.programLibraries.end());
    link(inputs, target.string(), result);
    return result;
}

}  // namespace simlab::engine
