// simlab slurm: a class graded (or the trade study measured) on a Slurm cluster. It writes an sbatch job array whose
// tasks are shards (simlab grade --shard I/N, simlab study trade --shard I/N) and a job that assembles their work
// once the array has ended, and with --submit submits both, the second dependent on the first. Every path in the
// scripts is absolute: the cluster's nodes must see this simlab, its build and the folders at the same paths (a
// shared filesystem), as they do on a university cluster's home or project space.
#include <CLI/CLI.hpp>
#include <cctype>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.h"
#include "simlab/cli_checks.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/build/manifest.h"
#include "simlab/course/package.h"
#include "simlab/isolation/process.h"
#include "simlab/common/text.h"

namespace fs = std::filesystem;

namespace simlab::cli {

namespace {

struct SlurmOptions {
    std::string what;  // "grade" or "study"
    std::string lab;
    std::string submissions;
    std::string out;
    int tasks = 0;
    int jobs = 2;
    double timeout = 0;
    double memory = 0;
    bool quick = false;
    double cap = 0;
    double maxEvaluations = 0;
    int repeats = 0;
    bool plots = true;
    bool submit = false;
    std::vector<std::string> sbatch;  // after --
};

// A number as an option's value: 15 significant digits, no trailing zeros.
std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.15g", value);
    return text;
}

std::string absolute(const std::string& path) { return fs::absolute(path).lexically_normal().string(); }

// The words of a command line, each as a shell reads it back.
std::string commandLine(const std::vector<std::string>& words) {
    std::string line;
    for (const std::string& w : words) line += (line.empty() ? "" : " ") + (w.rfind("\"$", 0) == 0 ? w : shellWord(w));
    return line;
}

// sbatch's extra options as #SBATCH lines: an option and the words after it that are not options, one per line.
std::string sbatchLines(const std::vector<std::string>& extra) {
    std::string lines, current;
    for (const std::string& word : extra) {
        if (!word.empty() && word[0] == '-' && !current.empty()) {
            lines += "#SBATCH " + current + "\n";
            current.clear();
        }
        current += (current.empty() ? "" : " ") + shellWord(word);
    }
    if (!current.empty()) lines += "#SBATCH " + current + "\n";
    return lines;
}

// A job's script, from the template simlab holds (grader/cli/scripts/slurm-job.sh, made text at build time).
const char* const kJobScript =
#include "slurm-job.sh.inc"
    ;

std::string script(const std::string& header, const std::string& name, const std::string& logs,
                   const std::string& logName, const std::string& array, int cpus, const std::string& chdir,
                   const std::vector<std::string>& extra, const std::vector<std::string>& command) {
    return engine::filledTemplate(kJobScript, {{"HEADER", header},
                                               {"NAME", name},
                                               {"ARRAY", array.empty() ? "" : "#SBATCH --array=" + array},
                                               {"CPUS", std::to_string(cpus)},
                                               {"OUTPUT", shellWord(logs + "/" + logName)},
                                               {"CHDIR", shellWord(chdir)},
                                               {"EXTRA", sbatchLines(extra)},
                                               {"COMMAND", commandLine(command)}});
}

// `name` on the PATH, as an absolute path; empty if it is not there.
std::string onPath(const std::string& name) {
    const char* path = std::getenv("PATH");
    std::istringstream dirs(path ? path : "");
    for (std::string dir; std::getline(dirs, dir, ':');) {
        if (dir.empty()) continue;
        const fs::path candidate = fs::path(dir) / name;
        if (::access(candidate.c_str(), X_OK) == 0 && fs::is_regular_file(candidate))
            return absolute(candidate.string());
    }
    return "";
}

// sbatch --parsable ARGS: the job's id. The submitting environment goes with it (the Slurm client's own variables,
// SLURM_CONF among them), as a shell would pass it.
std::string sbatch(const std::string& program, const std::vector<std::string>& args, const std::string& dir) {
    isolation::ProcessRequest r;
    r.argv = {program, "--parsable"};
    r.argv.insert(r.argv.end(), args.begin(), args.end());
    std::vector<std::string> slurm;
    for (char** e = environ; *e; ++e) {
        const std::string entry = *e;
        if (entry.rfind("SLURM_", 0) == 0 || entry.rfind("SBATCH_", 0) == 0 || entry.rfind("SIMLAB_", 0) == 0) {
            slurm.push_back(entry);
        }
    }
    r.env = isolation::childEnvironment(slurm);
    r.workDir = dir;
    r.limits.wallSeconds = r.limits.cpuSeconds = 120;
    r.limits.outputKiB = 1024;
    r.keepOutput = 1 << 20;
    const isolation::ProcessResult result = isolation::runProcess(r);
    if (!result.exitedCleanly()) {
        // Its first lines, on the one line of an error: joined, never a literal "\n".
        std::string said = isolation::firstLines(result.started ? result.output : result.error, 3);
        while (!said.empty() && std::isspace(static_cast<unsigned char>(said.back()))) said.pop_back();
        for (std::size_t at = said.find('\n'); at != std::string::npos; at = said.find('\n', at))
            said.replace(at, 1, "; ");
        throw std::runtime_error("sbatch refused the job: " + engine::printable(said));
    }
    std::string id = result.output.substr(0, result.output.find_first_of(";\n"));
    if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos) {
        throw std::runtime_error("sbatch answered '" + engine::printable(isolation::firstLines(result.output, 1)) +
                                 "', not a job id");
    }
    return id;
}

