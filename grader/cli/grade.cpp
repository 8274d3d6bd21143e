// simlab grade: grade every submission of a class on every test, in parallel, resumably.
#include <CLI/CLI.hpp>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>

#include "commands.h"
#include "simlab/cli_checks.h"
#include "simlab/course/batch.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/grading/grade.h"
#include "simlab/course/intake.h"
#include "simlab/build/manifest.h"
#include "simlab/course/manual.h"
#include "simlab/isolation/process.h"
#include "simlab/grading/report.h"
#include "simlab/common/text.h"

namespace fs = std::filesystem;

namespace simlab::cli {

namespace {

struct GradeCommandOptions {
    std::string assignment;
    std::string submissions;
    std::string out;
    int jobs = cores();
    std::vector<std::string> only;
    std::string junit;
    double timeout = 0;
    double memory = 0;
    std::string rubric;
    std::string from;
    std::string shard;  // "I/N"
    std::string course;  // course.toml: the late policy
    std::string submittedTimes;  // --submitted: the hand-in times the instructor names
    bool intakeOnly = false;
};

std::string minutesAndSeconds(double seconds) {
    char text[32];
    const long s = std::lround(seconds);
    if (s >= 60) std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
    else std::snprintf(text, sizeof text, "%lds", s);
    return text;
}

std::string studentLine(const engine::StudentRecord& r, bool reused) {
    std::string status = engine::statusName(r.status) + (r.note.empty() ? "" : ": " + r.note);
    if (reused) status += " (unchanged)";
    if (r.pendingPoints() > 0) status += "; " + engine::points(r.pendingPoints()) + " points to grade by hand";
    char score[32];
    std::snprintf(score, sizeof score, "%7s", (engine::points(r.total()) + "/" + engine::points(r.maxTotal())).c_str());
    std::string id = engine::printable(r.id);
    if (id.size() < 24) id.resize(24, ' ');
    return "  " + id + " " + score + "  " + engine::printable(status);
}

// The first Ctrl-C (or SIGTERM) stops launching, ends the running children and lets simlab write what is
// complete; a second one ends simlab at once. Only async-signal-safe calls here.
void onSignal(int) {
    static volatile sig_atomic_t signals = 0;
    if (signals++ > 0) {
        static const char line[] = "\nsimlab: stopped at once\n";
        (void)!::write(STDERR_FILENO, line, sizeof line - 1);
        ::_exit(130);
    }
    static const char line[] = "\nsimlab: stopping: finishing what is complete (press Ctrl-C again to quit at once)\n";
    (void)!::write(STDERR_FILENO, line, sizeof line - 1);
    isolation::interruptChildren();
}

// The folder of submissions: the one named, or the bundled sample class.
std::string submissionsFolder(const GradeCommandOptions& o, const engine::Manifest& manifest,
                              const engine::Assignment& assignment) {
    std::string root = o.submissions.empty() ? manifest.sampleClass + "/" + assignment.id : o.submissions;
    if (!std::filesystem::is_directory(root)) {
        throw engine::UsageError(o.submissions.empty() ? "this copy of simlab has no sample class for " +
                                                             assignment.id + "; name a folder of submissions"
                                                       : "no submissions folder " + root);
    }
    return root;
}

// --shard as (share, shares); (0, 0) without it. A shard leaves the class's files to the whole-class run.
std::pair<int, int> shardOf(const GradeCommandOptions& o) {
    if (o.shard.empty()) return {0, 0};
    const std::pair<int, int> shard = parseShard(o.shard);
    const char* clash = !o.from.empty()    ? "--from"
                        : !o.only.empty()  ? "--only"
                        : !o.junit.empty() ? "--junit"
                                           : nullptr;
    if (clash) {
        throw engine::UsageError(std::string("--shard grades a share of a class folder and leaves the class's files to "
                                             "the whole-class run: give ") +
                                 clash + " to that run instead");
    }
    return shard;
}

// The class folder to grade. A platform's download is taken in as a class folder beside the gradebook, with a roster
// of who is who; a folder that looks like one, or that holds loose files, is refused with the option to use.
std::string classFolder(const GradeCommandOptions& o, const std::string& root, const std::string& out,
                        const Rubric& rubric, std::vector<engine::IntakeStudent>& taken) {
    using namespace simlab::engine;
    if (o.from.empty()) {
        if (const std::string layout = layoutOf(root); layout == "loose files") {
            throw UsageError(printable(root) +
                             " holds files, not a folder per student: put each student's file in a "
                             "folder named after them, or, for a platform's download, add --from gradescope, canvas, "
                             "moodle or classroom");
        } else if (!layout.empty()) {
            throw UsageError(printable(root) + " looks like a " + layout + " download: add --from " + layout);
        }
        return root;
    }
    const std::size_t cap = static_cast<std::size_t>(rubric.limits.submissionKiB) * 1024;
    createOutputFolder(out);
    std::vector<std::string> handedIn = {rubric.submission};
    handedIn.insert(handedIn.end(), rubric.extraFiles.begin(), rubric.extraFiles.end());
    const std::vector<IntakeStudent> students = takeIn(o.from, root, out + "/class", handedIn, cap);
    taken = students;
    // The roster is the instructor's to edit (Canvas ids, sections): one that differs from the download's is kept,
    // and the download's is written beside it.
    const std::string roster = intakeRosterCsv(students), rosterPath = out + "/roster.csv";
    std::string written = rosterPath;
    if (fs::exists(rosterPath) && readFile(rosterPath) != roster) {
        written = out + "/roster.new.csv";
        std::cerr << "simlab: warning: kept " << printable(rosterPath) << ", which differs from the download's "
                  << "roster; the download's is " << printable(written) << "\n";
    }
    writeOutputAtomically(written, roster);
    std::printf("Took in %zu submitter%s of a %s download into %s/class; who is who: %s\n", students.size(),
                students.size() == 1 ? "" : "s", o.from.c_str(), printable(out).c_str(), printable(written).c_str());
    return out + "/class";
}

// Who is who in the class: the platform's ids (the download's, roster.csv's) and each folder by its own name.
engine::StudentIds classIds(const std::string& out, const std::string& root,
                            const std::vector<engine::IntakeStudent>& taken) {
    using namespace simlab::engine;
    StudentIds ids = rosterIds(out + "/roster.csv");
    for (const IntakeStudent& s : taken) {
        for (const std::string& id : {s.id, s.canvasId, s.sid, s.platformId, s.email}) ids.add(id, s.id);
    }
    for (const FolderEntry& e : listFolder(root, /*followFolder=*/true)) {
        if (e.type == EntryType::Directory && e.name[0] != '.') ids.add(e.name, e.name);
    }
    return ids;
}

// Each student's hand-in as the platform gave it: the download's (with Canvas's late flag), or, for a class taken in
// earlier (--intake-only), its roster's, else the file's own time; then the times the instructor names
// (--submitted), which win.
engine::HandIns handIns(const GradeCommandOptions& o, const std::string& out, const std::string& root,
                        const Rubric& rubric, const std::vector<engine::IntakeStudent>& taken,
                        const engine::StudentIds& ids) {
    using namespace simlab::engine;
    HandIns all;
    if (taken.empty()) all = rosterHandIns(out + "/roster.csv");
    if (taken.empty()) {
        for (const FolderEntry& e : listFolder(root, /*followFolder=*/true)) {
            if (e.type != EntryType::Directory || e.name[0] == '.' || all.count(e.name)) continue;
            const Submission found = findSubmission(root + "/" + e.name, rubric.submission, false);
            struct stat st {};
            if (!found.name.empty() && ::lstat((found.folder + "/" + found.name).c_str(), &st) == 0) {
                all[e.name] = handInOf(utcText(st.st_mtime), "the file's time", std::nullopt);
            }
        }
    }
    for (const IntakeStudent& s : taken) {
        const HandIn h =
            handInOf(s.submitted, s.submittedFrom, s.canvasFile.empty() ? std::nullopt : std::optional<bool>(s.late));
        const auto [kept, first] = all.emplace(s.id, h);
        if (first) continue;
        // A group's members share a folder: the latest of their times, late if any is.
        if (!h.time.empty() && (kept->second.time.empty() || *parseTime(h.time) > *parseTime(kept->second.time))) {
            kept->second.time = h.time;
            kept->second.from = h.from;
        }
        if (h.flaggedLate) kept->second.flaggedLate = *h.flaggedLate || kept->second.flaggedLate.value_or(false);
    }
    if (o.submittedTimes.empty()) return all;
    for (const auto& [id, h] : readSubmittedTimes(o.submittedTimes, ids)) {
        HandIn& kept = all[id];
        kept.time = h.time;
        kept.from = h.from;
        kept.vouched = h.vouched;
        if (h.flaggedLate) kept.flaggedLate = h.flaggedLate;
    }
    return all;
}

// The folder the labs are graded side by side in (OUT's parent): where a bank of slip days is kept.
std::string gradesRoot(const std::string& out) {
    const fs::path path = fs::path(out).lexically_normal();
    const fs::path folder = path.has_filename() ? path : path.parent_path();
    return folder.parent_path().empty() ? "." : folder.parent_path().string();
}

// The course file of a grading: --course, or course.toml beside the rubric.
std::string courseFile(const GradeCommandOptions& o, const engine::Assignment& assignment) {
    const std::string rubricPath = o.rubric.empty() ? assignment.rubric : o.rubric;
    std::string path = !o.course.empty() ? o.course : (fs::path(rubricPath).parent_path() / "course.toml").string();
    if (!o.course.empty() && !fs::is_regular_file(path))
        throw engine::UsageError("no course file " + engine::printable(path));
    return path;
}

// The course's rules read before anything is written: a mistake in them stops simlab with the grades as they were.
// A bank of slip days is kept across the labs graded side by side, each in a folder named after it.
void checkCourseRules(const GradeCommandOptions& o, const engine::Assignment& assignment, const std::string& out) {
    using namespace simlab::engine;
    const LatePolicy p = loadLatePolicy(courseFile(o, assignment), assignment.id, {});
    if (!p.active || p.slipDays == 0) return;
    const fs::path path = fs::path(out).lexically_normal();
    const std::string name = (path.has_filename() ? path : path.parent_path()).filename().string();
    if (name != assignment.id) {
        throw UsageError(
            "the course keeps a bank of slip days, spent across the labs graded side by side, each in a "
            "folder named after it (grades/" +
            assignment.id + ", grades/...): grade into a folder named " + assignment.id + ", not " + printable(out));
    }
}

// The course's bank of slip days: each student's account for this lab from the records of the labs graded beside
// it (the days they left it), said in one line. OUT must be named after the lab, as its neighbours are.
void slipDays(const engine::Assignment& assignment, const std::string& out, engine::LatePolicy& p) {
    using namespace simlab::engine;
    const std::string root = gradesRoot(out);
    const SlipLedger ledger = readSlipLedger(root);
    p.slipKnown = true;
    for (const SlipLedger::Lab& lab : ledger.labs) {
        for (const auto& [id, slip] : lab.students) {
            if (!p.slip.count(id)) p.slip[id] = slipAccount(ledger, p.slipDays, assignment.id, p.due, id);
        }
    }
    std::string before;
    for (const SlipLedger::Lab& lab : ledger.labs) {
        if (std::tie(lab.due, lab.id) < std::tie(p.due, assignment.id)) before += (before.empty() ? "" : ", ") + lab.id;
    }
    std::printf("Slip days: %d for each student, spent in the order of the labs' due dates across %s (before %s: %s)\n",
                p.slipDays, printable(root).c_str(), assignment.id.c_str(),
                before.empty() ? "no lab graded" : printable(before).c_str());
}

// The course's late policy (course.toml: --course, or beside the rubric), its extensions matched through the
// platform's ids, and each student's hand-in as the platform gave it; what the run says of those times.
void latePolicy(const GradeCommandOptions& o, const engine::Assignment& assignment, const Rubric& rubric,
                const std::string& out, const std::string& root, const std::vector<engine::IntakeStudent>& taken,
                engine::ClassOptions& options) {
    using namespace simlab::engine;
    const std::string path = courseFile(o, assignment);
    const StudentIds ids = classIds(out, root, taken);
    options.submitted = handIns(o, out, root, rubric, taken, ids);
    options.late = loadLatePolicy(path, assignment.id, ids);
    if (!options.late.active) return;
    if (options.late.slipDays > 0) slipDays(assignment, out, options.late);
    const LatePolicy& p = options.late;
    std::printf("Late policy of %s: due %s, %s %% per %s (at most %s %%)%s%s, %zu extension%s\n",
                printable(path).c_str(), utcText(p.due).c_str(), points(p.penaltyPercent).c_str(),
                p.periodHours == 24 ? "day" : "hour", points(p.maxPercent).c_str(),
                p.graceHours > 0 ? (", " + points(p.graceHours / 24) + " grace day(s)").c_str() : "",
                p.cutoff ? (", no credit after " + utcText(*p.cutoff)).c_str() : "", p.dueFor.size(),
                p.dueFor.size() == 1 ? "" : "s");
    options.handInNotes = checkHandIns(options.submitted, options.late);
}

// The sandbox in use, said to be fit for grading: no test's code may reach the class's files, the grades or the
// hidden tests.
const isolation::SandboxSupport& checkedSandbox(const engine::Manifest& manifest, const std::string& root,
                                                const std::string& out) {
    using namespace simlab::isolation;
    const SandboxSupport& sandbox = sandboxSupport();
    if (!sandbox.warning.empty()) std::cerr << "simlab: warning: " << sandbox.warning << "\n";
    // The class's files and the grades are simlab's places: no sandbox's to see, wherever they lie.
    addPlaces({root, out});
    // Hidden tests run only where no test's code can read them, nor the class's files.
    if (const std::string exposed = engine::placesExposed(manifest); !exposed.empty()) {
        throw engine::UsageError(exposed);
    }
    return sandbox;
}

// A line per student as they finish; on a terminal, a live status line under the log.
std::function<void(const engine::ClassProgress&)> progressPrinter(bool live) {
    return [live](const engine::ClassProgress& p) {
        if (live) std::fprintf(stderr, "\r\x1b[K");
        std::printf("%s\n", studentLine(*p.last, p.lastReused).c_str());
        std::fflush(stdout);
        if (live) {
            std::fprintf(stderr, "  [%d/%d] %s elapsed%s", p.done, p.total, minutesAndSeconds(p.elapsed).c_str(),
                         p.eta >= 0 && p.done < p.total ? (", about " + minutesAndSeconds(p.eta) + " left").c_str() : "");
            std::fflush(stderr);
        }
    };
}

// What grading the class came to: what was skipped, the summary, and the files written.
void reportClass(const GradeCommandOptions& o, bool sharded, const std::string& out,
                 const engine::Assignment& assignment, const Rubric& rubric, const engine::ClassResult& result) {
    using namespace simlab::engine;
    const std::vector<StudentRecord>& records = result.records;
    for (const Skipped& s : result.skipped) {
        std::cout << "  skipped " << printable(s.name) << ": " << s.why << "\n";
    }
    for (const std::string& w : result.warnings) std::cerr << "simlab: warning: " << printable(w) << "\n";

    std::cout << "\n" << summaryTable(rubric, records);
    for (const std::string& line : result.handIns) std::cout << "Hand-in times: " << printable(line) << "\n";
    const int others = static_cast<int>(records.size()) - result.graded - result.reused;
    std::cout << "\n"
              << result.graded << " graded, " << result.reused << " up to date and kept"
              << (o.only.empty() || others <= 0 ? ""
                                                : ", " + std::to_string(others) + " not asked for (--only) and kept")
              << "\n";
    // Points given by hand to a file the student has since replaced: kept and counted, but to be confirmed.
    int earlier = 0;
    for (const StudentRecord& r : records) {
        earlier += static_cast<int>(
            std::count_if(r.manual.begin(), r.manual.end(), [](const ManualGrade& m) { return m.earlierFile; }));
    }
    if (earlier > 0 && !sharded) {
        std::cout << earlier << (earlier == 1 ? " manual grade was" : " manual grades were")
                  << " given to an earlier file: see " << printable(out) << "/report.html\n";
    }
    if (sharded) {
        std::cout << "Wrote shard " << o.shard << "'s students into " << printable(out)
                  << "/students/<id>; once every shard has finished, the same command without --shard writes the "
                     "gradebook, the summary and the reports (it grades again only what no shard finished)\n";
        if (result.graderErrors > 0) {
            throw std::runtime_error(std::to_string(result.graderErrors) +
                                     " student(s) could not be graded (status 'grader error'); the whole-class run "
                                     "retries them");
        }
        return;
    }
    if (!o.junit.empty()) writeOutputAtomically(o.junit, junitXml(assignment, records));
    std::cout << "\nWrote " << printable(out) << "/gradebook.csv, " << printable(out) << "/summary.csv, "
              << printable(out) << "/report.html and " << printable(out)
              << "/students/<id>/{results.json,feedback.md,feedback.html,history.jsonl}"
              << (rubric.manual.empty() ? "" : ", and " + printable(out) + "/manual.csv (fill in the points of the "
                                                "items graded by hand, then run this again: no code runs again)")
              << (o.junit.empty() ? "" : ", " + printable(o.junit)) << "\n";
    if (result.graderErrors > 0) {
        throw std::runtime_error(std::to_string(result.graderErrors) +
                                 " student(s) could not be graded (status 'grader error'); run the command again "
                                 "to retry them");
    }
}

void runGrade(const GradeCommandOptions& o) {
    using namespace simlab::engine;
    const Manifest manifest = loadManifest();
    sayLeftovers(sweepLeftovers());
    const Assignment& assignment = manifest.find(o.assignment);
    if (!assignment.hiddenTestsBuilt) {
        throw UsageError("grading needs the hidden tests, which this copy of simlab does not have");
    }
    // Who may grade, first: a refused run writes nothing (no download taken in as another user's files).
    if (const std::string closed = sandboxCannotReach(manifest, assignment); !closed.empty()) throw UsageError(closed);
    if (const std::string closed = judgeNotYours(assignment); !closed.empty()) throw UsageError(closed);
    const std::string submissions = submissionsFolder(o, manifest, assignment);
    const std::string out = o.out.empty() ? "grades/" + assignment.id : o.out;
    const std::pair<int, int> shard = shardOf(o);
    const Rubric rubric = loadRubric(o.rubric.empty() ? assignment.rubric : o.rubric);
    // A sheet of manual points with a mistake stops simlab before anything changes.
    ManualSheet manual = readManualSheet(out, rubric);
    std::vector<IntakeStudent> taken;
    if (o.intakeOnly && o.from.empty()) {
        throw UsageError(
            "--intake-only takes a platform's download in: add --from gradescope, canvas, moodle or classroom");
    }
    if (!o.submittedTimes.empty() && !fs::is_regular_file(o.submittedTimes)) {
        throw UsageError("no submission times file " + printable(o.submittedTimes));
    }
    if (!shard.second) checkCourseRules(o, assignment, out);
    // Then the lock, before the download is taken in: a second simlab on the same folder stops before it writes.
    // (A shard shares the folder with the other shards, and takes its own lock as it grades.)
    std::optional<OutputLock> lock;
    if (!shard.second) {
        createOutputFolder(out);
        lock.emplace(out);
    }
    const std::string root = classFolder(o, submissions, out, rubric, taken);
    if (o.intakeOnly) {
        // A cluster's shards grade the class folder; the download is taken in once, here.
        std::printf(
            "Nothing graded (--intake-only). Grade it with: simlab grade %s %s/class -o %s, or share it out "
            "with simlab slurm grade %s %s/class --out %s\n",
            assignment.id.c_str(), printable(out).c_str(), printable(out).c_str(), assignment.id.c_str(),
            printable(out).c_str(), printable(out).c_str());
        return;
    }

    ClassOptions options;
    options.jobs = o.jobs;
    options.only = o.only;
    options.grade.includeHidden = true;
    options.grade.limits = limitsWith(rubric.limits, o.timeout, o.memory);
    options.shard = shard.first;
    options.shards = shard.second;
    options.manual = std::move(manual);
    options.locked = lock.has_value();
    if (!shard.second) latePolicy(o, assignment, rubric, out, root, taken, options);

    const isolation::SandboxSupport& sandbox = checkedSandbox(manifest, root, out);
    std::printf("Grading %s (%s) from %s into %s%s: %d jobs, sandbox: %s\n", assignment.id.c_str(),
                assignment.title.c_str(), printable(root).c_str(), printable(out).c_str(),
                shard.second ? (", shard " + o.shard).c_str() : "", o.jobs, sandbox.summary.c_str());
    std::fflush(stdout);

    const bool live = ::isatty(STDERR_FILENO) && ::isatty(STDOUT_FILENO);
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
    const Builder builder(manifest);
    ClassResult result;
    try {
        result = gradeClass(builder, assignment, rubric, root, out, options, progressPrinter(live));
    } catch (const Interrupted&) {
        if (live) std::fprintf(stderr, "\r\x1b[K");
        std::cerr << "simlab: interrupted; what finished is in " << printable(out)
                  << "/gradebook.csv. Run the same command again to grade the rest.\n";
        std::exit(130);
    }
    if (live) std::fprintf(stderr, "\r\x1b[K");
    reportClass(o, shard.second != 0, out, assignment, rubric, result);
    // The labs graded beside this one whose slip days it moved (or that were graded before the bank): named.
    if (options.late.slipKnown) {
        const std::string root = gradesRoot(out);
        const std::string stale = staleSlipLine(staleSlipLabs(readSlipLedger(root), options.late.slipDays), root);
        if (!stale.empty()) std::cout << "Slip days: " << printable(stale) << "\n";
    }
}

}  // namespace

void addGrade(CLI::App& app) {
    auto options = std::make_shared<GradeCommandOptions>();
    CLI::App* grade = app.add_subcommand(
        "grade", "Grade a class on every test: one folder per student (its name is the student id) holding their "
                 "file. Each student's results are written as they finish; run the command again after an "
                 "interruption and only what is unfinished or changed is graded again.");
    grade->add_option("assignment", options->assignment, "which assignment")->required();
    grade->add_option("submissions", options->submissions,
                      "folder of student folders (default: the bundled sample class)");
    grade->add_option("--out,-o", options->out, "where the gradebook and reports go (default: grades/<assignment>)");
    grade->add_option("--jobs,-j", options->jobs, "students graded at once (default: the number of cores)")
        ->check(CLI::Range(1, 64));
    grade->add_option("--only", options->only, "regrade only this student (repeatable); other rows are kept");
    grade->add_option("--junit", options->junit, "also write JUnit XML to this file");
    grade->add_option("--timeout", options->timeout,
                      "CPU seconds each test may use, its processes together, 0.1 to 3600 (default: the rubric's)")
        ->check(limitOption("cpu_seconds"));
    grade->add_option("--memory", options->memory,
                      "MiB of memory each test may hold, its processes together, 64 to 65536 (default: the rubric's)")
        ->check(limitOption("memory_mib"));
    grade->add_option("--rubric", options->rubric, "another rubric file (default: the assignment's)")
        ->check(CLI::ExistingFile);
    grade->add_option("--from", options->from,
                      "SUBMISSIONS is a platform's download, as it comes: gradescope (Export Submissions), canvas "
                      "(Download Submissions), moodle (Download all submissions) or classroom (gh classroom clone "
                      "student-repos); taken in as OUT/class, with OUT/roster.csv (names, ids, e-mails, late flags, "
                      "groups) for simlab export canvas")
        ->check(CLI::IsMember(engine::downloadLayouts()));
    grade->add_flag("--intake-only", options->intakeOnly,
                    "with --from: take the download in as OUT/class and OUT/roster.csv, and grade nothing (a cluster's "
                    "shards then grade OUT/class)");
    grade
        ->add_option("--course", options->course,
                     "the course's rules for late work (course.toml: a due date per assignment, the penalty per day "
                     "or hour, grace days, an extensions file); default: course.toml beside the rubric, if there "
                     "is one")
        ->check(CLI::ExistingFile);
    grade
        ->add_option("--submitted", options->submittedTimes,
                     "when each student handed in, on the platform's word: Canvas's submissions as its API gives "
                     "them (JSON: user_id, submitted_at, late), or a CSV of student (any id the platform gives) and "
                     "submitted; these times set how late, in place of the files' own")
        ->type_name("FILE");
    grade->add_option("--shard", options->shard,
                      "I/N: grade share I of N of the class (students I, I + N, ... in name order) into OUT's student "
                      "folders only, side by side with the other shards on a shared OUT; the command without "
                      "--shard then assembles the gradebook and reports, grading again nothing up to date")
        ->type_name("I/N");
    grade->callback([options] { runGrade(*options); });
}

}  // namespace simlab::cli
