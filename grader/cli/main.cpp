// simlab: the course's one command for students and instructors.
#include <CLI/CLI.hpp>
#include <iostream>

#include "commands.h"
#include "simlab/common/errors.h"
#include "simlab/common/text.h"
#include "simlab/reproducible_math.h"
#include "simlab/rubric/rubric.h"

int main(int argc, char** argv) {
    // Everything simlab starts inherits the mask (the judges and probes get it from childEnvironment).
    simlab::useReproducibleMath(argv);
    CLI::App app{"simlab: Simbody labs and their autograder.\n"
                 "Students: `simlab check apple` grades your starter/apple/NewtonsApple.cpp on the visible tests.\n"
                 "Instructors: `simlab grade apple SUBMISSIONS` grades a class on every test.",
                 "simlab"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "simlab " SIMLAB_VERSION, "print simlab's version and exit");
    app.failure_message([](const CLI::App* failed, const CLI::Error& e) {
        const std::string name = failed ? failed->get_name() : "simlab";
        const std::string command = name == "simlab" ? "simlab" : "simlab " + name;
        return "simlab: error: " + std::string(e.what()) + " (see " + command + " --help)\n";
    });
    simlab::cli::addCheck(app);
    simlab::cli::addGrade(app);
    simlab::cli::addBuild(app);
    simlab::cli::addList(app);
    simlab::cli::addLock(app);
    simlab::cli::addPackage(app);
    simlab::cli::addAutograde(app);
    simlab::cli::addExport(app);
    simlab::cli::addProject(app);
    simlab::cli::addAssignment(app);
    simlab::cli::addStudy(app);
    simlab::cli::addPlot(app);
    simlab::cli::addSimilarity(app);
    simlab::cli::addSlurm(app);
    // CLI11 would call an unknown command a missing one; say what it is.
    if (argc > 1 && argv[1][0] != '-') {
        bool known = false;
        std::string commands;
        for (const CLI::App* sub : app.get_subcommands({})) {
            known = known || sub->get_name() == argv[1];
            commands += (commands.empty() ? "" : ", ") + sub->get_name();
        }
        if (!known) {
            std::cerr << "simlab: error: unknown command '" << simlab::engine::printable(argv[1]) << "'; commands: "
                      << commands << '\n';
            return 2;
        }
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;
    } catch (const simlab::engine::UsageError& e) {
        std::cerr << "simlab: error: " << simlab::engine::printable(e.what()) << '\n';
        return 2;
    } catch (const simlab::RubricError& e) {
        std::cerr << "simlab: error in the rubric: " << simlab::engine::printable(e.what()) << '\n';
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "simlab: error: " << simlab::engine::printable(e.what()) << '\n';
        return 1;
    }
    return 0;
}
