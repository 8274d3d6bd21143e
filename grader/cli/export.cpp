// simlab export canvas: a graded class's scores as a CSV that Canvas's gradebook import takes, for one assignment.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "commands.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/build/manifest.h"
#include "simlab/course/manual.h"
#include "simlab/course/policy.h"
#include "simlab/grading/report.h"
#include "simlab/isolation/process.h"
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
    std::string comments;
};

// "a, b and 3 more": a list a person reads in one line.
std::string listed(const std::vector<std::string>& ids) {
    std::string out;
    const std::size_t shown = std::min<std::size_t>(ids.size(), 10);
    for (std::size_t i = 0; i < shown; ++i) out += (i ? ", " : "") + engine::printable(ids[i]);
    if (ids.size() > shown) out += " and " + std::to_string(ids.size() - shown) + " more";
    return out;
}

// Canvas's own gradebook export names students by Canvas's ID and the SIS ids, never by simlab's folder: each row
// whose folder is no graded student's is matched through the roster simlab wrote when it took the class in from a
// download (OUT/roster.csv: ID and SIS User ID beside the simlab id). Returns how many rows were matched so.
int matchThroughIntake(std::vector<engine::RosterEntry>& roster, const std::string& intakePath,
                       const std::set<std::string>& graded) {
    using namespace simlab::engine;
    // By the platform's ids alone; one that two students share names neither (StudentIds refuses it, naming both).
    StudentIds byCanvasId, bySis;
    try {
        for (const auto& [folder, id] : rosterColumn(intakePath, "ID")) byCanvasId.add(id, folder);
        for (const auto& [folder, sis] : rosterColumn(intakePath, "SIS User ID")) bySis.add(sis, folder);
    } catch (const UsageError&) {
        return 0;  // the instructor's edit of it, unreadable: the roster given is matched as it is
    }
    int matched = 0;
    for (RosterEntry& e : roster) {
        if (graded.count(e.folder)) continue;
        const std::optional<std::string> id =
            e.canvasId.empty() ? std::nullopt : byCanvasId.find(e.canvasId, printable(intakePath) + ", ID");
        const std::optional<std::string> sis =
            e.sisUserId.empty() ? std::nullopt : bySis.find(e.sisUserId, printable(intakePath) + ", SIS User ID");
        const std::string folder = id ? *id : sis ? *sis : "";
        if (!folder.empty()) {
            e.folder = folder;
            ++matched;
        }
    }
    return matched;
}

