// simlab project new: a biosimulation project of one's own, from the template (or from the worked example), in a
// folder that builds with CMake against this simlab.
#include <algorithm>
#include <CLI/CLI.hpp>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.h"
#include "simlab/build/build.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/build/manifest.h"
#include "simlab/common/text.h"

namespace simlab::cli {

namespace {

namespace fs = std::filesystem;

struct ProjectOptions {
    std::string output;
    std::string name;
    std::string dir = ".";
    std::string from = "template";
};

std::string readText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw engine::UsageError("cannot read " + path.string());
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::string replaceAll(std::string text, const std::string& from, const std::string& to) {
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
        text.replace(at, from.size(), to);
    }
    return text;
}

void requireProjectName(const std::string& name) {
    bool ok = !name.empty() && name.size() <= 40 && std::isalpha(static_cast<unsigned char>(name[0]));
    for (const char c : name) ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_');
    if (!ok) {
        throw engine::UsageError("a project's name is a letter, then up to 39 letters, digits or _ (it names its "
                                 "program), not '" + engine::printable(name) + "'");
    }
    // The name becomes a CMake target: not one of the targets CMake's generators make themselves.
    static const char* const reserved[] = {"all",     "clean",         "help",          "install",   "test",
                                           "package", "package_source", "edit_cache",   "rebuild_cache",
                                           "preinstall", "zero_check", "run_tests",     "all_build", "depend"};
    std::string lower;
    for (const char c : name) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const char* word : reserved) {
        if (lower == word) {
            throw engine::UsageError("'" + name + "' is a name CMake keeps for its own targets: choose another");
        }
    }
}

void runNew(const ProjectOptions& o) {
    requireProjectName(o.name);
    const engine::Manifest manifest = engine::loadManifest();
    const engine::Assignment& biosim = manifest.find("biosim");
    fs::path source;
    if (o.from == "template") {
        source = fs::path(biosim.starter).parent_path();
    } else {
        if (biosim.solution.empty()) throw engine::UsageError("this copy of simlab has no worked example");
        source = fs::path(biosim.solution).parent_path();
    }
    if (!fs::is_directory(o.dir)) throw engine::UsageError("no folder " + engine::printable(o.dir));
    const fs::path folder = fs::absolute(fs::path(o.dir) / o.name).lexically_normal();
    if (fs::exists(fs::symlink_status(folder)) && !(fs::is_directory(folder) && fs::is_empty(folder))) {
        throw engine::UsageError(engine::printable(folder.string()) + " already exists; choose another name or folder");
    }
    fs::create_directories(folder);

    std::string code = readText(source / "Project.cpp");
    std::string description = readText(source / "project.toml");
    // simlab is not on the PATH (a bundle builds it into build/bin): the project's files and the lines below name
    // this simlab by its full path, which works from the project's folder.
    const std::string simlab = shellWord(engine::printable(selfPath()));
    if (o.from == "template") {
        code = replaceAll(replaceAll(code, "PROJECT_NAME", o.name), "PROJECT_TITLE", o.name);
        description = replaceAll(replaceAll(description, "PROJECT_NAME", o.name), "PROJECT_TITLE", o.name);
        // The course tree's build/bin/simlab, from the project's own folder.
        code = replaceAll(code, "build/bin/simlab ", simlab + " ");
        description = replaceAll(description, "build/bin/simlab ", simlab + " ");
    } else {
        code = replaceAll(code, "d.program = \"babyboot\";", "d.program = \"" + o.name + "\";");
        description = replaceAll(description, "name = \"babyboot\"", "name = \"" + o.name + "\"");
        // The copy's program is ./build/NAME, and it names its drawings after itself.
        description = replaceAll(description, "`babyboot --", "`./build/" + o.name + " --");
        description = replaceAll(description, "(babyboot-", "(" + o.name + "-");
    }
    engine::writeFileAtomically((folder / "Project.cpp").string(), code);
    engine::writeFileAtomically((folder / "project.toml").string(), description);
    // find_package(simlab) finds this simlab's CMake package: where it was when the project was made, or wherever
    // CMAKE_PREFIX_PATH or simlab_DIR says.
    const std::string package = manifest.installed ? manifest.prefix + "/lib/cmake/simlab" : manifest.buildDir;
    engine::writeFileAtomically(
        (folder / "CMakeLists.txt").string(),
        "# " + o.name + ": a biosimulation project, built against simlab (made by `simlab project new`).\n"
            "cmake_minimum_required(VERSION 3.25)\n"
            "project(" + o.name + " CXX)\n"
            "find_package(simlab " + manifest.version + " REQUIRED CONFIG HINTS \"" + package + "\")\n"
            "simlab_project(" + o.name + " Project.cpp)\n");
    engine::writeFileAtomically((folder / ".gitignore").string(), "build/\n*Results.txt\n");

    const std::string shown = engine::printable(folder.string());
    std::cout << "Made " << shown << " from the " << (o.from == "template" ? "project template" : "baby boot")
              << ": Project.cpp, project.toml, CMakeLists.txt.\n"
              << "Next:\n"
              << "  cd " << shown << "\n"
              << "  cmake -S . -B build && cmake --build build     # build the lab program ./build/" << o.name << "\n"
              << "  ./build/" << o.name << " --help\n"
              << "  " << simlab << " check biosim Project.cpp\n"
              << "      (what is done, and what to do next)\n";
}

