// The simlab subcommands. Each add* function declares a subcommand's options and what it runs; main() only
// wires them together.
#pragma once

namespace CLI {
class App;
}

namespace simlab::cli {

void addCheck(CLI::App& app);
void addGrade(CLI::App& app);
void addBuild(CLI::App& app);
void addList(CLI::App& app);
void addPackage(CLI::App& app);
void addAutograde(CLI::App& app);

}  // namespace simlab::cli