// The feedback of each student of the roster, named as Canvas's download named their submission
// ("lovelaceada_101_9001_..."), zipped for Canvas's Re-Upload Submissions, which attaches each file to that
// submission as a comment. Returns the students who got one.
int writeCanvasComments(const std::string& zip, const std::string& grades,
                        const std::vector<engine::RosterEntry>& roster, std::vector<std::string>& without) {
    using namespace simlab::engine;
    if (!fs::exists("/usr/bin/zip")) throw UsageError("zip is not installed (apt-get install zip)");
    std::map<std::string, std::string> canvasFile;  // simlab id -> Canvas's name for the submission
    for (const auto& [id, name] : rosterColumn(grades + "/roster.csv", "Canvas file")) {
        if (!name.empty()) canvasFile.emplace(id, name);
    }
    const TempDir staging("simlab-comments");
    int written = 0;
    std::set<std::string> done;
    for (const RosterEntry& e : roster) {
        const std::string page = grades + "/students/" + e.folder + "/feedback.html";
        const auto name = canvasFile.find(e.folder);
        if (e.folder.empty() || !fs::is_regular_file(page) || name == canvasFile.end()) {
            if (!e.folder.empty()) without.push_back(e.folder);
            continue;
        }
        if (!done.insert(name->second).second) continue;
        writeOutputAtomically(staging.path() + "/" + name->second + "_simlab-feedback.html", readFile(page));
        ++written;
    }
    const fs::path target = fs::absolute(zip);
    fs::remove(target);
    if (written > 0) isolation::runTool({"/usr/bin/zip", "-q", "-r", "-X", target.string(), "."}, staging.path());
    return written;
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
    std::vector<RosterEntry> roster = readRoster(readFile(o.roster), o.roster);

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
    std::set<std::string> graded;
    for (const StudentRecord& r : records) graded.insert(r.id);
    const int throughIntake = matchThroughIntake(roster, grades + "/roster.csv", graded);
    const bool anyMatched =
        std::any_of(roster.begin(), roster.end(), [&](const RosterEntry& e) { return graded.count(e.folder) > 0; });
    if (!anyMatched && !roster.empty() && !records.empty()) {
        throw UsageError("no student of " + printable(o.roster) + " matches one of the " +
                         std::to_string(records.size()) + " graded in " + printable(grades) +
                         " (by its simlab id column, by Canvas's ID or SIS User ID through " + printable(grades) +
                         "/roster.csv, or by SIS Login ID): is it this course's roster?");
    }
    const double possible = rubric.totalPoints() + rubric.manualPoints();
    std::string column = o.name.empty() ? (assignment.title.empty() ? assignment.id : assignment.title) : o.name;
    if (!o.canvasId.empty()) column += " (" + o.canvasId + ")";

    const CanvasExport made = canvasCsv(column, possible, roster, records);
    writeOutputAtomically(o.output, made.csv);
    std::cout << "Wrote " << printable(o.output) << ": " << printable(column) << ", " << made.scored << " of "
              << roster.size() << " students on the roster scored (out of " << points(possible) << ")"
              << (throughIntake > 0 ? ", " + std::to_string(throughIntake) + " matched by Canvas's ID or SIS User ID"
                                    : "")
              << ".\n";
    const int late = static_cast<int>(
        std::count_if(records.begin(), records.end(), [](const StudentRecord& r) { return r.late.percent > 0; }));
    if (late > 0) std::cout << late << " with a late penalty taken from their score (gradebook.csv says how much).\n";
    if (!o.comments.empty()) {
        std::vector<std::string> without;
        const int commented = writeCanvasComments(o.comments, grades, roster, without);
        std::cout
            << "Wrote " << printable(o.comments) << ": the feedback of " << commented
            << " student(s), for Canvas's Re-Upload Submissions (each page becomes a comment on its submission).\n";
        if (!without.empty()) {
            std::cerr << "simlab: warning: " << without.size()
                      << " without a feedback page to upload (no feedback, or not taken in from a Canvas download): "
                      << listed(without) << "\n";
        }
    }
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
        "canvas",
        "Write a CSV for Canvas's gradebook import (Grades, Import): one row per student of the roster, "
        "one column for the assignment. The roster is a CSV whose header names Canvas's columns Student, "
        "ID, SIS User ID, SIS Login ID, Section (Canvas's own gradebook export has them) and 'simlab id', "
        "the student's folder name. Canvas's own gradebook export is such a roster: its ID and SIS User ID are "
        "matched through the roster simlab wrote when it took in a Canvas or Gradescope download "
        "(GRADES/roster.csv), else its SIS Login ID is the folder name. A roster that matches no graded "
        "student is refused. Students on the roster without a grade, and graded students not on the "
        "roster, are listed.");
    canvas->add_option("assignment", options->assignment, "which assignment")->required();
    canvas->add_option("--grades", options->grades, "the graded class, simlab grade's --out (default: grades/<assignment>)");
    canvas->add_option("--roster", options->roster, "the roster CSV")->required();
    canvas->add_option("-o,--output", options->output, "the CSV file to write")->required();
    canvas->add_option("--name", options->name, "the assignment's name in Canvas (default: the assignment's title)");
    canvas->add_option("--canvas-id", options->canvasId,
                       "the assignment's id in Canvas (the number in its address), so that Canvas matches the column "
                       "to it whatever its name");
    canvas->add_option("--comments", options->comments,
                       "also write a zip of each student's feedback page, named as Canvas's download named their "
                       "submission, for Canvas's Re-Upload Submissions (each becomes a comment on the submission)");
    canvas->add_option("--rubric", options->rubric,
                       "the rubric whose points count (default: the one the class was graded with, kept in the "
                       "grades folder)")
        ->check(CLI::ExistingFile);
    canvas->callback([options] { runCanvas(*options); });
}

}  // namespace simlab::cli
