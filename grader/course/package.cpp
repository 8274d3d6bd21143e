#include "simlab/course/package.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "simlab/build/build.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/isolation/process.h"
#include "simlab/grading/report.h"
#include "simlab/common/text.h"
#include "simlab/rubric/rubric.h"
#include "simlab/writers/html.h"

namespace fs = std::filesystem;

namespace simlab::engine {

namespace {

bool startsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

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

// The scripts a platform runs, as the tree holds them (grader/course/scripts/, made text at build time).
const char* const kGradescopeSetup =
#include "gradescope-setup.sh.inc"
    ;
const char* const kGradescopeRun =
#include "gradescope-run_autograder.sh.inc"
    ;
const char* const kPrairieLearnRun =
#include "prairielearn-run_autograder.sh.inc"
    ;

std::vector<Rule> instructorOnly(const Manifest& manifest) {
    // A worked example's solution (simlab_add_assignment's WORKED_EXAMPLE) is given to students; every other
    // solution is no student's (secretPaths, `simlab list --secrets`).
    std::vector<std::string> shipped;
    std::string kept;
    for (const Assignment& a : manifest.assignments) {
        if (!a.solutionShipped || a.solution.empty()) continue;
        shipped.push_back(relativeTo(fs::path(a.solution).parent_path().string(), manifest.sourceDir) + "/");
        kept += (kept.empty() ? "" : ", ") + shipped.back();
    }
    return {
        {"solutions/" + (kept.empty() ? std::string() : " (but the worked examples, " + kept + ")"),
         [shipped](const std::string& f) {
             return startsWith(f, "solutions/") &&
                    std::none_of(shipped.begin(), shipped.end(), [&](const std::string& s) { return startsWith(f, s); });
         }},
        {"tests/: the corpus is made from the solutions and holds expected scores",
         [](const std::string& f) { return startsWith(f, "tests/"); }},
        {".ci/ and bench/", [](const std::string& f) { return startsWith(f, ".ci/") || startsWith(f, "bench/"); }},
        // Labs of one's own, with their solutions, hidden tests and corpora: one is handed out as labs/<name>.
        {"examples/: labs of one's own, with their solutions", [](const std::string& f) { return startsWith(f, "examples/"); }},
    };
}

// Catch2 2.13's single header from this system (Boost Software License, its notice at its top) and a main
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
    // The header's notice points to the licence beside it: Debian's copyright file for the package holds it (and
    // THIRD_PARTY_NOTICES.md, copied into the bundle with the sources, holds it too).
    const std::string copyright = "/usr/share/doc/catch2/copyright";
    if (fs::exists(copyright)) {
        fs::copy_file(copyright, dir + "/third_party/catch2/LICENSE_1_0.txt", fs::copy_options::overwrite_existing);
        ++summary.files;
    }
}

// pandoc's Lua filter for the handout pages: every code block in a box (div.code) that takes the keyboard's focus,
// named for a screen reader by its kind and number, so that a block too wide for the page scrolls by keyboard.
const char kCodeBlocksFilter[] = R"(local names = { console = "console", sh = "shell commands", cpp = "C++ code",
                toml = "TOML", text = "text", gnuplot = "gnuplot script" }
local count = 0
function CodeBlock(block)
  count = count + 1
  local kind = block.classes[1]
  local label = ((kind and (names[kind] or kind)) or "text") .. ", example " .. count
  return pandoc.Div({ block }, pandoc.Attr("", { "code" }, { { "tabindex", "0" }, { "role", "group" },
                                                            { "aria-label", label } }))
end
)";

