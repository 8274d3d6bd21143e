// simlab similarity: the pairs of a class's submissions that share most of their code, on a page side by side.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

#include "commands.h"
#include "simlab/course/batch.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/build/manifest.h"
#include "simlab/course/similarity.h"
#include "simlab/common/text.h"
#include "simlab/rubric/rubric.h"

namespace fs = std::filesystem;

namespace simlab::cli {

namespace {

struct SimilarityOptions {
    std::string assignment;
    std::string submissions;
    std::string out;
    double floor = engine::kSimilarityFloor;
};

void runSimilarity(const SimilarityOptions& o) {
    using namespace simlab::engine;
    const Manifest manifest = loadManifest();
    const Assignment& assignment = manifest.find(o.assignment);
    const std::string root = o.submissions.empty() ? manifest.sampleClass + "/" + assignment.id : o.submissions;
    if (!fs::is_directory(root)) throw UsageError("no submissions folder " + root);
    const Rubric rubric = loadRubric(assignment.rubric);
    // Each student's file, found and read as grading finds and reads it.
    std::map<std::string, std::string> files;
    std::vector<std::string> without;
    for (const FolderEntry& e : listFolder(root, /*followFolder=*/true)) {
        if (e.type != EntryType::Directory || e.name[0] == '.') continue;
        const Gathered g = gatherSubmission(root + "/" + e.name, rubric, rubric.limits, false, false);
        if (g.files) files[e.name] = g.files->text;
        else without.push_back(printable(e.name) + " (" + statusName(g.status) + ")");
    }
    if (!without.empty()) {
        std::string list;
        for (const std::string& w : without) list += (list.empty() ? "" : ", ") + w;
        std::cerr << "simlab: warning: " << without.size() << " without a file to compare: " << list << "\n";
    }
    if (files.size() < 2) {
        throw UsageError("similarity needs at least two files to compare; " + printable(root) + " has " +
                         std::to_string(files.size()));
    }
    const std::string starter = fs::exists(assignment.starter) ? readFile(assignment.starter) : "";
    const SimilarityReport report = compareSubmissions(files, starter, o.floor);
    const std::string out = o.out.empty() ? "grades/" + assignment.id : o.out;
    fs::create_directories(out);
    writeOutputAtomically(out + "/similarity.html", similarityHtml(assignment.title, report, files));
    std::printf(
        "Compared %zu files in pairs, the starter's code removed by its tokens: the median pair shares %.0f %% (spread "
        "%.0f %%); flagged at %.0f %% or more (the floor) or at %.0f %% or more (the class):\n",
        report.ids.size(), report.median, report.spread, report.floor, report.threshold);
    for (std::size_t i = 0; i < report.flagged.size(); ++i) {
        const SimilarPair& p = report.flagged[i];
        std::printf("  %5.0f %%  %-12s  %s  %s  (similarity.html#pair%zu)\n", p.percent, flaggedBy(p).c_str(),
                    printable(p.a).c_str(), printable(p.b).c_str(), i);
    }
    if (report.flagged.empty()) std::printf("  no pair\n");
    std::printf("Wrote %s/similarity.html (each flagged pair side by side, its shared runs marked)\n",
                printable(out).c_str());
}

}  // namespace

void addSimilarity(CLI::App& app) {
    auto options = std::make_shared<SimilarityOptions>();
    CLI::App* similarity = app.add_subcommand(
        "similarity",
        "Find the pairs of a class's submissions that share most of their code: every pair compared by sim_c++ "
        "(Debian's similarity-tester) once the starter's code is removed by its tokens (identifiers compared by "
        "kind, so that renaming hides neither a copy nor the starter); a pair is flagged when one file holds "
        "at least --floor of the other, or at least 50 % and more than the class's median pair by three times the "
        "class's spread. Writes similarity.html with each flagged pair side by side, its shared runs marked. A lead "
        "for a person to read, not a verdict.");
    similarity->add_option("assignment", options->assignment, "which assignment")->required();
    similarity->add_option("submissions", options->submissions,
                           "folder of student folders, as simlab grade reads it (default: the bundled sample class)");
    similarity->add_option("--out,-o", options->out, "where similarity.html goes (default: grades/<assignment>)");
    similarity
        ->add_option("--floor", options->floor,
                     "flag every pair at or above this percent, however alike the class is (default: 90)")
        ->check(CLI::Range(1.0, 100.0));
    similarity->callback([options] { runSimilarity(*options); });
}

}  // namespace simlab::cli
