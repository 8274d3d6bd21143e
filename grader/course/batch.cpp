#include "simlab/course/batch.h"

#include <algorithm>
#include <atomic>
#include <ctime>
#include <cctype>
#include <chrono>
#include <exception>
#include <filesystem>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sys/stat.h>

#include "simlab/protocol/attachments.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/common/parallel.h"
#include "simlab/course/manual.h"
#include "simlab/grading/report.h"
#include "simlab/isolation/process.h"
#include "simlab/common/text.h"
#include "simlab/writers/writers.h"

namespace fs = std::filesystem;

namespace simlab::engine {

namespace {

const char kFeedbackHtml[] = "feedback.html";

bool isCppFile(const std::string& name) {
    const std::string e = fs::path(name).extension().string();
    return e == ".cpp" || e == ".cc" || e == ".cxx" || e == ".c++" || e == ".C";
}

std::string baseName(const std::string& relative) { return relative.substr(relative.rfind('/') + 1); }

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

StudentRecord classRecordOf(const std::string& id, const std::string& key, const GradeReport& report,
                            const std::string& file) {
    StudentRecord r = recordOf(report);
    r.id = id;
    r.key = key;
    r.file = file;
    return r;
}

// The files of a student's folder that a test drew for the feedback (attachments.h names them), for a record kept
// from an earlier run, whose report is gone.
std::vector<Attachment> attachedBeside(const std::string& dir) {
    std::vector<Attachment> attached;
    for (const FolderEntry& e : listFolder(dir, /*followFolder=*/false)) {
        if (e.type == EntryType::Regular && wire::isAttachmentName(e.name) && e.name != kFeedbackHtml) {
            Attachment a{e.name, ""};
            try {
                const std::string path = dir + "/" + e.name;
                if (fs::file_size(path) <= wire::kMaxAttachmentBytes) a.text = readFile(path);
            } catch (const std::exception&) {
                // linked, not shown
            }
            attached.push_back(std::move(a));
        }
    }
    return attached;
}

// What of the rubric decides the tests' verdicts: everything but the points (and the descriptions), so that a
// change of points alone re-scores the recorded verdicts instead of running every student's code again.
std::string verdictsOf(const Rubric& rubric) {
    std::string shape = rubric.assignment + "\n" + rubric.submission + "\n";
    for (const std::string& extra : rubric.extraFiles) shape += "extra " + extra + "\n";
    for (const RubricTest& t : rubric.tests) {
        shape += "test " + t.name + "\n" + t.visibility + "\n";
        for (const auto& [key, value] : t.params) shape += key + "=" + std::to_string(value) + "\n";
    }
    return shape;
}

// The record's tests scored with the rubric's points: each test's credit times its points now. True if a score
// moved.
bool rescore(StudentRecord& r, const Rubric& rubric) {
    bool moved = false;
    double score = 0, max = 0;
    for (TestResult& t : r.tests) {
        if (const RubricTest* test = rubric.find(t.name)) {
            const double now = roundScore(test->points * t.credit);
            moved = moved || now != t.score || test->points != t.maxScore;
            t.score = now;
            t.maxScore = test->points;
        }
        score += t.score;
        max += t.maxScore;
    }
    r.score = roundScore(score);
    r.maxScore = roundScore(max);
    return moved;
}

// A line of students/<id>/history.jsonl: when the grade was made, from which file, the score, and why.
void appendHistory(const std::string& dir, const StudentRecord& r, const std::string& why) {
    const std::time_t now = std::time(nullptr);
    char when[32];
    std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    const nlohmann::json line = {{"when", when},     {"file", r.file},           {"key", r.key},
                                 {"status", statusName(r.status)},
                                 {"score", r.score}, {"max_score", r.maxScore}, {"why", why}};
    std::string lines = fs::exists(dir + "/history.jsonl") ? readFile(dir + "/history.jsonl") : "";
    lines += line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
    writeOutputDurably(dir + "/history.jsonl", lines);
}

std::vector<std::string> namesOf(const std::vector<Attachment>& attached) {
    std::vector<std::string> names;
    for (const Attachment& a : attached) names.push_back(a.name);
    return names;
}

}  // namespace

Submission findSubmission(const std::string& folder, const std::string& expected, bool recursive, bool followFolder) {
    const std::vector<FolderEntry> entries = recursive ? walkFolder(folder) : listFolder(folder, followFolder);
    // Every C++-named entry counts, whatever it is: a link or a pipe named NewtonsApple.cpp is found here and
    // refused when read, never passed over for another file.
    std::vector<const FolderEntry*> cpp;
    for (const FolderEntry& e : entries) {
        if (e.type != EntryType::Directory && isCppFile(e.name)) cpp.push_back(&e);
    }
    auto chosen = [&](const FolderEntry& e, SubmissionStatus status, const std::string& note) {
        return Submission{e.folder, baseName(e.name), e.name, status, note};
    };
    for (const FolderEntry* e : cpp) {
        if (baseName(e->name) == expected) return chosen(*e, SubmissionStatus::Graded, "");
    }
    for (const FolderEntry* e : cpp) {
        if (lower(baseName(e->name)) == lower(expected)) {
            return chosen(*e, SubmissionStatus::MisnamedFile, "graded " + e->name + "; expected " + expected);
        }
    }
    if (cpp.size() == 1) {
        return chosen(*cpp[0], SubmissionStatus::MisnamedFile, "graded " + cpp[0]->name + "; expected " + expected);
    }
    if (cpp.empty()) return {folder, "", "", SubmissionStatus::MissingFile, "no " + expected + " (no C++ file at all)"};
    std::string found;
    for (const FolderEntry* e : cpp) found += (found.empty() ? "" : ", ") + e->name;
    return {folder, "", "", SubmissionStatus::MissingFile, "no " + expected + " (found " + found + ")"};
}

Gathered gatherSubmission(const std::string& folder, const Rubric& rubric, const Limits& limits, bool recursive,
                          bool followFolder) {
    Gathered g;
    g.found = findSubmission(folder, rubric.submission, recursive, followFolder);
    g.status = g.found.status;
    g.note = g.found.note;
    if (g.found.name.empty()) return g;
    const std::size_t cap = static_cast<std::size_t>(limits.submissionKiB) * 1024;
    // The folder that holds the file was found without following links, or was named by the user.
    const bool follow = recursive || followFolder;
    const HandedIn source = readHandedIn(g.found.folder, g.found.name, cap, follow);
    if (!source.ok) {
        g.status = source.found ? source.status.value_or(SubmissionStatus::UnsafeFile) : SubmissionStatus::MissingFile;
        g.note = source.found ? source.refusal : "no " + rubric.submission;
        return g;
    }
    SubmissionFiles files;
    files.name = g.found.name;
    files.shown = g.found.shown;
    files.text = source.text;
    for (const std::string& name : rubric.extraFiles) {
        HandedIn extra = readHandedIn(g.found.folder, name, cap, follow);
        if (extra.found) files.extras.push_back(std::move(extra));
    }
    g.files = std::move(files);
    return g;
}

GradeReport gradeFolder(const Builder& builder, const Assignment& assignment, const Rubric& rubric,
                        const std::string& folder, bool recursive, bool followFolder, const GradeOptions& options) {
    const Limits limits = options.limits.value_or(rubric.limits);
    const Gathered g = gatherSubmission(folder, rubric, limits, recursive, followFolder);
    if (!g.files) return notGradedReport(assignment, rubric, g.status, g.note, options.includeHidden);
    GradeReport report = gradeSubmission(builder, assignment, rubric, *g.files, options);
    if (report.status == SubmissionStatus::Graded) report.status = g.status;
    if (!g.note.empty()) report.note = g.note + (report.note.empty() ? "" : "; " + report.note);
    return report;
}

namespace {

// The class folder's students in name order (a shard's share of them); what is not a student's folder is listed in
// `skipped`.
std::vector<std::string> classStudents(const std::string& submissionsDir, const ClassOptions& options,
                                       std::vector<Skipped>& skipped) {
    std::vector<std::string> ids;
    for (const FolderEntry& e : listFolder(submissionsDir, /*followFolder=*/true)) {
        if (e.name[0] == '.') skipped.push_back({e.name, "a hidden folder or file (its name starts with a dot)"});
        else if (e.type == EntryType::Directory) ids.push_back(e.name);
        else if (e.type == EntryType::Symlink) skipped.push_back({e.name, "a symbolic link, not a folder"});
        else skipped.push_back({e.name, "a file, not a student's folder"});
    }
    for (const std::string& id : options.only) {
        if (!std::binary_search(ids.begin(), ids.end(), id)) {
            throw UsageError("no student '" + printable(id) + "' in " + printable(submissionsDir));
        }
    }
    if (options.shards <= 0) return ids;
    if (options.shard < 1 || options.shard > options.shards) {
        throw UsageError("shard " + std::to_string(options.shard) + " of " + std::to_string(options.shards) +
                         " does not exist: shards count from 1");
    }
    // A deterministic share: every shard lists the same class folder in the same (name) order.
    std::vector<std::string> share;
    for (std::size_t i = static_cast<std::size_t>(options.shard - 1); i < ids.size();
         i += static_cast<std::size_t>(options.shards)) {
        share.push_back(ids[i]);
    }
    return share;
}

// What every grade depends on besides the student's files.
Hash gradingBasis(const Builder& builder, const Assignment& assignment, const Rubric& rubric, const Limits& limits,
                  bool includeHidden) {
    Hash base;
    base.add(builder.gradingKey(assignment)).add(verdictsOf(rubric));
    for (double v : {limits.wallSeconds, limits.cpuSeconds, double(limits.memoryMiB), double(limits.outputKiB),
                     double(limits.fileMiB), double(limits.processes), double(limits.observationMiB),
                     double(limits.submissionKiB)}) {
        base.add(std::to_string(v));
    }
    base.add(includeHidden ? "all tests" : "visible tests");
    return base;
}

// The whole class's own files beside the grades: the sheet of points given by hand, written back at once with a row
// for every student and item (nothing typed in it is lost), and the rubric the class was graded with (the exports
// read its points).
void writeClassSheets(const std::string& outDir, const ManualSheet& sheet, const std::vector<std::string>& ids,
                      const Rubric& rubric, std::vector<std::string>& warnings) {
    const std::string sheetPath = outDir + "/manual.csv";
    if (!rubric.manual.empty() || fs::exists(sheetPath)) {
        const std::vector<std::string> stray = strayManualRows(sheet, ids, rubric);
        if (!stray.empty()) {
            warnings.push_back(std::to_string(stray.size()) + " row(s) of " + sheetPath +
                               " name no student of the class or no item of the rubric, and count for nothing "
                               "(kept as typed): " +
                               stray.front() + (stray.size() > 1 ? ", ..." : ""));
        }
        writeOutputAtomically(sheetPath, manualCsv(sheet, ids, rubric));
    }
    writeOutputAtomically(outDir + "/rubric.toml", readFile(rubric.path));
}

// A student to grade now, and why (history.jsonl).
struct Pending {
    std::string id, key, content;
    Gathered gathered;
    std::string why;
};

// Each student's grade: kept (up to date with their files and the grader) or to be made.
struct ClassPlan {
    std::map<std::string, StudentRecord> records;  // by id: the kept ones, then each as it is graded
    std::vector<std::string> rescored;             // kept records whose scores the rubric's points moved
    std::vector<Pending> pending;
    int reused = 0;
    // By id: what the grade an instructor saw was made from (manual.csv's file column), the grade kept from before
    // this run, else the one made now.
    std::map<std::string, std::string> graded;
};

// The key of a student's grade: the basis and the bytes that will be graded, read once, with care.
std::string submissionKey(const Hash& base, const Gathered& gathered, const Rubric& rubric) {
    Hash key = base;
    key.add(statusName(gathered.status)).add(gathered.note).add(gathered.found.shown);
    if (gathered.files) {
        key.add(gathered.files->text);
        for (const std::string& name : rubric.extraFiles) {
            const auto extra = std::find_if(gathered.files->extras.begin(), gathered.files->extras.end(),
                                            [&](const HandedIn& h) { return h.name == name; });
            key.add(extra == gathered.files->extras.end() ? "(none)" : extra->ok ? extra->text : extra->refusal);
        }
    }
    return key.hex();
}

// What is graded, the grader and the rubric aside: which of a student's files the points given by hand were given to.
std::string contentOf(const Gathered& gathered, const Rubric& rubric) {
    return submissionKey(Hash(), gathered, rubric).substr(0, 12);
}

ClassPlan planClass(const std::vector<std::string>& ids, const std::string& submissionsDir, const std::string& outDir,
                    const Rubric& rubric, const Limits& limits, const Hash& base, const ClassOptions& options) {
    ClassPlan plan;
    for (const std::string& id : ids) {
        const bool wanted = options.only.empty() || std::count(options.only.begin(), options.only.end(), id);
        const std::string recordPath = outDir + "/students/" + id + "/record.json";
        std::optional<StudentRecord> kept;
        if (fs::exists(recordPath)) kept = readRecordJson(readFile(recordPath));
        const std::string before = kept ? kept->content : "";
        // A record of tests the rubric does not hold was not written for this rubric: damaged, so graded again.
        if (kept && std::any_of(kept->tests.begin(), kept->tests.end(),
                                [&](const TestResult& t) { return !rubric.find(t.name); })) {
            kept.reset();
        }
        if (kept) kept->id = id;
        if (kept && !wanted) {
            plan.records[id] = *kept;
            plan.graded[id] = before;
            continue;
        }
        if (!wanted) continue;
        Gathered gathered = gatherSubmission(submissionsDir + "/" + id, rubric, limits, false, false);
        const std::string key = submissionKey(base, gathered, rubric), content = contentOf(gathered, rubric);
        plan.graded[id] = before.empty() ? content : before;
        if (kept && options.only.empty() && kept->key == key) {
            kept->content = content;
            if (rescore(*kept, rubric)) plan.rescored.push_back(id);
            plan.records[id] = *kept;
            ++plan.reused;
        } else {
            const std::string why = !kept                          ? "first graded"
                                    : kept->key == "retry"         ? "its last grading failed"
                                    : kept->basis != base.hex()    ? "the grader, the rubric's tests or the limits changed"
                                    : !options.only.empty()        ? "asked for (--only)"
                                                                   : "the submission changed";
            plan.pending.push_back({id, key, content, std::move(gathered), why});
        }
    }
    return plan;
}

// When the student handed their file in (the platform's time, else the file's own), and the late policy applied.
void stampLateness(StudentRecord& r, const std::string& submissionsDir, const ClassOptions& options) {
    // A student the platform names has its time, or none (their files were written when the download was taken
    // in: no time of theirs).
    HandIn handIn;
    if (const auto given = options.submitted.find(r.id); given != options.submitted.end()) {
        handIn = given->second;
        r.submitted = handIn.time;
        r.submittedFrom = handIn.time.empty() ? "" : handIn.from;
    } else if (struct stat st{};
               !r.file.empty() && ::lstat((submissionsDir + "/" + r.id + "/" + r.file).c_str(), &st) == 0) {
        r.submitted = utcText(st.st_mtime);
        r.submittedFrom = "the file's time";
    }
    applyLatePolicy(r, options.late, handIn);
}

// Kept records: results.json written again from each (its scores now, and the points given by hand); the feedback
// of those re-scored by the rubric's points or graded by hand says so too, and one graded by a simlab that wrote no
// feedback.html gets one, so that report.html links to a page.
void refreshKeptRecords(const Assignment& assignment, const Rubric& rubric, const std::string& outDir,
                        const ManualSheet& sheet, const std::string& submissionsDir, const ClassOptions& options,
                        ClassPlan& plan) {
    for (auto& [id, r] : plan.records) {
        applyManual(r, sheet, rubric);
        // The time, the lateness and the slip days the bank gives now (what the labs due before it spent).
        const std::string before = recordJson(r);
        stampLateness(r, submissionsDir, options);
        if (recordJson(r) != before) writeOutputDurably(outDir + "/students/" + id + "/record.json", recordJson(r));
        const bool moved = std::count(plan.rescored.begin(), plan.rescored.end(), id) > 0;
        const std::string dir = outDir + "/students/" + id;
        writeOutputAtomically(dir + "/results.json", resultsJson(r));
        if (!moved && rubric.manual.empty() && !options.late.active) continue;
        if (moved) {
            writeOutputDurably(dir + "/record.json", recordJson(r));
            appendHistory(dir, r, "the rubric's points changed (re-scored from the recorded verdicts)");
        }
        const std::vector<Attachment> attached = attachedBeside(dir);
        writeOutputAtomically(dir + "/feedback.md", feedbackMarkdown(assignment, r, rubric.manual, namesOf(attached)));
        writeOutputAtomically(dir + "/" + kFeedbackHtml, feedbackHtml(assignment, r, rubric.manual, attached));
    }
    for (const auto& [id, r] : plan.records) {
        const std::string dir = outDir + "/students/" + id;
        if (!fs::exists(dir + "/" + kFeedbackHtml)) {
            writeOutputAtomically(dir + "/" + kFeedbackHtml,
                                  feedbackHtml(assignment, r, rubric.manual, attachedBeside(dir)));
        }
    }
}

// The pending students graded `jobs` at a time. Each student's files are written as they finish, the record last
// (the commit), and the gradebook after each: replaced whole (never half written), and flushed to the disk at the
// end. A gradebook a power cut took back is written again from the records.
class ClassGrading {
public:
    struct Context {
        const Builder& builder;
        const Assignment& assignment;
        const Rubric& rubric;
        const std::string& outDir;
        const std::string& submissionsDir;
        const ClassOptions& options;
        const ManualSheet& sheet;
        std::string basis;
        std::chrono::steady_clock::time_point start;
        int students;  // the students this run is about: the class, or those asked for
        std::function<void(const ClassProgress&)> onProgress;
    };

