// What the study's files share: the study program's lines, running it, the work queue, and the written results.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "simlab/common/files.h"
#include "simlab/common/parallel.h"
#include "simlab/integrators.h"
#include "simlab/study/study.h"

namespace simlab::study {

namespace fs = std::filesystem;
using nlohmann::json;
using engine::forEachInParallel;

/// A subject's header line and its points, as the study program printed them (for `study minimal`, its rows).
struct SubjectRun {
    json subject;
    std::vector<json> points;
    std::vector<json> minimal;
};

// The integrators a study program may name, in the order a study runs them: simlab::kIntegrators
// (simlab/integrators.h).

/// A study program's line as simlab takes it - the type ("subject", "point", "minimal"), and for each field the
/// type it must have: what a program built from a student's file prints is data, never trusted. A subject's name
/// is a plain word (letters, digits, '.', '_', '-'), since it names files and plots; texts are made printable and
/// cut at 300 bytes; numbers are finite or null; an integrator, a mode and a status are among the known ones.
/// Empty, with `why` saying what is wrong, for a line no study prints.
std::optional<json> wellFormedLine(const json& line, std::string& why);

/// Runs a study program, handing each line it prints to `onLine` as it comes, made well formed (a line that is not
/// stops the study, saying what it was); what is not a JSON line (a progress line, an error) goes to our standard
/// error, printable. A student's study program runs in the sandbox, as a probe does (its folder lent read-only, a
/// scratch working directory, no network); the course's runs as a tool. Returns its exit status (128 + N for
/// signal N).
int runStudyProgram(const std::vector<std::string>& argv, bool sandboxed,
                    const std::function<void(const json&)>& onLine);

/// The studies' programs and objects of `labs` (their objects, for a study of a file), built now where this tree's
/// build leaves them out (SIMLAB_BUILD_STUDIES=OFF, or a build configured before they were built by default):
/// `cmake --build BUILD --target simlab_studies -j CORES`, with the build's lines on standard error.
void ensureStudiesBuilt(const engine::Manifest& m, const std::vector<const engine::Assignment*>& labs, bool ofAFile,
                        int cores);

/// A student's file built into a study program of its own, as `simlab build` builds its lab program, with grading's
/// object check, to run in grading's sandbox: the program's folder and its path (both empty for a study of the
/// reference solution).
struct StudyProgram {
    std::unique_ptr<engine::TempDir> folder;
    std::string path;
};

/// `file`, a student's file of lab `a`, built into a study program (StudyProgram). Throws engine::UsageError, in one
/// line, for a file that is not a C++ source, does not compile or link, or is refused by the object check (its
/// compiler's first lines on standard error), or where the sandbox could reach what it must not.
StudyProgram buildStudyOfFile(const engine::Manifest& manifest, const engine::Assignment& a, const std::string& file,
                              const CommandLine& command);

/// How far a study has come, on standard error at least every two seconds while it runs - "point n of N measured,
/// about S s left", the time left read from the pace so far - and once more when it ends.
class Progress {
public:
    using Clock = std::chrono::steady_clock;

    Progress();
    ~Progress() { finish(false); }
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    /// The study's points in all; the lines begin once it is known.
    void setTotal(std::size_t total) { total_ = total; }
    void pointDone() { ++done_; }
    /// Stops the lines; a study that ended well says so in a last one.
    void finish(bool ended);

private:
    void tick();
    void say(bool ended) const;

    const Clock::time_point began_;
    std::atomic<std::size_t> total_{0}, done_{0};
    std::mutex lock_;
    std::condition_variable wake_;
    bool stopped_ = false;
    std::thread ticker_;
};

/// The study in parts (--shard, --assemble), runTrade having checked the options.
void runTradeInParts(const StudyOptions& o, const std::vector<const engine::Assignment*>& labs,
                     const CommandLine& command);

/// A number as `format` prints it; "" for what is not a number.
std::string number(const json& value, const char* format = "%.6g");
/// A text; "" for what is not one.
std::string text(const json& value);

/// The digits a study's table gives the cheapest setting for, unless it is told others.
inline const std::vector<double> kTableDigits = {4, 6, 8, 10, 12};

/// trade.csv, the tables and (unless o.plots is off) the plots of `runs`, into `dir`: a table gives the cheapest
/// setting for each of `targets` digits (a question's study: those it asks, and each digit past them its grader reads).
void writeTrade(const StudyOptions& o, const fs::path& dir, const std::vector<SubjectRun>& runs,
                const std::vector<double>& targets = kTableDigits);
/// `study minimal`'s files and table from its rows, into `dir`.
void writeMinimal(const fs::path& dir, const std::vector<json>& rows);

}  // namespace simlab::study
