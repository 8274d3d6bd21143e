#include "simlab/engine/package.h"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <set>
#include <sstream>

#include "simlab/engine/build.h"
#include "simlab/engine/errors.h"
#include "simlab/engine/files.h"
#include "simlab/engine/process.h"
#include "simlab/engine/text.h"

namespace fs = std::filesystem;

namespace simlab::engine {

namespace {

bool startsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

// Runs a trusted tool to completion; its output, or throws with it.
std::string runTool(const std::vector<std::string>& argv, const std::string& dir) {
    ProcessRequest r;
    r.argv = argv;
    r.env = childEnvironment({"LC_ALL=C"});
    r.workDir = dir;
    r.limits.wallSeconds = r.limits.cpuSeconds = 300;
    r.limits.fileMiB = 4096;
    r.limits.outputKiB = 64 * 1024;
    r.keepOutput = 64 << 20;
    const ProcessResult result = runProcess(r);
    if (!result.exitedCleanly()) {
        throw std::runtime_error(argv[0] + " failed: " + (result.started ? firstLines(result.output, 3) : result.error));
    }
    return result.output;
}

std::string relativeTo(const std::string& path, const std::string& base) {
    return fs::relative(path, base).generic_string();
}

// Files left out of a package, by the rule that leaves them out.
struct Rule {
    std::string description;
    std::function<bool(const std::string&)> matches;
};

PackageSummary copyFiles(const Manifest& manifest, const std::vector<Rule>& rules, const std::string& outDir) {
    PackageSummary summary;
    std::vector<int> counts(rules.size(), 0);
    for (const std::string& file : projectFiles(manifest.sourceDir)) {
        bool left = false;
        for (std::size_t i = 0; i < rules.size() && !left; ++i) {
            if (rules[i].matches(file)) {
                ++counts[i];
                left = true;
            }
        }
        if (left) continue;
        const fs::path target = fs::path(outDir) / file;
        fs::create_directories(target.parent_path());
        fs::copy_file(fs::path(manifest.sourceDir) / file, target, fs::copy_options::overwrite_existing);
        ++summary.files;
    }
    for (std::size_t i = 0; i < rules.size(); ++i) {
        if (counts[i] > 0) summary.left.push_back(rules[i].description + " (" + std::to_string(counts[i]) + (counts[i] == 1 ? " file)" : " files)"));
    }
    return summary;
}

std::vector<Rule> instructorOnly() {
    return {
        // The project's reference solution is its worked example, the baby boot, which students are given.
        {"solutions/ (but the worked example project, solutions/biosim/)",
         [](const std::string& f) { return startsWith(f, "solutions/") && !startsWith(f, "solutions/biosim/"); }},
        {"tests/: the corpus is made from the solutions and holds expected scores",
         [](const std::string& f) { return startsWith(f, "tests/"); }},
        {".ci/ and bench/", [](const std::string& f) { return startsWith(f, ".ci/") || startsWith(f, "bench/"); }},
    };
}

// Catch2 2.13's single header from this system (Boost Software License; the notice is at its top) and a main
// for it, in third_party/catch2: CMakeLists.txt builds the grader with them where the system's Catch2 is not 2.13
// (Ubuntu 24.04 ships Catch2 3).
void addCatch2(const Manifest& manifest, const std::string& dir, PackageSummary& summary) {
    fs::create_directories(dir + "/third_party/catch2");
    fs::copy_file(manifest.catch2Include + "/catch2/catch.hpp", dir + "/third_party/catch2/catch.hpp",
                  fs::copy_options::overwrite_existing);
    writeFileAtomically(dir + "/third_party/catch2/catch_main.cpp",
                        "// Catch2's main, for systems without Catch2 2.13 (see CMakeLists.txt).\n"
                        "#define CATCH_CONFIG_MAIN\n#include \"catch2/catch.hpp\"\n");
    summary.files += 2;
}

// The handouts as pages. Each handouts/<id>.md becomes handouts/<id>.html beside it: pandoc, standalone, with its
// images inlined and its mathematics as MathML, so that the page opens from disk with no network. Where the
// assignment's reference program draws (--plot) and replays (--replay), the page ends with the reference run's plot
// and a link to its replay page, made here by running it. Says in `summary` what it made, or why nothing.
void addHandoutPages(const Manifest& manifest, const std::string& dir, PackageSummary& summary) {
    const std::string pandoc = fs::exists("/usr/bin/pandoc") ? "/usr/bin/pandoc" : "";
    if (pandoc.empty()) {
        summary.made.push_back("no handout pages: pandoc is not installed (scripts/install-deps installs it)");
        return;
    }
    const std::string handouts = fs::absolute(dir).string() + "/handouts";  // the programs run elsewhere
    int pages = 0, runs = 0;
    for (const Assignment& a : manifest.assignments) {
        const std::string markdown = handouts + "/" + a.id + ".md";
        if (!fs::exists(markdown)) continue;
        std::string after;
        if (!a.referenceProgramPath.empty()) {
            TempDir scratch("simlab-handout-");
            const std::string plot = "figures/" + a.id + "-reference.svg", replay = a.id + "-replay.html";
            ProcessRequest r;
            r.argv = {a.referenceProgramPath, "--quiet", "--output", scratch.path() + "/results.txt", "--plot",
                      handouts + "/" + plot, "--replay", handouts + "/" + replay};
            r.env = childEnvironment({"LC_ALL=C"});
            r.workDir = scratch.path();
            r.limits.wallSeconds = r.limits.cpuSeconds = 120;
            r.limits.outputKiB = 1024;
            r.keepOutput = 4096;
            const ProcessResult ran = runProcess(r);
            if (ran.exitedCleanly() && fs::exists(handouts + "/" + plot) && fs::exists(handouts + "/" + replay)) {
                ++runs;
                after = "<section id=\"reference-run\">\n<h2>The reference solution's run</h2>\n<p>What <code>" + a.program +
                        "</code> draws with <code>--plot</code> on the reference solution, with its default settings:</p>\n"
                        "<p><img src=\"" + plot + "\" alt=\"the reference run against the exact solution\" "
                        "style=\"max-width: 100%\"></p>\n<p><a href=\"" + replay + "\">Replay the run in 3-D</a> "
                        "(<code>--replay</code>: a page of its own, which also opens offline).</p>\n</section>\n";
            } else {
                std::error_code ignored;
                fs::remove(handouts + "/" + plot, ignored);
                fs::remove(handouts + "/" + replay, ignored);
                // A program that does not draw refuses the options (a usage error, 2): its page is the handout
                // alone. Anything else is a run that should have drawn, and is said.
                if (!(ran.started && ran.signal == 0 && ran.exitCode == 2)) {
                    std::string said = ran.output.substr(0, ran.output.find_last_not_of("\n") + 1);
                    said = said.substr(said.find_last_of('\n') + 1);  // its last line: the error
                    summary.made.push_back("no reference run in handouts/" + a.id + ".html: " + a.program + " " +
                                           (ran.started ? "failed: " + printable(said) : ran.error));
                }
            }
        }
        std::string title = a.title.empty() ? a.id : a.title;
        std::vector<std::string> argv = {pandoc, a.id + ".md", "--standalone", "--self-contained", "--mathml",
                                         "--metadata", "pagetitle=" + title, "--output", a.id + ".html"};
        const std::string afterFile = handouts + "/." + a.id + "-after.html";
        if (!after.empty()) {
            writeFileAtomically(afterFile, after);
            argv.push_back("--include-after-body=." + a.id + "-after.html");
        }
        runTool(argv, handouts);
        std::error_code ignored;
        fs::remove(afterFile, ignored);
        ++pages;
    }
    summary.files += pages + 2 * runs;
    summary.made.push_back(std::to_string(pages) + " handout pages (handouts/<id>.html), " + std::to_string(runs) +
                           " with the reference run's plot and replay");
}

void makeExecutable(const std::string& path) {
    fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                    fs::perm_options::add);
}

}  // namespace

