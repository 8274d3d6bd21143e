// handout-check: runs the commands a handout shows and compares their output with what the handout prints, so
// a handout cannot drift from the programs it describes.
//
// In a ```console block, a line "$ command" is a command and the lines after it, up to the next command, are its
// expected output. A command shown without output is not run (building, opening a plot window). In expected
// output, a line "..." stands for any number of lines and "..." inside a line for any text; trailing spaces are
// ignored, and the exit status is not checked (a starter stopping at a TODO is the point of some examples).
//
// Commands run in a scratch folder laid out like the top of the simlab tree: build/bin holds the lab programs and
// simlab, handouts/ is the real one. A block opened as ```console solution runs as if the student had finished:
// build/bin/<program> is the program built from the reference solution, and the in-tree student folder (what
// `simlab check <id>` grades by default) holds a copy of the solution's folder.
//
//   handout-check HANDOUT.md [--keep DIR] [--finished SOLUTIONS]
//
// --keep DIR leaves the two trees in DIR (starter-tree, solution-tree) with what ran in them: the files the commands
// wrote and each command's output, named by the command ("$ build/bin/simlab study trade apple --quick" prints to
// simlab-study-trade-apple-quick.out), for tests that read a handout's runs instead of running them again.
//
// --finished SOLUTIONS takes each finished folder from SOLUTIONS/<id>/ and builds build/bin/<program> from it with
// `simlab build`, as a student who finished would: so the examples run in a copy of simlab that holds no reference
// solution, the student bundle (SIMLAB_MANIFEST names its build's manifest, and HANDOUT.md is its copy).
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "simlab/common/files.h"
#include "simlab/build/manifest.h"
#include "simlab/isolation/process.h"

namespace fs = std::filesystem;
using namespace simlab::engine;
using namespace simlab::isolation;

namespace {

struct Example {
    int line = 0;  // of the command, in the handout
    bool solution = false;
    std::string command;
    std::vector<std::string> expected;
};

std::string trimRight(std::string s) {
    while (!s.empty() && (s.back() == ' ' || s.back() == '\r')) s.pop_back();
    return s;
}

std::vector<Example> parse(const std::string& path) {
    std::ifstream in(path);
    std::vector<Example> examples;
    std::string line;
    bool inBlock = false, solution = false;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        if (!inBlock && line.rfind("```console", 0) == 0) {
            inBlock = true;
            solution = line.find("solution") != std::string::npos;
        } else if (inBlock && line.rfind("```", 0) == 0) {
            inBlock = false;
        } else if (inBlock && line.rfind("$ ", 0) == 0) {
            examples.push_back({number, solution, line.substr(2), {}});
        } else if (inBlock && !examples.empty()) {
            examples.back().expected.push_back(trimRight(line));
        }
    }
    return examples;
}

// `text` matches `pattern`, where "..." in the pattern matches any run of characters.
bool lineMatches(const std::string& pattern, const std::string& text) {
    const std::size_t wild = pattern.find("...");
    if (wild == std::string::npos) return pattern == text;
    if (text.compare(0, wild, pattern, 0, wild) != 0) return false;
    const std::string rest = pattern.substr(wild + 3);
    for (std::size_t at = wild; at <= text.size(); ++at) {
        if (lineMatches(rest, text.substr(at))) return true;
    }
    return false;
}

// The lines match, a pattern line "..." standing for any number of lines.
bool linesMatch(const std::vector<std::string>& pattern, std::size_t p, const std::vector<std::string>& text,
                std::size_t t) {
    if (p == pattern.size()) return t == text.size();
    if (pattern[p] == "...") {
        for (std::size_t skip = t; skip <= text.size(); ++skip) {
            if (linesMatch(pattern, p + 1, text, skip)) return true;
        }
        return false;
    }
    return t < text.size() && lineMatches(pattern[p], text[t]) && linesMatch(pattern, p + 1, text, t + 1);
}

std::vector<std::string> splitLines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) lines.push_back(trimRight(line));
    while (!lines.empty() && lines.back().empty()) lines.pop_back();
    return lines;
}

// `simlab build ID SOURCE -o PROGRAM` with the simlab of `manifest`: the lab program of a finished file, as a student
// builds it.
void buildProgram(const Manifest& manifest, const std::string& id, const std::string& source,
                  const std::string& program) {
    ProcessRequest request;
    request.argv = {manifest.buildDir + "/bin/simlab", "build", id, source, "--output", program};
    request.env = childEnvironment({"SIMLAB_MANIFEST=" + manifest.path, "LC_ALL=C"});
    request.workDir = fs::path(program).parent_path().string();
    request.limits.cpuSeconds = 300;
    request.limits.wallSeconds = 1500;
    request.limits.processes = 64;
    request.limits.memoryMiB = 8192;
    const ProcessResult result = runProcess(request);
    if (!result.exitedCleanly()) throw std::runtime_error("simlab build " + id + " " + source + ":\n" + result.output);
}

