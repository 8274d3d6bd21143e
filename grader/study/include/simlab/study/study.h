// The studies of the labs' numerics (`simlab study`): the work-precision trade of a lab's reference solution or of
// a student's file, what over-modelling costs, the labs' extreme cases and the long-run view. Each lab's study
// program (simlab/study.h) measures; this library runs it, checks what it prints, and writes the tables and plots.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "simlab/grading/grade.h"
#include "simlab/rubric/rubric.h"

namespace simlab::engine {
struct Assignment;
struct Manifest;
}  // namespace simlab::engine

namespace simlab::study {

struct StudyOptions {
    bool minimal = false;  ///< `study minimal` rather than `study trade`
    std::string lab;
    std::string output = "study";
    bool quick = false;
    double maxEvaluations = 0;  // 0: the study program's default
    double cap = 0;             // 0: the study program's default
    int repeats = 0;            // 0: the study program's default
    int jobs = 2;               // study programs run at once, one core each
    bool plots = true;
    std::string file;       ///< a student file to study instead of the reference solution
    bool question = false;  ///< the trade question's scene (grading/trade-question.json), as the grader measures it
    bool fronts = false;    ///< measure the fronts of the question's data files and write them there
    std::string student;    ///< with question: this student's own scene, where the rubric gives each one
    std::string shard;      ///< "I/N": measure share I of N of the (lab, integrator) parts into OUTPUT/parts
    bool assemble = false;  ///< trade.csv and the plots from OUTPUT/parts, measuring only the parts missing
};

/// What the command lends a study: the machine's cores, and its readings of --shard and of a student's file, so
/// that a study takes them as simlab's other commands do.
struct CommandLine {
    int cores = 1;
    std::function<std::pair<int, int>(const std::string&)> parseShard;
    std::function<engine::SubmissionFiles(const std::string&, const Rubric&, const Limits&)> readSubmission;
};

/// `simlab study trade` (and, with `minimal`, `simlab study minimal`): measures, prints the tables, writes the files.
/// Throws engine::UsageError, in one line, for options that do not go together or a lab without a study.
void runTrade(const StudyOptions& o, const CommandLine& command);

struct ExtremesOptions {
    std::string lab;
    std::string output = "study";
    bool quick = false;
    double cap = 20;
};

/// `simlab study extremes`: every extreme case of the labs, named; throws std::runtime_error if one ends silently or
/// not as the lab promises.
void runExtremes(const ExtremesOptions& o);

struct LongRunOptions {
    std::string lab;
    double finalTime = 0;  ///< s; 0: the study program's default (1000 s, or a short run with --quick)
    bool quick = false;
    std::string output = "long-run";
    bool plots = true;
    std::string file;  ///< a student file to follow instead of the reference solution
};

/// `simlab study long-run` of the lab's reference solution: the lab checked and its study program built where it is
/// not yet; returns the program and its arguments (its name first), for the command to hand over to.
std::vector<std::string> longRunCommand(const LongRunOptions& o, int cores);

/// `simlab study long-run --file`: the student's file built into a study program of its own, with grading's object
/// check, and run in grading's sandbox, where it writes the CSV and the figure in a scratch folder; its lines are
/// printed as they come (made printable: they are data), and the two files are copied into o.output where they are
/// what the view writes. Returns the view's exit status (0, or 1 when a setting stopped short or the run failed);
/// throws engine::UsageError, in one line, for a lab with no such view or a file that does not build.
int runLongRunOfFile(const LongRunOptions& o, const CommandLine& command);

}  // namespace simlab::study