    ClassGrading(Context context, ClassPlan& plan, ClassResult& result)
        : c_(std::move(context)), plan_(plan), result_(result) {
        progress_.total = c_.students;
        progress_.reused = plan.reused;
    }

    // The kept students reported, then the pending ones graded. Returns what stopped a setup for every student,
    // if something did.
    std::exception_ptr run() {
        publish(false);
        for (const auto& [id, r] : plan_.records) {
            if (c_.options.only.empty() || std::count(c_.options.only.begin(), c_.options.only.end(), id)) {
                ++progress_.done;
                progress_.last = &r;
                progress_.lastReused = true;
                if (c_.onProgress) c_.onProgress(progress_);
            }
        }
        alreadyDone_ = progress_.done;
        forEachInParallel(plan_.pending.size(), c_.options.jobs, [this](std::size_t i) {
            if (!stop_) gradeOne(plan_.pending[i]);
        });
        return setupFailure_;
    }

    void publish(bool durable) {
        if (c_.options.shards > 0) return;  // the whole-class run writes the gradebook
        std::vector<StudentRecord> sorted;
        for (const auto& [id, r] : plan_.records) sorted.push_back(r);
        const std::string text = gradebookCsv(c_.rubric, sorted);
        if (durable) writeOutputDurably(c_.outDir + "/gradebook.csv", text);
        else writeOutputAtomically(c_.outDir + "/gradebook.csv", text);
    }

private:
    void gradeOne(const Pending& p) {
        GradeOptions grade = c_.options.grade;
        grade.student = p.id;  // the folder's name: their own trade scene where the rubric gives each one
        try {
            GradeReport report;
            if (p.gathered.files) {
                report = gradeSubmission(c_.builder, c_.assignment, c_.rubric, *p.gathered.files, grade);
                if (report.status == SubmissionStatus::Graded) report.status = p.gathered.status;
                if (!p.gathered.note.empty()) {
                    report.note = p.gathered.note + (report.note.empty() ? "" : "; " + report.note);
                }
            } else {
                report =
                    notGradedReport(c_.assignment, c_.rubric, p.gathered.status, p.gathered.note, grade.includeHidden);
            }
            StudentRecord graded = classRecordOf(p.id, p.key, report, p.gathered.found.shown);
            graded.content = p.content;
            finish(graded, &report, p.why);
        } catch (const Interrupted&) {
            stop_ = true;  // this student has no outcome: the next run grades them
        } catch (const SetupError&) {
            // No student's fault, and every one would meet it: stop, keep what was graded, and say why.
            std::lock_guard<std::mutex> guard(lock_);
            if (!setupFailure_) setupFailure_ = std::current_exception();
            stop_ = true;
        } catch (const std::exception& e) {
            // simlab could not grade this one (a disk full, say): a row that says so, and a retry next run.
            StudentRecord failed;
            failed.id = p.id;
            failed.key = "retry";
            failed.content = p.content;
            failed.status = SubmissionStatus::GraderError;
            failed.note = e.what();
            failed.maxScore = c_.rubric.totalPoints();
            failed.assignment = c_.assignment.id;
            try {
                finish(failed, nullptr, p.why + "; simlab could not grade it: " + failed.note);
            } catch (const std::exception&) {
                stop_ = true;  // nothing can be written: stop rather than lose grades silently
            }
            std::lock_guard<std::mutex> guard(lock_);
            ++result_.graderErrors;
        }
    }