void runSlurm(const SlurmOptions& o) {
    const engine::Manifest manifest = engine::loadManifest();
    const bool grading = o.what == "grade";
    const engine::Assignment* assignment = nullptr;
    if (grading || o.lab != "all") assignment = &manifest.find(o.lab);
    if (grading && !fs::is_directory(o.submissions)) {
        throw engine::UsageError("no submissions folder " + engine::printable(o.submissions));
    }
    const std::string simlab = selfPath();
    const std::string out = absolute(o.out);
    const std::string slurmDir = out + "/slurm", logs = slurmDir + "/logs";
    fs::create_directories(logs);
    const std::string labName = assignment ? assignment->id : "all";
    // A lab of one's own is named to the tasks by its folder, whose path they share.
    const std::string labArgument = assignment && engine::isOwnLab(manifest, *assignment) ? assignment->dir : labName;
    int tasks = o.tasks;
    if (tasks == 0) {
        if (grading) throw engine::UsageError("--tasks: how many array tasks share the class");
        int labs = 0;  // one task per part: a lab and an integrator
        for (const engine::Assignment& a : manifest.assignments) {
            if (!a.studyProgramPath.empty() && (o.lab == "all" || a.id == o.lab)) ++labs;
        }
        tasks = std::max(1, labs * 9);
    }
    const std::string shard = "\"${SLURM_ARRAY_TASK_ID}/" + std::to_string(tasks) + "\"";

    std::vector<std::string> array, assemble;
    std::string arrayFile, assembleFile, arrayHeader, assembleHeader, result;
    if (grading) {
        std::vector<std::string> common = {simlab,  "grade", labArgument, absolute(o.submissions),
                                           "--out", out,     "--jobs",    std::to_string(o.jobs)};
        if (o.timeout > 0) common.insert(common.end(), {"--timeout", number(o.timeout)});
        if (o.memory > 0) common.insert(common.end(), {"--memory", number(o.memory)});
        array = common;
        array.insert(array.end(), {"--shard", shard});
        assemble = common;
        arrayFile = slurmDir + "/grade.sbatch";
        assembleFile = slurmDir + "/assemble.sbatch";
        arrayHeader = "# Grades " + labName + "'s class as " + std::to_string(tasks) +
                      " array tasks, each a share of it (simlab grade --shard). A task cut short resumes where it "
                      "stopped when run again; the assembly grades whatever no task finished.\n";
        assembleHeader = "# Assembles the gradebook, the summary and the reports of " + labName +
                         " once the array has ended, grading again only what no task finished.\n";
        result = out + "/gradebook.csv";
    } else {
        std::vector<std::string> common = {simlab, "study", "trade", labArgument, "--output", out, "--jobs", "1"};
        if (o.quick) common.push_back("--quick");
        if (o.cap > 0) common.insert(common.end(), {"--cap", number(o.cap)});
        if (o.maxEvaluations > 0) common.insert(common.end(), {"--max-evaluations", number(o.maxEvaluations)});
        if (o.repeats > 0) common.insert(common.end(), {"--repeats", std::to_string(o.repeats)});
        array = common;
        array.insert(array.end(), {"--shard", shard});
        assemble = common;
        assemble.push_back("--assemble");
        if (!o.plots) assemble.push_back("--no-plots");
        arrayFile = slurmDir + "/study.sbatch";
        assembleFile = slurmDir + "/assemble.sbatch";
        arrayHeader = "# Measures the trade study of " + labName + " as " + std::to_string(tasks) +
                      " array tasks, each a share of its parts (one per lab and integrator).\n";
        assembleHeader = "# Writes trade.csv and the plots of " + labName +
                         " from the parts once the array has ended, measuring any part no task finished.\n";
        result = out + "/trade.csv";
    }
    const std::string what = grading ? "grade" : "study";
    engine::writeFileAtomically(arrayFile,
                                script(arrayHeader, "simlab-" + what + "-" + labName, logs, what + "-%A-%a.out",
                                       "1-" + std::to_string(tasks), grading ? o.jobs : 1, out, o.sbatch, array));
    engine::writeFileAtomically(assembleFile,
                                script(assembleHeader, "simlab-assemble-" + labName, logs, "assemble-%j.out", "",
                                       grading ? o.jobs : 1, out, o.sbatch, assemble));
    fs::permissions(arrayFile, fs::perms::owner_exec | fs::perms::group_exec, fs::perm_options::add);
    fs::permissions(assembleFile, fs::perms::owner_exec | fs::perms::group_exec, fs::perm_options::add);
    std::cout << "Wrote " << engine::printable(arrayFile) << " (" << tasks << " array tasks) and "
              << engine::printable(assembleFile) << " (after them); logs go to " << engine::printable(logs) << "\n";

    if (!o.submit) {
        std::cout << "Submit them on the cluster's login node:\n"
                  << "  job=$(sbatch --parsable " << shellWord(arrayFile) << ")\n"
                  << "  sbatch --dependency=afterany:${job%%;*} " << shellWord(assembleFile) << "\n";
        return;
    }
    const std::string program = onPath("sbatch");
    if (program.empty()) {
        throw engine::UsageError(
            "sbatch is not on the PATH, so this is no Slurm login node: the scripts are written; "
            "submit them where Slurm runs");
    }
    std::vector<std::string> args = o.sbatch;
    args.push_back(arrayFile);
    const std::string first = sbatch(program, args, out);
    args = {"--dependency=afterany:" + first};
    args.insert(args.end(), o.sbatch.begin(), o.sbatch.end());
    args.push_back(assembleFile);
    const std::string second = sbatch(program, args, out);
    std::cout << "Submitted job " << first << " (" << tasks << " array tasks) and job " << second
              << ", which assembles after it: follow them with squeue -j " << first << "," << second << "; "
              << engine::printable(result) << " is written at the end\n";
}

}  // namespace

