// The simlab subcommands. Each add* function declares a subcommand's options and what it runs; main() only
// wires them together.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "simlab/common/text.h"
#include "simlab/grading/grade.h"
#include "simlab/rubric/rubric.h"

namespace CLI {
class App;
class Validator;
}  // namespace CLI

namespace simlab::engine {
struct Assignment;
struct Manifest;
}  // namespace simlab::engine

namespace simlab::cli {

/// A CLI11 check that an option's value is within the range of the rubric limit `key` ("cpu_seconds").
CLI::Validator limitOption(const std::string& key);

/// `rubric` with the command line's --timeout (CPU seconds; the wall-clock net grows to six times it if it is
/// smaller) and --memory (MiB) in place of its own; 0 keeps the rubric's. Throws UsageError if out of range.
Limits limitsWith(const Limits& rubric, double timeout, double memory);

/// The file `path` and the rubric's extra files beside it, read as grading reads them (readHandedIn). Throws
/// UsageError, in one line, for a file that is not there or not safe to read.
engine::SubmissionFiles readSubmission(const std::string& path, const Rubric& rubric, const Limits& limits);

/// The cores this machine offers (at least 1): the default for what runs at once.
int cores();

/// This simlab's full path (from /proc/self/exe; "simlab" if it cannot be read).
std::string selfPath();

using engine::shellWord;  // `word` as a POSIX shell reads it back as one word (simlab/common/text.h)

/// Replaces this process with the program at `path`, run with `args` (its name first), after flushing standard
/// output; throws std::runtime_error, in one line, if it cannot be run.
[[noreturn]] void handOver(const std::string& path, std::vector<std::string> args);

/// One line on stderr naming what sweepLeftovers removed (nothing when it removed nothing).
void sayLeftovers(const std::vector<std::string>& removed);

/// --shard's "I/N" as (I, N), 1 <= I <= N <= 10000; a UsageError in one line otherwise.
std::pair<int, int> parseShard(const std::string& text);

void addAssignment(CLI::App& app);
void addCheck(CLI::App& app);
void addGrade(CLI::App& app);
void addBuild(CLI::App& app);
void addList(CLI::App& app);
/// simlab lock and simlab clean.
void addLock(CLI::App& app);
void addPackage(CLI::App& app);
void addAutograde(CLI::App& app);
void addExport(CLI::App& app);
void addProject(CLI::App& app);
void addStudy(CLI::App& app);
/// `simlab study long-run` (study_long_run.cpp), under `study`.
void addStudyLongRun(CLI::App& study);
void addPlot(CLI::App& app);
void addSimilarity(CLI::App& app);
void addSlurm(CLI::App& app);

}  // namespace simlab::cli