// A scratch tree for one mode: build/bin with the programs, handouts/, and a manifest whose student files are
// the starters (or copies of the finished folders: the solutions', or those in `finished`).
void prepare(const Manifest& manifest, const std::string& root, bool solution, const std::string& finishedDir) {
    fs::create_directories(root + "/build/bin");
    fs::create_symlink(manifest.sourceDir + "/handouts", root + "/handouts");
    fs::create_symlink(manifest.buildDir + "/bin/simlab", root + "/build/bin/simlab");
    nlohmann::json json = nlohmann::json::parse(readFile(manifest.path));
    for (nlohmann::json& a : json["assignments"]) {
        const std::string id = a["id"], program = a["program"], source = a["source"];
        // A reference program with a name of its own (the project's worked example, babyboot) is there too.
        const std::string reference = a["reference_program_path"];
        const std::string referenceName = fs::path(reference).filename().string();
        if (!reference.empty() && referenceName != program + "-reference" && referenceName != program) {
            fs::create_symlink(reference, root + "/build/bin/" + referenceName);
        }
        if (!solution) {
            fs::create_symlink(a["program_path"].get<std::string>(), root + "/build/bin/" + program);
            continue;
        }
        // The whole finished folder: the solution and what is handed in beside it (answers, say).
        const std::string solutionFile = a["solution"];
        const fs::path finished = finishedDir.empty() ? fs::path(solutionFile).parent_path() : fs::path(finishedDir) / id;
        if (finishedDir.empty() ? solutionFile.empty() : !fs::is_directory(finished)) {
            throw std::runtime_error("no finished folder for " + id + (finishedDir.empty() ? "" : " in " + finishedDir));
        }
        const fs::path copy = fs::path(root) / "starter" / id;
        fs::create_directories(copy);
        for (const fs::directory_entry& file : fs::directory_iterator(finished)) {
            if (file.is_regular_file()) fs::copy_file(file.path(), copy / file.path().filename());
        }
        a["starter"] = (copy / source).string();
        if (finishedDir.empty()) {
            fs::create_symlink(a["reference_program_path"].get<std::string>(), root + "/build/bin/" + program);
        } else {
            buildProgram(manifest, id, (copy / source).string(), root + "/build/bin/" + program);
        }
    }
    writeFileAtomically(root + "/manifest.json", json.dump(2));
}

// The file a kept command's output goes to: its words, from the program's name on, joined by '-'.
std::string outputName(const std::string& command) {
    std::string name;
    for (const char c : command.substr(command.rfind("build/bin/", 0) == 0 ? 10 : 0)) {
        if (std::isalnum(static_cast<unsigned char>(c))) name += c;
        else if (!name.empty() && name.back() != '-') name += '-';
    }
    while (!name.empty() && name.back() == '-') name.pop_back();
    return name.substr(0, 120) + ".out";
}

}  // namespace

int main(int argc, char** argv) {
    std::string keepDir, finishedDir;
    bool usage = argc < 2 || argc % 2 != 0;
    for (int i = 2; i + 1 < argc && !usage; i += 2) {
        const std::string option = argv[i];
        if (option == "--keep") keepDir = argv[i + 1];
        else if (option == "--finished") finishedDir = fs::absolute(argv[i + 1]).string();
        else usage = true;
    }
    if (usage) {
        std::cerr << "usage: handout-check HANDOUT.md [--keep DIR] [--finished SOLUTIONS]\n";
        return 2;
    }
    const bool keep = !keepDir.empty();
    try {
        const Manifest manifest = loadManifest();
        const std::vector<Example> examples = parse(argv[1]);
        TempDir scratch("simlab-handout-");
        const std::string top = keep ? fs::absolute(keepDir).string() : scratch.path();
        if (keep) {
            fs::remove_all(top);
            fs::create_directories(top);
        }
        const std::string starterRoot = top + "/starter-tree", solutionRoot = top + "/solution-tree";
        prepare(manifest, starterRoot, false, finishedDir);
        const bool anySolution = std::any_of(examples.begin(), examples.end(), [](const Example& e) {
            return e.solution && !e.expected.empty();
        });
        if (anySolution) prepare(manifest, solutionRoot, true, finishedDir);

        int run = 0, failed = 0;
        for (const Example& e : examples) {
            if (e.expected.empty()) continue;
            ++run;
            const std::string root = e.solution ? solutionRoot : starterRoot;
            ProcessRequest request;
            request.argv = {"/bin/bash", "-c", e.command};
            request.env = childEnvironment({"SIMLAB_MANIFEST=" + root + "/manifest.json", "LC_ALL=C"});
            request.workDir = root;
            // CPU time decides, so that a busy machine runs the same examples; wall time is a wide net.
            request.limits.cpuSeconds = 300;
            request.limits.wallSeconds = 1500;
            request.limits.processes = 64;
            request.limits.memoryMiB = 8192;
            request.keepOutput = 1 << 20;
            const ProcessResult result = runProcess(request);
            if (keep) writeFileAtomically(root + "/" + outputName(e.command), result.output);
            std::vector<std::string> expected = e.expected;
            while (!expected.empty() && expected.back().empty()) expected.pop_back();
            const std::vector<std::string> actual = splitLines(result.output);
            char took[32];
            std::snprintf(took, sizeof took, " (%.1f s)", result.wallSeconds);
            if (linesMatch(expected, 0, actual, 0)) {
                std::cout << "ok: line " << e.line << ": $ " << e.command << took << "\n";
                continue;
            }
            ++failed;
            std::cout << "MISMATCH: line " << e.line << ": $ " << e.command << "\n--- the handout shows:\n";
            for (const std::string& l : expected) std::cout << l << "\n";
            std::cout << "--- the command printed:\n" << result.output << "---\n";
        }
        std::cout << run << " examples run, " << failed << " differ\n";
        return failed == 0 && run > 0 ? 0 : 1;
    } catch (const std::exception& e) {
        std::cerr << "handout-check: error: " << e.what() << '\n';
        return 2;
    }
}