std::vector<std::string> projectFiles(const std::string& sourceDir) {
    std::vector<std::string> files;
    if (fs::exists(fs::path(sourceDir) / ".git") && fs::exists("/usr/bin/git")) {
        std::istringstream list(runTool({"/usr/bin/git", "-C", sourceDir, "ls-files", "--cached", "--others",
                                         "--exclude-standard"},
                                        sourceDir));
        std::string file;
        while (std::getline(list, file)) {
            if (fs::is_regular_file(fs::path(sourceDir) / file)) files.push_back(file);  // not deleted since
        }
    } else {
        auto it = fs::recursive_directory_iterator(sourceDir);
        for (; it != fs::recursive_directory_iterator(); ++it) {
            const fs::path& p = it->path();
            if (it->is_directory() && (p.filename() == ".git" || fs::exists(p / "CMakeCache.txt"))) {
                it.disable_recursion_pending();
            } else if (it->is_regular_file()) {
                files.push_back(relativeTo(p.string(), sourceDir));
            }
        }
    }
    std::sort(files.begin(), files.end());
    files.erase(std::unique(files.begin(), files.end()), files.end());
    return files;
}

PackageSummary writeStudentBundle(const Manifest& manifest, const std::string& outDir) {
    if (fs::exists(outDir) && !fs::is_empty(outDir)) {
        throw UsageError("'" + outDir + "' exists and is not empty; name a new folder");
    }
    std::set<std::string> hidden;
    for (const Assignment& a : manifest.assignments) {
        for (const std::string& h : a.hiddenTests) hidden.insert(relativeTo(h, manifest.sourceDir));
    }
    std::vector<Rule> rules = instructorOnly();
    rules.push_back({"hidden tests", [hidden](const std::string& f) { return hidden.count(f) > 0; }});
    rules.push_back({"README.md: replaced by handouts/README-student.md",
                     [](const std::string& f) { return f == "README.md"; }});
    fs::create_directories(outDir);
    PackageSummary summary = copyFiles(manifest, rules, outDir);
    fs::copy_file(manifest.sourceDir + "/handouts/README-student.md", outDir + "/README.md");
    ++summary.files;
    addCatch2(manifest, outDir, summary);
    addHandoutPages(manifest, outDir, summary);
    return summary;
}