// A CMake list of `items`, one bracket argument each (nothing in them is read as CMake syntax).
std::string cmakeList(const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& item : items) {
        if (item.find("]==]") != std::string::npos || item.find(';') != std::string::npos) {
            throw engine::UsageError("simlab's path " + engine::printable(item) + " cannot be written in CMake");
        }
        out += " [==[" + item + "]==]";
    }
    return out;
}

// What a lab of one's own builds against (simlab_add_lab in cmake/simlabConfig.cmake.in): the folders of simlab's
// CMake scripts and of the course's tree, and simlab_kit_targets(), which makes each library of the manifest's kit
// an imported target of the name simlab_add_assignment() uses, its headers the kit's.
std::string cmakeKit(const engine::Manifest& manifest) {
    const engine::Kit& kit = manifest.kit;
    if (kit.targets.empty()) return "";
    std::string out = "set(SIMLAB_KIT_CMAKE_DIR" + cmakeList({kit.cmakeDir}) + ")\n"
                      "set(SIMLAB_KIT_SOURCE_DIR" + cmakeList({manifest.sourceDir}) + ")\n"
                      "function(simlab_kit_targets)\n";
    out += "  set(include" + cmakeList(kit.include) + ")\n";
    for (const engine::Kit::Target& t : kit.targets) {
        std::string links;
        for (const std::string& link : t.links) {
            links += link == "Simbody" ? std::string(" ${Simbody_LIBRARIES}") : cmakeList({link});
        }
        out += "  add_library(" + t.name + " " + t.kind + " IMPORTED GLOBAL)\n"
               "  set(files" + cmakeList(t.files) + ")\n"
               "  set(links" + links + ")\n"
               "  set_target_properties(" + t.name + " PROPERTIES INTERFACE_INCLUDE_DIRECTORIES \"${include}\"\n"
               "                        INTERFACE_LINK_LIBRARIES \"${links}\"";
        if (t.kind == "OBJECT") out += " IMPORTED_OBJECTS \"${files}\"";
        if (t.kind == "STATIC") out += " IMPORTED_LOCATION \"${files}\"";
        out += ")\n";
    }
    return out + "endfunction()\n";
}

// What simlab's CMake package (cmake/simlabConfig.cmake.in) reads: what a lab of one's own builds against, and, where
// this simlab has the biosim lab, how a project builds (its compile command, with its precompiled header made if
// this is an installed simlab, and the lab program's link). A Gradescope archive of one lab has no biosim lab:
// simlab_project() then stops in one line.
void runCMakeConfig(const ProjectOptions& o) {
    const engine::Manifest manifest = engine::loadManifest();
    const std::vector<std::string> ids = manifest.ids();
    std::string project = "set(SIMLAB_PROJECT_COMPILE)\n";
    if (std::find(ids.begin(), ids.end(), "biosim") != ids.end()) {
        const engine::Assignment& biosim = manifest.find("biosim");
        engine::ensurePrecompiledHeader(manifest, biosim);
        const std::vector<std::string> linkOptions(manifest.link.begin() + (manifest.link.empty() ? 0 : 1),
                                                   manifest.link.end());
        project = "set(SIMLAB_PROJECT_COMPILE" + cmakeList(biosim.compile) + ")\n"
                  "set(SIMLAB_PROJECT_CONTRACT" + cmakeList({biosim.contractInclude}) + ")\n"
                  "set(SIMLAB_PROJECT_LINK_OPTIONS" + cmakeList(linkOptions) + ")\n"
                  "set(SIMLAB_PROJECT_OBJECTS" + cmakeList(biosim.programObjects) + ")\n"
                  "set(SIMLAB_PROJECT_LIBRARIES" + cmakeList(manifest.programLibraries) + ")\n";
    }
    engine::writeFileAtomically(o.output, "# Written by " + selfPath() +
                                              " project cmake-config: how a project builds against it.\n" +
                                              project + cmakeKit(manifest));
}

}  // namespace

void addProject(CLI::App& app) {
    CLI::App* project = app.add_subcommand("project", "Biosimulation projects: start one of your own.");
    project->require_subcommand(1);
    auto options = std::make_shared<ProjectOptions>();
    CLI::App* make = project->add_subcommand(
        "new", "Make a project folder DIR/NAME from the template: Project.cpp (your model), project.toml (its "
               "description) and a CMakeLists.txt that builds its lab program ./build/NAME.");
    make->add_option("name", options->name, "the project's name, which is also its program's")->required();
    make->add_option("dir", options->dir, "the folder to make it in")->capture_default_str();
    make->add_option("--from", options->from, "template, or babyboot: start from the worked example")
        ->check(CLI::IsMember({"template", "babyboot"}))
        ->capture_default_str();
    make->callback([options] { runNew(*options); });

    // What find_package(simlab) runs (cmake/simlabConfig.cmake.in): not listed, since nobody types it.
    auto config = std::make_shared<ProjectOptions>();
    CLI::App* cmake = project->add_subcommand(
        "cmake-config", "Write FILE: the CMake variables simlab_project() builds a project's program with.");
    cmake->group("");
    cmake->add_option("file", config->output, "the file to write")->required();
    cmake->callback([config] { runCMakeConfig(*config); });
}

}  // namespace simlab::cli