// `markdown` with each image that stands alone on its line and shows an SVG of handouts/ (`dir`) that carries a
// text alternative (a plot drawn by simlab) written as the shared figure: the plot's title as the image's alt,
// its description, and its points as tables. Other lines as they are.
std::string withPlotFigures(const std::string& markdown, const std::string& dir) {
    std::istringstream in(markdown);
    std::string out, line;
    bool fenced = false;
    int figures = 0;
    while (std::getline(in, line)) {
        const std::string trimmed = line.substr(0, line.find_last_not_of(" \t\r") + 1);
        const std::size_t start = trimmed.find_first_not_of(' ');
        if (start != std::string::npos && (trimmed.compare(start, 3, "```") == 0 || trimmed.compare(start, 3, "~~~") == 0)) {
            fenced = !fenced;
        }
        const std::size_t close = trimmed.find("](");
        if (!fenced && trimmed.rfind("![", 0) == 0 && close != std::string::npos && trimmed.back() == ')') {
            const std::string alt = trimmed.substr(2, close - 2), src = trimmed.substr(close + 2, trimmed.size() - close - 3);
            const bool plain = src.find_first_of(" \"'<>") == std::string::npos && src.find("..") == std::string::npos &&
                               src.size() > 4 && src.compare(src.size() - 4, 4, ".svg") == 0;
            const std::string svg = plain && fs::is_regular_file(dir + "/" + src) ? readFile(dir + "/" + src) : "";
            if (svg.find("<metadata id=\"simlab-plot-data\">") != std::string::npos) {
                out += writers::figureHtml("figure-" + std::to_string(++figures), src, svg, alt);
                continue;
            }
        }
        out += line + "\n";
    }
    return out;
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
    // A console block keeps its lines as a terminal shows them (pandoc's default style wraps them, so a table's
    // columns fall apart); a wide one scrolls.
    // Each block is in a box that takes the keyboard's focus (codeBlocks), so that one too wide for the page can be
    // scrolled without a mouse; the box scrolls, not the block in it.
    TempDir styleDir("simlab-handout-style-");
    const std::string style = styleDir.path() + "/style.html", filter = styleDir.path() + "/code-blocks.lua";
    writeFileAtomically(style, "<style>\nbody { max-width: 48em; }\n"
                               "pre, pre > code { white-space: pre; line-height: 1.35; }\n"
                               "pre { background: #f6f6f6; padding: 0.6em 0.8em; margin: 0; overflow: visible; }\n"
                               "div.code { overflow-x: auto; margin: 1em 0; background: #f6f6f6; }\n"
                               "div.code div.sourceCode { overflow: visible; margin: 0; }\n"
                               "div.code:focus-visible { outline: 2px solid #0b57d0; outline-offset: 2px; }\n"
                               "figure { margin: 1em 0; }\nfigcaption { color: #444; }\n"
                               "details.data table { margin: 0.5em 0 1em; border-collapse: collapse; }\n"
                               "details.data th, details.data td { padding: 2px 10px; text-align: right; }\n"
                               "details.data caption { text-align: left; font-weight: 600; }\n</style>\n");
    writeFileAtomically(filter, kCodeBlocksFilter);
    int pages = 0, runs = 0;
    for (const Assignment& a : manifest.assignments) {
        const std::string markdown = handouts + "/" + a.id + ".md";
        if (!fs::exists(markdown)) continue;
        std::string after;
        if (!a.referenceProgramPath.empty()) {
            TempDir scratch("simlab-handout-");
            const std::string plot = "figures/" + a.id + "-reference.svg", replay = a.id + "-replay.html";
            isolation::ProcessRequest r;
            r.argv = {a.referenceProgramPath, "--quiet", "--output", scratch.path() + "/results.txt", "--plot",
                      handouts + "/" + plot, "--replay", handouts + "/" + replay};
            r.env = isolation::childEnvironment({"LC_ALL=C"});
            r.workDir = scratch.path();
            r.limits.wallSeconds = r.limits.cpuSeconds = 120;
            r.limits.outputKiB = 1024;
            r.keepOutput = 4096;
            const isolation::ProcessResult ran = isolation::runProcess(r);
            if (ran.exitedCleanly() && fs::exists(handouts + "/" + plot) && fs::exists(handouts + "/" + replay)) {
                ++runs;
                after = "<section id=\"reference-run\">\n<h2>The reference solution's run</h2>\n<p>What <code>" + a.program +
                        "</code> draws with <code>--plot</code> on the reference solution, with its default settings:</p>\n" +
                        writers::figureHtml("reference-plot", plot, readFile(handouts + "/" + plot),
                                            "the reference run against the exact solution") +
                        "<p><a href=\"" + replay + "\">Replay the run in 3-D</a> "
                        "(<code>--replay</code>: a page of its own, which also opens offline).</p>\n</section>\n";
            } else {
                std::error_code ignored;
                fs::remove(handouts + "/" + plot, ignored);
                fs::remove(handouts + "/" + replay, ignored);
                // A program that does not draw refuses the options (a usage error, 2): its page is the handout
                // alone. Anything else is a run that should have drawn, and is said.
                if (!(ran.started && ran.signal == 0 && ran.exitCode == 2)) {
                    std::string said = ran.output.substr(0, ran.output.find_last_not_of('\n') + 1);
                    said = said.substr(said.find_last_of('\n') + 1);  // its last line: the error
                    summary.made.push_back("no reference run in handouts/" + a.id + ".html: " + a.program + " " +
                                           (ran.started ? "failed: " + printable(said) : ran.error));
                }
            }
        }
        std::string title = a.title.empty() ? a.id : a.title;
        // Read as CommonMark, as the handouts are written (and as a forge shows them): a fence's info string may
        // carry words after the language ("console solution"), a heading needs no blank line before it, and no
        // "smart" typography turns an option's "--" into a dash.
        // The handout's plots that carry their points (figures drawn by simlab) get their text alternative from
        // the shared figure (figureHtml), in a copy of the handout beside it (its images' paths hold there).
        const std::string source = "." + a.id + "-page.md";
        writeFileAtomically(handouts + "/" + source, withPlotFigures(readFile(markdown), handouts));
        std::vector<std::string> argv = {pandoc, "--from", "commonmark_x-smart", source, "--standalone",
                                         "--self-contained", "--mathml", "--include-in-header=" + style,
                                         "--lua-filter=" + filter, "--metadata", "lang=en",
                                         "--metadata", "pagetitle=" + title, "--output", a.id + ".html"};
        const std::string afterFile = handouts + "/." + a.id + "-after.html";
        if (!after.empty()) {
            writeFileAtomically(afterFile, after);
            argv.push_back("--include-after-body=." + a.id + "-after.html");
        }
        isolation::runTool(argv, handouts);
        std::error_code ignored;
        fs::remove(afterFile, ignored);
        fs::remove(handouts + "/" + source, ignored);
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

// A package's folder: new, or empty.
void requireNewFolder(const std::string& outDir) {
    if (fs::exists(outDir) && !fs::is_empty(outDir)) {
        throw UsageError("'" + outDir + "' exists and is not empty; name a new folder");
    }
}

// A platform's grader runs the hidden tests too.
void requireHiddenTests(const Assignment& assignment) {
    if (!assignment.hiddenTestsBuilt) {
        throw UsageError("the autograder needs the hidden tests, which this copy of simlab does not have");
    }
}

// The file `path` with its line `line` left out (a .gitignore's rule).
void dropLine(const std::string& path, const std::string& line) {
    std::istringstream in(readFile(path));
    std::string kept, each;
    while (std::getline(in, each)) {
        if (each != line) kept += each + "\n";
    }
    writeFileAtomically(path, kept);
}

// A UUID of the form PrairieLearn's info.json takes (version 4's layout), the same for the same `name`: a
// question packaged again keeps its identity, and its statistics, in PrairieLearn.
std::string stableUuid(const std::string& name) {
    std::string h = Hash().add("simlab PrairieLearn question").add(name).hex().substr(0, 32);
    h[12] = '4';
    h[16] = "89ab"[std::stoi(h.substr(16, 1), nullptr, 16) & 3];
    return h.substr(0, 8) + "-" + h.substr(8, 4) + "-" + h.substr(12, 4) + "-" + h.substr(16, 4) + "-" + h.substr(20);
}

}  // namespace

std::vector<std::string> projectFiles(const std::string& sourceDir) {
    std::vector<std::string> files;
    if (fs::exists(fs::path(sourceDir) / ".git") && fs::exists("/usr/bin/git")) {
        // What the repository tracks, nothing else: no build log, editor file or other untracked file is handed out.
        std::string tracked;
        try {
            tracked = isolation::runTool({"/usr/bin/git", "-C", sourceDir, "ls-files", "--cached"}, sourceDir);
        } catch (const std::runtime_error& e) {
            // git's own message is several lines; the user gets one.
            const std::string said = e.what();
            if (said.find("dubious ownership") != std::string::npos) {
                throw UsageError("git will not read " + printable(sourceDir) +
                                 ": it belongs to another user (git's \"dubious ownership\"); run simlab as its owner, "
                                 "or trust it with git config --global --add safe.directory " +
                                 printable(sourceDir));
            }
            const std::size_t fatal = said.find("fatal: ");
            std::string line = said.substr(fatal == std::string::npos ? 0 : fatal);
            line = line.substr(0, line.find('\n'));
            throw UsageError("git cannot list the files of " + printable(sourceDir) + ": " + printable(line));
        }
        std::istringstream list(tracked);
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

bool isOwnLab(const Manifest& manifest, const Assignment& assignment) {
    return std::none_of(manifest.assignments.begin(), manifest.assignments.end(),
                        [&](const Assignment& a) { return a.dir == assignment.dir; });
}

std::string labPlace(const Assignment& assignment) { return "labs/" + fs::path(assignment.dir).filename().string(); }

namespace {

// A lab of one's own in a package, as labs/<its folder's name>: its folder but its corpus (the solution's edits),
// its solution's folder, the hidden tests unless `withHidden`, and anything hidden or built in it.
void addLab(const Assignment& lab, const std::string& dir, bool withHidden, PackageSummary& summary) {
    const fs::path from(lab.dir), to = fs::path(dir) / labPlace(lab);
    const std::string solution = lab.solution.empty() ? "" : fs::path(lab.solution).parent_path().string();
    int left = 0;
    for (auto it = fs::recursive_directory_iterator(from); it != fs::recursive_directory_iterator(); ++it) {
        const fs::path& p = it->path();
        const std::string name = p.filename().string();
        const bool hidden = std::find(lab.hiddenTests.begin(), lab.hiddenTests.end(), p.string()) != lab.hiddenTests.end();
        if (it->is_directory() && (p == from / "corpus" || p.string() == solution || name.front() == '.' ||
                                   fs::exists(p / "CMakeCache.txt"))) {
            it.disable_recursion_pending();
            ++left;
        } else if (it->is_regular_file() && (name.front() == '.' || (hidden && !withHidden))) {
            ++left;
        } else if (it->is_regular_file()) {
            const fs::path target = to / p.lexically_relative(from);
            fs::create_directories(target.parent_path());
            fs::copy_file(p, target, fs::copy_options::overwrite_existing);
            ++summary.files;
        }
    }
    summary.made.push_back(labPlace(lab) + ": the lab " + lab.id + " without its corpus and solution" +
                           (withHidden ? "" : " and hidden tests") + " (" + std::to_string(left) + " left out)");
}

}  // namespace

PackageSummary writeStudentLab(const Assignment& lab, const std::string& dir) {
    PackageSummary summary;
    addLab(lab, dir, false, summary);
    return summary;
}

PackageSummary writeStudentBundle(const Manifest& manifest, const std::string& outDir, const Assignment* lab) {
    requireNewFolder(outDir);
    std::set<std::string> hidden;
    for (const Assignment& a : manifest.assignments) {
        for (const std::string& h : a.hiddenTests) hidden.insert(relativeTo(h, manifest.sourceDir));
    }
    std::vector<Rule> rules = instructorOnly(manifest);
    rules.push_back({"hidden tests", [hidden](const std::string& f) { return hidden.count(f) > 0; }});
    rules.push_back({"README.md: replaced by handouts/README-student.md",
                     [](const std::string& f) { return f == "README.md"; }});
    fs::create_directories(outDir);
    PackageSummary summary = copyFiles(manifest, rules, outDir);
    fs::copy_file(manifest.sourceDir + "/handouts/README-student.md", outDir + "/README.md");
    ++summary.files;
    addCatch2(manifest, outDir, summary);
    addHandoutPages(manifest, outDir, summary);
    if (lab) addLab(*lab, outDir, false, summary);
    return summary;
}

PackageSummary writeGradescopeZip(const Manifest& manifest, const Assignment& assignment, const std::string& zip) {
    if (!fs::exists("/usr/bin/zip")) throw UsageError("zip is not installed (apt-get install zip)");
    requireHiddenTests(assignment);
    const fs::path target = fs::absolute(zip);
    if (!fs::is_directory(target.parent_path())) {
        throw UsageError("cannot write '" + zip + "': no directory " + target.parent_path().string());
    }
    TempDir staging("simlab-gradescope-");
    // simlab and this assignment alone: the course's other labs (their hidden tests and trade files) are neither
    // carried nor built, and a lab of one's own carries none of the course's. It is built against simlab once
    // simlab is, its hidden tests then closed as the course's are.
    const bool own = isOwnLab(manifest, assignment);
    std::vector<Rule> rules = instructorOnly(manifest);
    std::vector<std::string> others;
    std::string left;
    for (const Assignment& a : manifest.assignments) {
        if (!own && a.id == assignment.id) continue;
        const std::string dir = relativeTo(a.dir, manifest.sourceDir) + "/";
        const std::string starter = relativeTo(fs::path(a.starter).parent_path().string(), manifest.sourceDir) + "/";
        others.push_back(dir);
        if (starter.rfind("starter/", 0) == 0) others.push_back(starter);
        left += (left.empty() ? "" : ", ") + a.id;
    }
    if (!others.empty()) {
        rules.push_back({std::string(own ? "the course's labs" : "the course's other labs") + " (" + left + ")",
                         [others](const std::string& f) {
                             return std::any_of(others.begin(), others.end(),
                                                [&](const std::string& o) { return startsWith(f, o); });
                         }});
    }
    PackageSummary summary = copyFiles(manifest, rules, staging.path());
    // The two scripts Gradescope runs, from the templates simlab holds (grader/course/scripts/).
    std::string targets = "simlab " + assignment.id + "_grader", lab;
    if (own) {
        addLab(assignment, staging.path(), true, summary);
        targets = "simlab_kit";
        lab = labPlace(assignment);
    }
    writeFileAtomically(staging.path() + "/setup.sh",
                        filledTemplate(kGradescopeSetup, {{"TARGETS", shellWord(targets)}, {"LAB", shellWord(lab)}}));
    writeFileAtomically(staging.path() + "/run_autograder",
                        filledTemplate(kGradescopeRun, {{"ASSIGNMENT_NAME", assignment.id},
                                                        {"ASSIGNMENT", shellWord(own ? lab : assignment.id)}}));
    addCatch2(manifest, staging.path(), summary);
    makeExecutable(staging.path() + "/setup.sh");
    makeExecutable(staging.path() + "/run_autograder");
    summary.files += 2;

    std::error_code ignored;
    fs::remove(target, ignored);
    isolation::runTool({"/usr/bin/zip", "-q", "-r", "-X", target.string(), "."}, staging.path());
    return summary;
}

const char* const kPrairieLearnOwnLab =
    "a PrairieLearn question is made for the course's labs; a lab of one's own goes to Gradescope (package "
    "gradescope), GitHub Classroom (package github-classroom) or students (package student) for now";

PackageSummary writePrairieLearnQuestion(const Manifest& manifest, const Assignment& assignment,
                                         const std::string& outDir, const PrairieLearnOptions& options) {
    if (isOwnLab(manifest, assignment)) throw UsageError(kPrairieLearnOwnLab);
    requireHiddenTests(assignment);
    requireNewFolder(outDir);
    if (options.timeout < 1 || options.timeout > 600) {
        throw UsageError("--timeout must be 1 to 600 seconds (PrairieLearn's limit)");
    }
    const bool imageName = !options.image.empty() && std::all_of(options.image.begin(), options.image.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || std::string("._-/:@").find(c) != std::string::npos;
    });
    if (!imageName) throw UsageError("'" + options.image + "' is not a Docker image name (such as course/simlab:2025)");
    fs::create_directories(outDir + "/tests");
    // The grading image's build context: the project as students may have it - no hidden test, no solution but the
    // worked example - and its Dockerfile. PrairieLearn pulls images from a public registry: anyone may pull it.
    std::set<std::string> hidden;
    for (const Assignment& a : manifest.assignments) {
        for (const std::string& h : a.hiddenTests) hidden.insert(relativeTo(h, manifest.sourceDir));
    }
    std::vector<Rule> rules = instructorOnly(manifest);
    rules.push_back({"hidden tests: in the question's tests/hidden/, which PrairieLearn keeps from students",
                     [hidden](const std::string& f) { return hidden.count(f) > 0; }});
    PackageSummary summary = copyFiles(manifest, rules, outDir + "/image/simlab");
    addCatch2(manifest, outDir + "/image/simlab", summary);
    writeFileAtomically(outDir + "/image/Dockerfile",
        "# The grading image of the simlab " + assignment.id + " question: Ubuntu 24.04 with simlab built in\n"
        "# /simlab (scripts/setup installs the packages and builds; simlab needs CMake 3.25 and\n"
        "# libtomlplusplus-dev). It holds no hidden test: those are in ../tests/, which PrairieLearn keeps from\n"
        "# students. Build it here and push it where PrairieLearn pulls images from, under the name that\n"
        "# ../info.json gives as externalGradingOptions.image; then, once, make the judge of the hidden tests with it:\n"
        "#     docker build -t " + options.image + " . && docker push " + options.image + "\n"
        "#     docker run --rm -v \"$PWD/../tests:/grade/tests\" " + options.image +
            " /simlab/scripts/prairielearn-judge " + assignment.id + " /grade/tests\n"
        "FROM ubuntu:24.04\n"
        "COPY simlab /simlab\n"
        "RUN SIMLAB_CMAKE_ARGS=-DBUILD_TESTING=OFF SIMLAB_TARGETS=\"simlab " + assignment.id +
            "_grader\" /simlab/scripts/setup && \\\n"
        "    rm -rf /var/lib/apt/lists/*\n");

    // The hidden tests, for the judge the instructor makes once in the image (scripts/prairielearn-judge), which
    // PrairieLearn copies to /grade/tests with the entry point at grading time.
    for (const std::string& h : assignment.hiddenTests) {
        std::error_code missing;
        if (!fs::exists(h, missing)) continue;
        const std::string to = outDir + "/tests/hidden/" + relativeTo(h, manifest.sourceDir);
        fs::create_directories(fs::path(to).parent_path());
        fs::copy_file(h, to);
        ++summary.files;
    }

    // The entry point: PrairieLearn copies the question's tests/ to /grade/tests and runs it there.
    writeFileAtomically(outDir + "/tests/run_autograder",
                        filledTemplate(kPrairieLearnRun,
                                       {{"ASSIGNMENT_NAME", assignment.id}, {"ASSIGNMENT", shellWord(assignment.id)}}));
    makeExecutable(outDir + "/tests/run_autograder");

    const nlohmann::json info = {
        {"uuid", stableUuid(assignment.id)},
        {"title", assignment.title.empty() ? assignment.id : assignment.title},
        {"topic", "simlab"},
        {"tags", {"simlab", assignment.id}},
        {"type", "v3"},
        {"singleVariant", true},
        {"gradingMethod", "External"},
        {"externalGradingOptions",
         {{"enabled", true},
          {"image", options.image},
          {"entrypoint", "/grade/tests/run_autograder"},
          {"timeout", options.timeout}}}};
    writeFileAtomically(outDir + "/info.json", info.dump(4) + "\n");

    const std::string file = writers::htmlText(assignment.source);
    const std::string input =
        options.upload ? "  <pl-file-upload file-names=\"" + file + "\"></pl-file-upload>\n"
                       : "  <pl-file-editor file-name=\"" + file + "\" ace-mode=\"ace/mode/c_cpp\" source-file-name=\"" +
                             file + "\"></pl-file-editor>\n";
    writeFileAtomically(outDir + "/question.html",
        "<pl-question-panel>\n"
        "  <p>" + writers::htmlText(assignment.title) + ": complete <code>" + file + "</code> as the handout says, "
        "then submit it. The autograder builds it against the course's grader and runs every test; each test's "
        "points and outcome, and the plots of your run, show under your submission.</p>\n" + input +
        "</pl-question-panel>\n\n"
        "<pl-submission-panel>\n"
        "  <pl-external-grader-results></pl-external-grader-results>\n"
        "  <pl-file-preview></pl-file-preview>\n"
        "</pl-submission-panel>\n");
    if (!options.upload) {
        fs::copy_file(assignment.starter, outDir + "/" + assignment.source);
        ++summary.files;
    }
    summary.files += 4;
    summary.made.push_back("info.json (image " + options.image + ", timeout " + std::to_string(options.timeout) +
                           " s), question.html, tests/run_autograder, tests/hidden/ (its judge, tests/judge, made "
                           "once in the image: image/Dockerfile says how), image/Dockerfile");
    return summary;
}

PackageSummary writeClassroomTemplate(const Manifest& manifest, const Assignment& assignment, const std::string& outDir) {
    const bool own = isOwnLab(manifest, assignment);
    PackageSummary summary = writeStudentBundle(manifest, outDir, own ? &assignment : nullptr);
    // The template is a repository: the carried Catch2 header must be committed with it (GitHub's Ubuntu 24.04
    // ships Catch2 3).
    if (fs::exists(outDir + "/.gitignore")) dropLine(outDir + "/.gitignore", "/third_party/");

    const std::string file = own ? labPlace(assignment) + "/" + relativeTo(assignment.starter, assignment.dir)
                                 : relativeTo(assignment.starter, manifest.sourceDir);
    const std::string check =
        "build/bin/simlab check " + (own ? labPlace(assignment) : assignment.id) + " " + file;
    const std::string targets = own ? "simlab_kit" : "simlab " + assignment.id + "_grader";
    double visible = 0;
    for (const RubricTest& t : loadRubric(assignment.rubric).tests) {
        if (t.visible()) visible += t.points;
    }
    // If simlab could not be built or run, the reporter still gets its two results: nothing earned, every visible
    // point missed, as errors.
    const std::string failedTest = "{\"name\": \"simlab check\", \"status\": \"error\", \"score\": 0, "
                                   "\"message\": \"simlab could not build or run: see the steps above\", \"line_no\": 0}";
    const std::string failed = "'{\"version\": 1, \"status\": \"error\", \"max_score\": 0, \"tests\": [" + failedTest +
                               "]}' '{\"version\": 1, \"status\": \"error\", \"max_score\": " + points(visible) +
                               ", \"tests\": [" + failedTest + "]}'";
    fs::create_directories(outDir + "/.github/workflows");
    writeFileAtomically(outDir + "/.github/workflows/classroom.yml",
        "# GitHub Classroom's autograding of the " + assignment.id + " lab: on every push, build simlab, run the\n"
        "# visible tests on " + file + " and report the points to Classroom (the name of the workflow\n"
        "# and of its job are the ones Classroom looks for). The points are a self-check: this runs in the\n"
        "# student's repository, which the student can change. Grades come from the instructor's simlab grade.\n"
        "name: Autograding Tests\n"
        "on:\n"
        "  - push\n"
        "  - workflow_dispatch\n"
        "permissions:\n"
        "  checks: write\n"
        "  actions: read\n"
        "  contents: read\n"
        "jobs:\n"
        "  run-autograding-tests:\n"
        "    runs-on: ubuntu-24.04\n"
        "    if: github.actor != 'github-classroom[bot]'\n"
        "    steps:\n"
        "      - name: Checkout code\n"
        "        uses: actions/checkout@v4\n"
        "      # Only what a check of this lab needs: its packages (scripts/install-deps --lean: no pages, schematics or\n"
        "      # test tools), and simlab with this lab's grader, compiled through ccache, whose cache Actions keeps\n"
        "      # between pushes (the student's file alone compiles anew).\n"
        "      - name: Install the packages a check needs\n"
        "        run: |\n"
        "          scripts/install-deps --lean\n"
        "          sudo apt-get install -y -qq --no-install-recommends ccache\n"
        "      - name: Restore the compiler's cache\n"
        "        uses: actions/cache@v4\n"
        "        with:\n"
        "          path: build/ccache\n"
        "          key: simlab-ccache-${{ runner.os }}-${{ github.sha }}\n"
        "          restore-keys: simlab-ccache-${{ runner.os }}-\n"
        "      - name: Build simlab and the lab's grader\n"
        "        run: SIMLAB_SKIP_APT=1 SIMLAB_CMAKE_ARGS=-DBUILD_TESTING=OFF SIMLAB_TARGETS=\"" + targets +
        "\" scripts/setup\n"
        "      - name: Run the visible tests\n"
        "        id: simlab\n"
        "        if: always()\n"
        "        run: |\n"
        "          if ! " + check + " --format classroom >\"$RUNNER_TEMP/simlab.json\"; then\n"
        "            printf '%s\\n' " + failed + " >\"$RUNNER_TEMP/simlab.json\"\n"
        "          fi\n"
        "          # Two runners, the points earned and the points missed, so that the reporter's table and the\n"
        "          # points Classroom records agree under partial credit.\n"
        "          echo \"earned=$(sed -n 1p \"$RUNNER_TEMP/simlab.json\" | base64 -w 0)\" >>\"$GITHUB_OUTPUT\"\n"
        "          echo \"missed=$(sed -n 2p \"$RUNNER_TEMP/simlab.json\" | base64 -w 0)\" >>\"$GITHUB_OUTPUT\"\n"
        "      - name: Autograding Reporter\n"
        "        if: always()\n"
        "        uses: classroom-resources/autograding-grading-reporter@v1\n"
        "        env:\n"
        "          EARNED_RESULTS: \"${{ steps.simlab.outputs.earned }}\"\n"
        "          MISSED_RESULTS: \"${{ steps.simlab.outputs.missed }}\"\n"
        "        with:\n"
        "          runners: earned,missed\n");

    writeFileAtomically(outDir + "/README.md", readFile(outDir + "/README.md") +
        "\n## Your repository checks itself\n\n"
        "Every push runs `.github/workflows/classroom.yml` (the Actions tab shows it): it builds simlab, runs `" +
        check + "` on the visible tests, and GitHub Classroom shows the points, the same points as that command "
        "gives on your machine. They are a self-check, not your grade: your instructor grades the last commit "
        "before the deadline with every test, the hidden ones too.\n");
    summary.files += 1;
    summary.made.push_back(".github/workflows/classroom.yml: on every push, the visible tests of " + assignment.id +
                           " (" + points(visible) + " points), reported to GitHub Classroom");
    return summary;
}

PackageSummary writeInstalledTree(const Manifest& manifest, const std::string& root) {
    if (manifest.installed) throw UsageError("this simlab is installed already: install from a build tree");
    std::ifstream in(manifest.path);
    nlohmann::json j = nlohmann::json::parse(in);
    PackageSummary summary;
    std::set<std::string> copied;
    const auto copy = [&](const fs::path& from, const fs::path& to) {
        if (!copied.insert(from.string()).second) return;
        std::error_code error;
        fs::create_directories(to.parent_path());
        if (fs::is_directory(from, error)) {
            fs::copy(from, to, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
            for (auto it = fs::recursive_directory_iterator(to); it != fs::recursive_directory_iterator(); ++it) {
                if (it->is_regular_file()) ++summary.files;
            }
        } else if (fs::is_regular_file(from, error)) {
            fs::copy_file(from, to, fs::copy_options::overwrite_existing);
            ++summary.files;
        }
    };
    const std::string pchDir = manifest.buildDir + "/pch";
    // The build folder first: it lies inside the source folder.
    const std::vector<std::pair<std::string, std::string>> places = {{manifest.buildDir, "/lib/simlab/build"},
                                                                     {manifest.sourceDir, "/share/simlab/source"}};
    // Where in `text` a path inside one of the places begins (npos if nowhere), and which place it is in.
    struct Found {
        std::size_t at = std::string::npos;
        std::string from, to;
    };
    const auto find = [&](const std::string& text) {
        for (const auto& [from, to] : places) {
            const std::size_t at = text.find(from);
            if (at == std::string::npos) continue;
            const std::size_t end = at + from.size();
            if (end < text.size() && text[end] != '/') continue;
            return Found{at, from, to};
        }
        return Found{};
    };
    std::function<void(nlohmann::json&)> relocate = [&](nlohmann::json& value) {
        if (value.is_structured()) {
            for (nlohmann::json& element : value) relocate(element);
            return;
        }
        if (!value.is_string()) return;
        std::string text = value.get<std::string>();
        if (const auto [at, from, to] = find(text); at != std::string::npos) {
            const std::size_t end = at + from.size();
            const std::string path = text.substr(at), rest = text.substr(end);
            if (path.rfind(pchDir + "/", 0) == 0) {
                // The headers a precompiled header is made from; not the made one, which names them by path.
                for (const auto& entry : fs::directory_iterator(pchDir)) {
                    if (entry.path().extension() == ".h") copy(entry.path(), root + to + "/pch/" + entry.path().filename().string());
                }
            } else if (!rest.empty() && from == manifest.sourceDir && fs::is_regular_file(path)) {
                // A source file comes with its folder (a starter's or solution's other files, a rubric's tests).
                copy(fs::path(path).parent_path(), root + to + fs::path(rest).parent_path().string());
            } else if (!rest.empty()) {
                copy(path, root + to + rest);
            }
            text = text.substr(0, at) + "@prefix@" + to + rest;
        }
        value = text;
    };
    relocate(j);
    // The project's other sources too, so that an installed simlab makes packages (they build simlab where they
    // are unpacked): all but the corpus and its tests, CI and benchmarks. What the manifest names is copied already.
    for (const std::string& file : projectFiles(manifest.sourceDir)) {
        if (startsWith(file, "tests/") || startsWith(file, ".ci/") || startsWith(file, "bench/")) continue;
        const std::string from = manifest.sourceDir + "/" + file;
        if (!copied.count(from) && !copied.count(fs::path(from).parent_path().string())) {
            copy(from, root + "/share/simlab/source/" + file);
        }
        // An example lab's solution, hidden tests and corpus are as secret as the course's (the template's are not:
        // `simlab assignment new` copies them for every user).
        const std::string name = fs::path(file).filename().string();
        if (startsWith(file, "examples/") && !startsWith(file, "examples/template/") &&
            (file.find("/solution/") != std::string::npos || file.find("/corpus/") != std::string::npos ||
             startsWith(name, "hidden") || startsWith(name, "trade-hidden"))) {
            closeToOthers(root + "/share/simlab/source/" + file);
        }
    }
    // What no test's code may read, readable by the installing user alone: in a container without bubblewrap, a
    // prefix in /usr/local lies among the system's files, which every sandboxed process may read, and there the
    // files' modes are what keeps the throwaway users out (simlab check and grade refuse to run otherwise).
    const auto installedPath = [&](const std::string& path) -> std::string {
        const auto [at, from, to] = find(path);
        return at == 0 ? root + to + path.substr(from.size()) : "";
    };
    std::set<std::string> secrets;
    for (const Assignment& a : manifest.assignments) {
        for (const std::string& secret : secretPaths(manifest, a)) secrets.insert(secret);
    }
    for (const std::string& secret : secrets) {
        const std::string path = installedPath(secret);
        if (!path.empty()) closeToOthers(path);
    }
    j["installed"] = true;
    fs::create_directories(root + "/lib/simlab");
    writeFileAtomically(root + "/lib/simlab/simlab-build.json", j.dump(2) + "\n");
    summary.made.push_back("lib/simlab/simlab-build.json: the build manifest, its paths written from the prefix");
    summary.left.push_back("the precompiled headers: made where the prefix is, when simlab first needs them");
    return summary;
}

}  // namespace simlab::engine
