// simlab export canvas: a graded class's scores as a CSV that Canvas's gradebook import takes, for one assignment.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/build/manifest.h"
#include "simlab/course/manual.h"
#include "simlab/grading/report.h"
#include "simlab/writers/roster.h"
#include "simlab/common/text.h"
#include "simlab/writers/writers.h"
#include "simlab/rubric/rubric.h"

namespace fs = std::filesystem;

namespace simlab::cli {

namespace {

struct CanvasOptions {
    std::string assignment;
    std::string grades;
    std::string roster;
    std::string output;
    std::string name;
    std::string canvasId;
    std::string rubric;
};

// "a, b and 3 more": a list a person reads in one line.
std::string listed(const std::vector<std::string>& ids) {
    std::string out;
    const std::size_t shown = std::min<std::size_t>(ids.size(), 10);
    for (std::size_t i = 0; i < shown; ++i) out += (i ? ", " : "") + engine::printable(ids[i]);
    if (ids.size() > shown) out += " and " + std::to_string(ids.size() - shown) + " more";
    return out;
}

void runCanvas(const CanvasOptions& o) {
    using namespace simlab::engine;
    const Manifest manifest = loadManifest();
    const Assignment& assignment = manifest.find(o.assignment);
    if (!o.canvasId.empty() && !std::all_of(o.canvasId.begin(), o.canvasId.end(), [](unsigned char c) { return std::isdigit(c); })) {
        throw UsageError("--canvas-id '" + o.canvasId + "' is not a number (Canvas's assignment id, from its address)");
    }
    const std::string grades = o.grades.empty() ? "grades/" + assignment.id : o.grades;
    if (!fs::is_directory(grades + "/students")) {
        throw UsageError("no graded class in " + grades + " (no students/ folder): run simlab grade " + assignment.id +
                         " first");
    }
    if (!fs::is_regular_file(o.roster)) throw UsageError("no roster file " + o.roster);
    const std::vector<RosterEntry> roster = readRoster(readFile(o.roster), o.roster);

    // The class as simlab keeps it: each student's record.json (gradebook.csv is made from them).
    std::vector<StudentRecord> records;
    std::vector<std::string> unreadable;
    for (const FolderEntry& e : listFolder(grades + "/students", /*followFolder=*/true)) {
        if (e.type != EntryType::Directory) continue;
        const std::string path = grades + "/students/" + e.name + "/record.json";
        std::optional<StudentRecord> record;
        if (fs::is_regular_file(path)) record = readRecordJson(readFile(path));
        if (!record) {
            unreadable.push_back(e.name);
            continue;
        }
        record->id = e.name;
        records.push_back(*record);
    }
    // What a person graded counts too (manual.csv, beside the gradebook).
    // The rubric the class was graded with: simlab grade keeps a copy beside the grades.
    const std::string kept = grades + "/rubric.toml";
    const Rubric rubric = loadRubric(!o.rubric.empty() ? o.rubric : fs::exists(kept) ? kept : assignment.rubric);
    const ManualSheet sheet = readManualSheet(grades, rubric);
    for (StudentRecord& r : records) applyManual(r, sheet, rubric);
    const double possible = rubric.totalPoints() + rubric.manualPoints();
    std::string column = o.name.empty() ? (assignment.title.empty() ? assignment.id : assignment.title) : o.name;
    if (!o.canvasId.empty()) column += " (" + o.canvasId + ")";

    const CanvasExport made = canvasCsv(column, possible, roster, records);
    writeFileAtomically(o.output, made.csv);
    std::cout << "Wrote " << printable(o.output) << ": " << printable(column) << ", " << made.scored << " of "
              << roster.size() << " students on the roster scored (out of " << points(possible) << ").\n";
    if (!made.unmatched.empty()) {
        std::cerr << "simlab: warning: " << made.unmatched.size()
                  << " scored on a row with no ID, SIS User ID or SIS Login ID, which Canvas cannot match: add one to "
                  << printable(o.roster) << ": " << listed(made.unmatched) << "\n";
    }
    if (!made.noId.empty()) {
        std::cerr << "simlab: warning: " << made.noId.size()
                  << " on the roster without a simlab id (blank: Canvas keeps what it has): " << listed(made.noId) << "\n";
    }
    if (!made.missingFile.empty()) {
        std::cerr << "simlab: warning: " << made.missingFile.size()
                  << " handed in no file to grade (blank, not 0: give the grade in Canvas): " << listed(made.missingFile)
                  << "\n";
    }
    if (!made.manualPending.empty()) {
        std::cerr << "simlab: warning: " << made.manualPending.size() << " with items graded by hand still pending in "
                  << grades << "/manual.csv (blank until they have their points): " << listed(made.manualPending) << "\n";
    }
    if (!made.notGraded.empty()) {
        std::cerr << "simlab: warning: " << made.notGraded.size()
                  << " on the roster without a grade (blank: Canvas keeps what it has): " << listed(made.notGraded)
                  << "\n";
    }
    if (!made.notOnRoster.empty()) {
        std::cerr << "simlab: warning: " << made.notOnRoster.size()
                  << " graded but not on the roster (left out of the file): " << listed(made.notOnRoster) << "\n";
    }
    if (!unreadable.empty()) {
        std::cerr << "simlab: warning: " << unreadable.size() << " with no readable record.json (run simlab grade "
                  << assignment.id << " again): " << listed(unreadable) << "\n";
    }
}

}  // namespace

void addExport(CLI::App& app) {
    CLI::App* exporter = app.add_subcommand("export", "Write a graded class's scores for another system's gradebook.");
    exporter->require_subcommand(1);

    auto options = std::make_shared<CanvasOptions>();
    CLI::App* canvas = exporter->add_subcommand(
        "canvas", "Write a CSV for Canvas's gradebook import (Grades, Import): one row per student of the roster, "
                  "one column for the assignment. The roster is a CSV whose header names Canvas's columns Student, "
                  "ID, SIS User ID, SIS Login ID, Section (Canvas's own gradebook export has them) and 'simlab id', "
                  "the student's folder name (without it, the SIS Login ID is the folder name). Students on the "
                  "roster without a grade, and graded students not on the roster, are listed.");
    canvas->add_option("assignment", options->assignment, "which assignment")->required();
    canvas->add_option("--grades", options->grades, "the graded class, simlab grade's --out (default: grades/<assignment>)");
    canvas->add_option("--roster", options->roster, "the roster CSV")->required();
    canvas->add_option("-o,--output", options->output, "the CSV file to write")->required();
    canvas->add_option("--name", options->name, "the assignment's name in Canvas (default: the assignment's title)");
    canvas->add_option("--canvas-id", options->canvasId,
                       "the assignment's id in Canvas (the number in its address), so that Canvas matches the column "
                       "to it whatever its name");
    canvas->add_option("--rubric", options->rubric,
                       "the rubric whose points count (default: the one the class was graded with, kept in the "
                       "grades folder)")
        ->check(CLI::ExistingFile);
    canvas->callback([options] { runCanvas(*options); });
}

}  // namespace simlab::cli
