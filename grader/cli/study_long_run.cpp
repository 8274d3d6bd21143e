// `simlab study long-run LAB`: its options; the study (simlab/study/study.h) checks the lab and builds the studies
// where they are not built yet, and this command hands over to the lab's study program.
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <memory>

#include "commands.h"
#include "simlab/cli_checks.h"
#include "simlab/study/study.h"

namespace simlab::cli {

void addStudyLongRun(CLI::App& studies) {
    auto options = std::make_shared<study::LongRunOptions>();
    CLI::App* longRun = studies.add_subcommand(
        "long-run",
        "A long-run view of the book (its spin about the intermediate axis) or the baby boot: RungeKuttaMerson at "
        "accuracies 1e-6 and 1e-9 and Verlet at a fixed step of 1 ms, each run to the final time (1000 s) and "
        "sampled 20 times a decade from 0.1 s. It prints, for each setting, the energy's drift |E(t) - E(0)| / "
        "scale at 1, 10, 100 and 1000 s and the time its trajectory keeps less than 1 digit - against the "
        "long-double reference for the book, against the same method run tighter (a tenth of the accuracy, half "
        "the step) for the chaotic boot - and writes LAB-long-run.csv and LAB-long-run.svg (both against time on "
        "log-log axes). The full view takes a minute or two; --quick, seconds. --file follows a student's own "
        "book file instead of the reference solution.");
    longRun->add_option("lab", options->lab, "book or biosim (the baby boot)")->required();
    longRun->add_option("--final-time", options->finalTime, "s, how long each setting runs (default 1000)")
        ->check(simlab::between(1.0, 1e5));
    longRun->add_flag("--quick", options->quick,
                      "a final time of 20 s (seconds of work), unless --final-time is given");
    longRun->add_option("--output,-o", options->output, "folder for the CSV and the figure")->capture_default_str();
    longRun->add_flag("!--no-plots", options->plots, "the CSV and the table only");
    longRun->add_option("--file", options->file,
                        "follow this student file (the book's) instead of the reference solution: it is built with "
                        "grading's object check and run in grading's sandbox");
    longRun->callback([options] {
        if (!options->file.empty()) {
            study::CommandLine command;
            command.cores = cores();
            command.readSubmission = readSubmission;
            // The view's own status: 1 when a setting stopped short (its table says where and why).
            if (const int status = study::runLongRunOfFile(*options, command); status != 0) std::exit(status);
            return;
        }
        const std::vector<std::string> command = study::longRunCommand(*options, cores());
        handOver(command.front(), command);
    });
}

}  // namespace simlab::cli