PackageSummary writeGradescopeZip(const Manifest& manifest, const Assignment& assignment, const std::string& zip) {
    if (!fs::exists("/usr/bin/zip")) throw UsageError("zip is not installed (apt-get install zip)");
    if (!assignment.hiddenTestsBuilt) {
        throw UsageError("the autograder needs the hidden tests, which this copy of simlab does not have");
    }
    const fs::path target = fs::absolute(zip);
    if (!fs::is_directory(target.parent_path())) {
        throw UsageError("cannot write '" + zip + "': no directory " + target.parent_path().string());
    }
    TempDir staging("simlab-gradescope-");
    PackageSummary summary = copyFiles(manifest, instructorOnly(), staging.path());

    writeFileAtomically(staging.path() + "/setup.sh",
        "#!/usr/bin/env bash\n"
        "# Gradescope runs this once, as root, to build the autograder image. Choose an Ubuntu 24.04 (or newer)\n"
        "# base image: simlab needs CMake 3.25 and libtomlplusplus-dev.\n"
        "set -euo pipefail\n"
        "source_dir=$(cd \"$(dirname \"${BASH_SOURCE[0]}\")\" && pwd)\n"
        "SIMLAB_CMAKE_ARGS=\"-DBUILD_TESTING=OFF ${SIMLAB_CMAKE_ARGS:-}\" \"$source_dir/scripts/setup\"\n");
    writeFileAtomically(staging.path() + "/run_autograder",
        "#!/usr/bin/env bash\n"
        "# Gradescope runs this for every submission: it grades /autograder/submission on every test of the\n"
        "# " + assignment.id + " assignment and writes /autograder/results/results.json.\n"
        "# AUTOGRADER_ROOT replaces /autograder (for testing).\n"
        "root=${AUTOGRADER_ROOT:-/autograder}\n"
        "exec \"$root/source/build/bin/simlab\" autograde " + assignment.id +
            " --submission \"$root/submission\" --results \"$root/results/results.json\"\n");
    addCatch2(manifest, staging.path(), summary);
    makeExecutable(staging.path() + "/setup.sh");
    makeExecutable(staging.path() + "/run_autograder");
    summary.files += 2;

    std::error_code ignored;
    fs::remove(target, ignored);
    runTool({"/usr/bin/zip", "-q", "-r", "-X", target.string(), "."}, staging.path());
    return summary;
}

}  // namespace simlab::engine