    void finish(StudentRecord record, const GradeReport* report, const std::string& why) {
        const std::string dir = c_.outDir + "/students/" + record.id;
        fs::create_directories(dir);
        record.basis = c_.basis;
        applyManual(record, c_.sheet, c_.rubric);
        stampLateness(record, c_.submissionsDir, c_.options);
        writeOutputAtomically(dir + "/results.json", resultsJson(record));
        if (report) writeOutputAtomically(dir + "/output.txt", testOutputText(*report));
        std::vector<Attachment> attached;
        if (report) {
            for (const TestResult& t : report->tests) {
                for (const auto& [name, text] : t.attachments) {
                    if (name == kFeedbackHtml) continue;  // the page below
                    writeOutputAtomically(dir + "/" + name, text);
                    attached.push_back({name, text});
                }
            }
        }
        const std::vector<ManualItem>& manual = c_.rubric.manual;
        writeOutputAtomically(dir + "/feedback.md", feedbackMarkdown(c_.assignment, record, manual, namesOf(attached)));
        writeOutputAtomically(dir + "/" + kFeedbackHtml, feedbackHtml(c_.assignment, record, manual, attached));
        appendHistory(dir, record, why);
        writeOutputDurably(dir + "/record.json", recordJson(record));  // last: the commit

        std::lock_guard<std::mutex> guard(lock_);
        plan_.records[record.id] = record;
        ++result_.graded;
        publish(false);
        ++progress_.done;
        progress_.elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - c_.start).count();
        const double graded = progress_.done - alreadyDone_;
        progress_.eta = progress_.elapsed / graded * (progress_.total - progress_.done);
        progress_.last = &plan_.records[record.id];
        progress_.lastReused = false;
        if (c_.onProgress) c_.onProgress(progress_);
    }