void addSlurm(CLI::App& app) {
    CLI::App* slurm = app.add_subcommand(
        "slurm",
        "Grade a class, or measure the trade study, on a Slurm cluster: an sbatch job array of shards and "
        "a job that assembles their work after them (the cluster's nodes must share this simlab and the "
        "folders at the same paths).");
    slurm->require_subcommand(1);

    auto g = std::make_shared<SlurmOptions>();
    g->what = "grade";
    CLI::App* grade = slurm->add_subcommand(
        "grade",
        "Write OUT/slurm/grade.sbatch (TASKS array tasks, each simlab grade --shard I/TASKS) and "
        "OUT/slurm/assemble.sbatch (simlab grade without --shard, after the array); --submit submits them. "
        "Options after -- go to sbatch (--partition=..., --time=..., --mem=...).");
    grade->add_option("assignment", g->lab, "which assignment")->required();
    grade->add_option("submissions", g->submissions, "folder of student folders")->required();
    grade->add_option("sbatch", g->sbatch, "after --: options for sbatch");
    grade->add_option("--out,-o", g->out, "where the gradebook and reports go (shared by the nodes)")->required();
    grade->add_option("--tasks", g->tasks, "array tasks: shards of the class, 1 to 10000")
        ->required()
        ->check(CLI::Range(1, 10000));
    grade->add_option("--jobs,-j", g->jobs, "students each task grades at once (its cores)")
        ->check(CLI::Range(1, 64))
        ->capture_default_str();
    grade->add_option("--timeout", g->timeout, "as simlab grade's --timeout")->check(limitOption("cpu_seconds"));
    grade->add_option("--memory", g->memory, "as simlab grade's --memory")->check(limitOption("memory_mib"));
    grade->add_flag("--submit", g->submit, "submit both jobs with sbatch (the second dependent on the first)");
    grade->callback([g] { runSlurm(*g); });

    auto s = std::make_shared<SlurmOptions>();
    s->what = "study";
    s->out = "study";
    CLI::App* study = slurm->add_subcommand("study", "The labs' numerics on a cluster.");
    study->require_subcommand(1);
    CLI::App* trade = study->add_subcommand(
        "trade",
        "Write OUTPUT/slurm/study.sbatch (one array task per lab and integrator unless --tasks says "
        "otherwise, each simlab study trade --shard I/N) and OUTPUT/slurm/assemble.sbatch (--assemble, after "
        "the array: trade.csv and the plots); --submit submits them. Options after -- go to sbatch.");
    trade->add_option("lab", s->lab, "apple, projectile, book, biosim or all")->required();
    trade->add_option("sbatch", s->sbatch, "after --: options for sbatch");
    trade->add_option("--output,-o", s->out, "folder for the parts, trade.csv and the plots (shared by the nodes)")
        ->capture_default_str();
    trade->add_option("--tasks", s->tasks, "array tasks (default: one per lab and integrator)")
        ->check(CLI::Range(1, 10000));
    trade->add_flag("--quick", s->quick, "as simlab study trade's --quick");
    trade->add_option("--max-evaluations", s->maxEvaluations, "as simlab study trade's")
        ->check(simlab::between(100.0, 1e9));
    trade->add_option("--cap", s->cap, "as simlab study trade's")->check(simlab::between(0.01, 3600.0));
    trade->add_option("--repeats", s->repeats, "as simlab study trade's")->check(CLI::Range(1, 100));
    trade->add_flag("!--no-plots", s->plots, "trade.csv and the tables only");
    trade->add_flag("--submit", s->submit, "submit both jobs with sbatch (the second dependent on the first)");
    trade->callback([s] { runSlurm(*s); });
}

}  // namespace simlab::cli
