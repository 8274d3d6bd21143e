// `simlab study`: its subcommands' options (the studies themselves are simlab/study/study.h's).
#include <CLI/CLI.hpp>
#include <memory>

#include "commands.h"
#include "simlab/cli_checks.h"
#include "simlab/study/study.h"

namespace simlab::cli {

namespace {

/// What a study takes from the command: the cores, and --shard and a student's file read as the other commands do.
study::CommandLine commandLine() {
    study::CommandLine command;
    command.cores = cores();
    command.parseShard = parseShard;
    command.readSubmission = readSubmission;
    return command;
}

}  // namespace

void addStudy(CLI::App& app) {
    CLI::App* studies = app.add_subcommand("study", "Measure the labs' numerics: what accuracy costs.");
    studies->require_subcommand(1);
    auto options = std::make_shared<study::StudyOptions>();
    CLI::App* trade = studies->add_subcommand(
        "trade",
        "Work-precision study of a lab's reference solution: every integrator at accuracies 1e-1 ... "
        "1e-14 and fixed steps, each point under a cost cap; writes trade.csv and plots, prints the "
        "cheapest setting for 4 to 12 digits.");
    trade->add_option("lab", options->lab, "the lab's id (simlab list), or all")->required();
    trade->add_option("--output,-o", options->output, "folder for trade.csv and the plots")->capture_default_str();
    trade->add_flag("--quick", options->quick,
                    "fewer step sizes, a cap of 1e5 evaluations, and each point timed once, on its measured run "
                    "(no timed runs of its own unless --repeats is given)");
    trade
        ->add_option("--max-evaluations", options->maxEvaluations,
                     "the cost cap: evaluations one point may take (default 5e5; 1e5 with --quick; with --question, "
                     "the grader's cap on an answer, or this if lower)")
        ->check(simlab::between(100.0, 1e9));
    trade
        ->add_option("--cap", options->cap,
                     "seconds of CPU time one point may take (default 600): a net for a run that would not end, "
                     "never the cost cap (a point it stops is failed, and says so)")
        ->check(simlab::between(0.01, 3600.0));
    trade->add_option("--repeats", options->repeats, "timed runs per point, the fastest kept (default 3)")
        ->check(CLI::Range(1, 100));
    trade->add_flag("!--no-plots", options->plots, "write trade.csv and the table only");
    trade->add_option("--jobs,-j", options->jobs,
                      "study programs run at once, one core each: a lab's sweeps side by side (with --shard and "
                      "--assemble, its parts; with --fronts, its scenes)")
        ->check(CLI::Range(1, 64))
        ->capture_default_str();
    trade->add_option("--file", options->file,
                      "study this student file instead of the reference solution: it is built with grading's object "
                      "check and run in grading's sandbox");
    trade->add_flag("--question", options->question,
                    "study the scene of the lab's graded trade question (not the lab's default one) as the grader "
                    "measures an answer: the integrators it allows, each point stopped at the grader's cap on an "
                    "answer and measured from the grader's starts where it keeps the digits asked for; its sweeps "
                    "run on every core, with a progress line every few seconds");
    trade->add_option("--student", options->student,
                      "with --question: study your own scene, where the course gives each student one (simlab check "
                      "--student ID says which)");
    trade->add_flag("--fronts", options->fronts,
                    "for those who keep the course: measure the front of every scene of the trade question, its "
                    "pool of students' scenes and its hidden variants on the reference solution and write it into "
                    "grading/trade-*.json");
    trade
        ->add_option("--shard", options->shard,
                     "I/N: measure share I of N of the study's parts (one per lab and integrator) into "
                     "OUTPUT/parts, beside the other shards on a shared OUTPUT (a cluster's job array)")
        ->type_name("I/N");
    trade->add_flag("--assemble", options->assemble,
                    "write trade.csv and the plots from OUTPUT/parts, measuring here any part no shard finished");
    trade->callback([options] { study::runTrade(*options, commandLine()); });

    CLI::App* minimal = studies->add_subcommand(
        "minimal",
        "What over-modelling costs: each scene with its minimal mobilizers and over-modelled (a Free "
        "mobilizer, say), each model's work-precision curve measured with RungeKuttaMerson at accuracies "
        "1e-1 to 1e-12, and the two read at equal digits (evaluations, and seconds per run timed in "
        "batches).");
    minimal->add_option("lab", options->lab, "the lab's id (simlab list), or all")->required();
    minimal->add_option("--output,-o", options->output, "folder for minimal.csv and minimal-points.csv")
        ->capture_default_str();
    minimal->add_option("--repeats", options->repeats, "timed batches per accuracy, the fastest kept (default 3)")
        ->check(CLI::Range(1, 100));
    minimal->add_option("--file", options->file,
                        "study this student file's minimal model instead of the solution's (built with grading's "
                        "object check, run in grading's sandbox)");
    minimal->callback([options] {
        options->minimal = true;
        study::runTrade(*options, commandLine());
    });

    auto extremes = std::make_shared<study::ExtremesOptions>();
    CLI::App* extreme = studies->add_subcommand(
        "extremes",
        "Runs the lab program on its extreme cases (assignments/LAB/study/extremes.toml: tiny, huge, zero and "
        "degenerate scenes, settings at their limits), each under a time cap, and names each outcome: "
        "accurate (with digits; inaccurate below 3), rejected or trouble (with the program's one line). "
        "Exits 1 if any "
        "ends silently or not as the lab promises.");
    extreme->add_option("lab", extremes->lab, "the lab's id (simlab list), or all")->required();
    extreme->add_option("--output,-o", extremes->output, "folder for extremes.csv")->capture_default_str();
    extreme->add_flag("--quick", extremes->quick, "skip the cases marked slow");
    extreme->add_option("--cap", extremes->cap, "seconds of CPU time one case may take (wall time: five times as many)")
        ->check(simlab::between(1.0, 3600.0))
        ->capture_default_str();
    extreme->callback([extremes] { study::runExtremes(*extremes); });

    addStudyLongRun(*studies);
}

}  // namespace simlab::cli