    Context c_;
    ClassPlan& plan_;
    ClassResult& result_;
    std::mutex lock_;
    ClassProgress progress_;
    int alreadyDone_ = 0;
    std::atomic<bool> stop_{false};
    std::exception_ptr setupFailure_;
};

}  // namespace

ClassResult gradeClass(const Builder& builder, const Assignment& assignment, const Rubric& rubric,
                       const std::string& submissionsDir, const std::string& outDir, const ClassOptions& options,
                       const std::function<void(const ClassProgress&)>& onProgress) {
    const auto start = std::chrono::steady_clock::now();
    ClassResult result;
    const std::vector<std::string> ids = classStudents(submissionsDir, options, result.skipped);
    const bool sharded = options.shards > 0;
    createOutputFolder(outDir);
    fs::create_directories(outDir + "/students");
    // One simlab at a time writes a class's grades, or shards side by side, each its own students.
    std::optional<OutputLock> outputLock;
    if (!options.locked) {
        outputLock.emplace(outDir,
                           sharded ? std::to_string(options.shard) + "-of-" + std::to_string(options.shards) : "");
    }
    const Limits limits = options.grade.limits.value_or(rubric.limits);
    const Hash base = gradingBasis(builder, assignment, rubric, limits, options.grade.includeHidden);
    ClassPlan plan = planClass(ids, submissionsDir, outDir, rubric, limits, base, options);
    // What a person graded (manual.csv, read by the caller), each row with points told which file they were given
    // to; a shard leaves the class's own files to the whole run.
    ManualSheet sheet = sharded ? ManualSheet{} : options.manual;
    stampManual(sheet, plan.graded);
    if (!sharded) writeClassSheets(outDir, sheet, ids, rubric, result.warnings);
    refreshKeptRecords(assignment, rubric, outDir, sheet, submissionsDir, options, plan);
    const int students = static_cast<int>(options.only.empty() ? ids.size() : options.only.size());
    ClassGrading grading(
        {builder, assignment, rubric, outDir, submissionsDir, options, sheet, base.hex(), start, students, onProgress},
        plan, result);
    const std::exception_ptr setupFailure = grading.run();

    for (const std::string& id : ids) {
        if (plan.records.count(id)) result.records.push_back(plan.records[id]);
    }
    grading.publish(true);
    result.reused = plan.reused;
    result.handIns = options.handInNotes;
    if (!sharded) {
        writeOutputAtomically(outDir + "/summary.csv", summaryCsv(rubric, result.records));
        writeOutputAtomically(outDir + "/report.html", classReportHtml(assignment, rubric, result));
    }
    if (setupFailure) std::rethrow_exception(setupFailure);
    if (isolation::childrenInterrupted()) throw Interrupted();
    return result;
}

}  // namespace simlab::engine
