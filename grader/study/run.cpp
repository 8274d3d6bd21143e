// Running a study program and reading what it prints; building the studies where they are not built; the work queue.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <iostream>
#include <optional>
#include <unistd.h>

#include "internal.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/build/build.h"
#include "simlab/build/manifest.h"
#include "simlab/common/text.h"
#include "simlab/isolation/process.h"
#include "simlab/rubric/rubric.h"

namespace simlab::study {

// What a study program printed, made well formed (internal.h).
std::optional<json> wellFormedLine(const json& line, std::string& why) {
    auto fail = [&](const std::string& what) -> std::optional<json> {
        why = what;
        return std::nullopt;
    };
    if (!line.is_object() || !line.contains("type") || !line["type"].is_string()) return fail("a line without a type");
    const std::string type = line["type"];
    if (type != "subject" && type != "point" && type != "minimal")
        return fail("a line of type '" + engine::printable(type) + "'");
    json out = {{"type", type}};
    auto textField = [&](const char* key) {
        const std::string value = line.contains(key) && line[key].is_string() ? line[key].get<std::string>() : "";
        out[key] = engine::printable(value.substr(0, 300));
    };
    auto numberField = [&](const char* key) {
        const bool finite = line.contains(key) && line[key].is_number() && std::isfinite(line[key].get<double>());
        out[key] = finite ? line[key] : json();
    };
    const std::string subject =
        line.contains("subject") && line["subject"].is_string() ? line["subject"].get<std::string>() : "";
    const bool plainWord = !subject.empty() && subject.size() <= 64 && subject[0] != '.' &&
                           std::all_of(subject.begin(), subject.end(), [](char c) {
                               return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
                           });
    if (!plainWord) return fail("a subject named '" + engine::printable(subject.substr(0, 80)) + "'");
    out["subject"] = subject;
    if (type == "subject") {
        for (const char* key : {"lab", "figure", "final_figure", "conserved", "reference", "timing"}) textField(key);
        for (const char* key :
             {"final_time", "reference_digits", "cap", "max_evaluations", "repeats", "starts", "points", "sweeps"}) {
            numberField(key);
        }
        return out;
    }
    const std::string integrator =
        line.contains("integrator") && line["integrator"].is_string() ? line["integrator"].get<std::string>() : "";
    if (!isIntegratorName(integrator)) {
        return fail("an integrator named '" + engine::printable(integrator.substr(0, 80)) + "'");
    }
    out["integrator"] = integrator;
    const std::string mode = line.contains("mode") && line["mode"].is_string() ? line["mode"].get<std::string>() : "";
    if (mode != "accuracy" && mode != "fixed step")
        return fail("a mode named '" + engine::printable(mode.substr(0, 80)) + "'");
    out["mode"] = mode;
    const std::string status =
        line.contains("status") && line["status"].is_string() ? line["status"].get<std::string>() : "";
    static const char* const kStatuses[] = {"ok", "too costly", "failed", "blew up", "no error control"};
    if (std::find_if(std::begin(kStatuses), std::end(kStatuses), [&](const char* k) { return status == k; }) ==
        std::end(kStatuses)) {
        return fail("a status '" + engine::printable(status.substr(0, 80)) + "'");
    }
    out["status"] = status;
    textField("message");
    for (const char* key : {"accuracy", "step", "reached", "final_digits", "worst_digits", "drift", "steps_taken",
                            "steps_attempted", "evaluations", "seconds", "repeats"}) {
        numberField(key);
    }
    if (type == "minimal") {
        textField("lab");
        textField("model");
        out["over_modelled"] =
            line.contains("over_modelled") && line["over_modelled"].is_boolean() && line["over_modelled"].get<bool>();
        numberField("dof");
        numberField("coordinates");
    }
    return out;
}

namespace {

/// Held while a line goes to standard error: the study programs' lines and the progress come from several threads.
std::mutex stderrLock;

}  // namespace

Progress::Progress() : began_(Clock::now()), ticker_([this] { tick(); }) {}

void Progress::finish(bool ended) {
    {
        std::lock_guard<std::mutex> guard(lock_);
        if (stopped_) return;
        stopped_ = true;
    }
    wake_.notify_all();
    ticker_.join();
    if (ended) say(true);
}

void Progress::tick() {
    std::unique_lock<std::mutex> guard(lock_);
    while (!wake_.wait_for(guard, std::chrono::milliseconds(1500), [this] { return stopped_; })) say(false);
}

void Progress::say(bool ended) const {
    const std::size_t total = total_, done = std::min<std::size_t>(done_, total);
    if (total == 0) return;
    const double seconds = std::chrono::duration<double>(Clock::now() - began_).count();
    char line[160];
    if (ended) {
        std::snprintf(line, sizeof line, "  point %zu of %zu measured, in %.0f s\n", done, total, seconds);
    } else if (done == 0) {
        std::snprintf(line, sizeof line, "  point 0 of %zu measured\n", total);
    } else {
        const double left = std::max(1.0, seconds * static_cast<double>(total - done) / static_cast<double>(done));
        std::snprintf(line, sizeof line, "  point %zu of %zu measured, about %.0f s left\n", done, total, left);
    }
    std::lock_guard<std::mutex> guard(stderrLock);
    std::cerr << line << std::flush;
}

int runStudyProgram(const std::vector<std::string>& argv, bool sandboxed,
                    const std::function<void(const json&)>& onLine) {
    engine::TempDir scratch("simlab-study-run-");
    isolation::ProcessRequest request;
    request.argv = argv;
    request.env = isolation::childEnvironment({"LC_ALL=C", "SIMLAB_PROGRESS=1"});
    request.workDir = scratch.path();
    request.limits.cpuSeconds = 4 * 3600;  // a net: the points' evaluation caps bound the work
    request.limits.wallSeconds = 12 * 3600;
    request.limits.memoryMiB = 8192;
    request.limits.outputKiB = 1 << 20;
    request.limits.fileMiB = 64;
    request.limits.processes = 16;
    request.keepOutput = 0;
    std::string malformed;
    request.onOutputLine = [&](const std::string& line) {
        const json j = json::parse(line, nullptr, false);
        if (!j.is_discarded() && j.is_object()) {
            std::string why;
            if (const std::optional<json> taken = wellFormedLine(j, why)) onLine(*taken);
            else if (malformed.empty()) malformed = why;
        } else if (!line.empty()) {
            std::lock_guard<std::mutex> guard(stderrLock);
            std::cerr << engine::printable(line) << '\n';
        }
    };
    if (sandboxed) {
        // A student's file built into a study program: the students' system-call filter, as for a probe.
        request.isolate = true;
        request.studentCode = true;
        request.scratchWorkDir = true;
        request.readOnlyPaths = {fs::path(argv.front()).parent_path().string()};
    }
    const isolation::ProcessResult result = isolation::runProcess(request);
    if (!result.started) throw std::runtime_error("cannot run " + argv.front() + ": " + result.error);
    if (!malformed.empty()) {
        throw std::runtime_error(fs::path(argv.front()).filename().string() + " printed a line no study prints (" +
                                 malformed + "): the study stops");
    }
    if (result.cpuTimeout || result.wallTimeout) throw std::runtime_error(argv.front() + " ran past its time net");
    if (result.signal != 0) return 128 + result.signal;
    return result.exitCode;
}

void ensureStudiesBuilt(const engine::Manifest& m, const std::vector<const engine::Assignment*>& labs, bool ofAFile,
                        int cores) {
    std::vector<std::string> needed;
    for (const engine::Assignment* a : labs) {
        if (ofAFile) needed.insert(needed.end(), a->studyObjects.begin(), a->studyObjects.end());
        else if (!a->studyProgramPath.empty()) needed.push_back(a->studyProgramPath);
    }
    if (ofAFile) needed.insert(needed.end(), m.studyLibraries.begin(), m.studyLibraries.end());
    if (std::all_of(needed.begin(), needed.end(), [](const std::string& p) { return fs::exists(p); })) return;
    if (m.installed) {
        throw engine::UsageError("this installation (" + engine::printable(m.prefix) +
                                 ") was made from a build without "
                                 "the studies: build them (cmake --build BUILD --target simlab_studies), then install");
    }
    if (m.studiesTarget.empty()) throw engine::UsageError("the studies are not built: run scripts/setup again");
    const std::string jobs = std::to_string(cores);
    const std::vector<std::string> argv = {m.cmake, "--build", m.buildDir, "--target", m.studiesTarget, "-j", jobs};
    std::cerr << "simlab study: building the studies first, once (" << m.cmake << " --build " << m.buildDir
              << " --target " << m.studiesTarget << "; about a minute)" << std::endl;
    // A trusted tool with generous nets; its lines are progress, not the study's output.
    isolation::ProcessRequest build;
    build.argv = argv;
    for (char** variable = environ; *variable; ++variable) build.env.emplace_back(*variable);  // the build's own
    build.workDir = m.buildDir;
    build.limits.cpuSeconds = build.limits.wallSeconds = 4 * 3600;
    build.limits.memoryMiB = 1 << 16;
    build.limits.processes = 4096;
    build.limits.fileMiB = 1 << 12;
    build.limits.outputKiB = 1 << 20;
    build.keepOutput = 0;
    build.onOutputLine = [](const std::string& line) { std::cerr << line << '\n'; };
    const isolation::ProcessResult built = isolation::runProcess(build);
    if (!built.started) throw std::runtime_error("cannot run " + m.cmake + ": " + built.error);
    if (!built.exitedCleanly()) {
        throw std::runtime_error("building the studies failed (" + m.cmake + " --build " + m.buildDir + " --target " +
                                 m.studiesTarget + " says why)");
    }
}

StudyProgram buildStudyOfFile(const engine::Manifest& manifest, const engine::Assignment& a, const std::string& file,
                              const CommandLine& command) {
    engine::requireCppSource(file);
    const Rubric rubric = loadRubric(a.rubric);
    const engine::SubmissionFiles files = command.readSubmission(file, rubric, rubric.limits);
    if (const std::string closed = engine::sandboxCannotReach(manifest, a); !closed.empty()) {
        throw engine::UsageError(closed);
    }
    StudyProgram built;
    built.folder = std::make_unique<engine::TempDir>("simlab-study-");
    built.path = built.folder->path() + "/" + a.program + "-study";
    const engine::BuildResult result = engine::Builder(manifest).buildStudy(a, files.name, files.text, built.path);
    if (!result.ok) {
        std::cerr << engine::printable(isolation::firstLines(result.log, 30), true);
        throw engine::UsageError(engine::printable(file) + (result.stage == "link"    ? " did not link"
                                                            : result.stage == "check" ? " is refused (forbidden code)"
                                                                                      : " did not compile"));
    }
    // Grading's sandbox, where the program can read nothing but the system and its own folder.
    fs::permissions(built.folder->path(), fs::perms::owner_all | fs::perms::group_exec | fs::perms::others_exec);
    return built;
}

}  // namespace simlab::study
