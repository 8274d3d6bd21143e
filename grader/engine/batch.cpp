#include "simlab/engine/batch.h"

#include <algorithm>
#include <cctype>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "simlab/engine/errors.h"
#include "simlab/engine/files.h"
#include "simlab/engine/process.h"
#include "simlab/engine/report.h"
#include "simlab/engine/text.h"

namespace fs = std::filesystem;

namespace simlab::engine {

namespace {

bool isCppFile(const std::string& name) {
    const std::string e = fs::path(name).extension().string();
    return e == ".cpp" || e == ".cc" || e == ".cxx" || e == ".c++" || e == ".C";
}

std::string baseName(const std::string& relative) { return relative.substr(relative.rfind('/') + 1); }

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

// --- Records ---------------------------------------------------------------------------------------------------

std::string jsonText(const nlohmann::json& j) {
    return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

nlohmann::json toJson(const StudentRecord& r) {
    nlohmann::json tests = nlohmann::json::array();
    for (const TestResult& t : r.tests) {
        nlohmann::json j = {{"name", t.name},         {"visibility", t.visibility}, {"score", t.score},
                            {"max_score", t.maxScore}, {"outcome", outcomeName(t.outcome)},
                            {"reason", t.reason},     {"feedback", t.feedback},     {"seconds", t.seconds}};
        if (t.figure) j["figure"] = {{"value", *t.figure}, {"unit", t.unit}};
        tests.push_back(j);
    }
    return {{"id", r.id},       {"key", r.key},           {"status", r.status},   {"note", r.note},
            {"file", r.file},   {"score", r.score},       {"max_score", r.maxScore},
            {"seconds", r.seconds}, {"compiler", r.compiler}, {"tests", tests}};
}

std::optional<StudentRecord> fromJson(const nlohmann::json& j) {
    try {
        StudentRecord r;
        r.id = j.at("id");
        r.key = j.at("key");
        r.status = j.at("status");
        r.note = j.at("note");
        r.file = j.at("file");
        r.score = j.at("score");
        r.maxScore = j.at("max_score");
        r.seconds = j.at("seconds");
        r.compiler = j.at("compiler");
        for (const nlohmann::json& t : j.at("tests")) {
            TestResult x;
            x.name = t.at("name");
            x.visibility = t.at("visibility");
            x.score = t.at("score");
            x.maxScore = t.at("max_score");
            x.outcome = outcomeNamed(t.at("outcome"));
            x.reason = t.at("reason");
            x.feedback = t.at("feedback").get<std::vector<std::string>>();
            x.seconds = t.at("seconds");
            if (t.contains("figure")) {
                x.figure = t["figure"].at("value").get<double>();
                x.unit = t["figure"].at("unit");
            }
            r.tests.push_back(x);
        }
        return r;
    } catch (const std::exception&) {
        return std::nullopt;  // damaged or from another version: regrade
    }
}

StudentRecord recordOf(const std::string& id, const std::string& key, const GradeReport& report,
                       const std::string& file) {
    StudentRecord r;
    r.id = id;
    r.key = key;
    r.status = report.status;
    r.note = report.note;
    r.file = file;
    r.score = report.score();
    r.maxScore = report.maxScore();
    r.seconds = report.seconds;
    r.compiler = firstLines(report.build.ok ? report.build.warnings : report.build.log, 20);
    r.tests = report.tests;
    return r;
}

// --- CSV ----------------------------------------------------------------------------------------------------------

std::string gradebookCsv(const Rubric& rubric, const std::vector<StudentRecord>& records) {
    std::ostringstream out;
    out << "student,score,max,status";
    for (const RubricTest& t : rubric.tests) out << "," << csvCell(t.name);
    // Items a person grades: a column each, "pending" until the instructor fills in the points.
    for (const ManualItem& m : rubric.manual) out << "," << csvCell("manual (" + points(m.points) + "): " + m.name);
    out << "\n";
    for (const StudentRecord& r : records) {
        out << csvCell(r.id) << "," << points(r.score) << "," << points(r.maxScore) << "," << csvCell(r.status);
        for (const RubricTest& t : rubric.tests) {
            const auto found = std::find_if(r.tests.begin(), r.tests.end(),
                                            [&](const TestResult& x) { return x.name == t.name; });
            out << "," << (found == r.tests.end() ? "" : points(found->score));
        }
        for (std::size_t i = 0; i < rubric.manual.size(); ++i) out << ",pending";
        out << "\n";
    }
    return out.str();
}

// --- Text --------------------------------------------------------------------------------------------------------

struct Spread {
    int count = 0;
    double median = NAN, min = NAN, max = NAN;
};

Spread spreadOf(std::vector<double> values) {
    Spread s;
    s.count = static_cast<int>(values.size());
    if (values.empty()) return s;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    s.median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
    s.min = values.front();
    s.max = values.back();
    return s;
}

struct TestSummary {
    const RubricTest* test = nullptr;
    int graded = 0;  // students whose file was built and run
    int passed = 0;
    Spread figures;
    std::string unit;
};

std::vector<TestSummary> summarize(const Rubric& rubric, const std::vector<StudentRecord>& records) {
    std::vector<TestSummary> out;
    for (const RubricTest& test : rubric.tests) {
        TestSummary s;
        s.test = &test;
        std::vector<double> figures;
        for (const StudentRecord& r : records) {
            for (const TestResult& t : r.tests) {
                if (t.name != test.name || t.outcome == Outcome::MissingFile) continue;
                ++s.graded;
                s.passed += t.outcome == Outcome::Passed;
                if (t.figure) {
                    figures.push_back(*t.figure);
                    s.unit = t.unit;
                }
            }
        }
        s.figures = spreadOf(figures);
        out.push_back(s);
    }
    return out;
}

std::string number(double v) {
    if (std::isnan(v)) return "";
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", v);
    return text;
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
    auto chosen = [&](const FolderEntry& e, const std::string& status, const std::string& note) {
        return Submission{e.folder, baseName(e.name), e.name, status, note};
    };
    for (const FolderEntry* e : cpp) {
        if (baseName(e->name) == expected) return chosen(*e, "graded", "");
    }
    for (const FolderEntry* e : cpp) {
        if (lower(baseName(e->name)) == lower(expected)) {
            return chosen(*e, "misnamed file", "graded " + e->name + "; expected " + expected);
        }
    }
    if (cpp.size() == 1) return chosen(*cpp[0], "misnamed file", "graded " + cpp[0]->name + "; expected " + expected);
    if (cpp.empty()) return {folder, "", "", "missing file", "no " + expected + " (no C++ file at all)"};
    std::string found;
    for (const FolderEntry* e : cpp) found += (found.empty() ? "" : ", ") + e->name;
    return {folder, "", "", "missing file", "no " + expected + " (found " + found + ")"};
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
        g.status = source.found ? source.status : "missing file";
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
    if (report.status == "graded") report.status = g.status;
    if (!g.note.empty()) report.note = g.note + (report.note.empty() ? "" : "; " + report.note);
    return report;
}

ClassResult gradeClass(const Builder& builder, const Assignment& assignment, const Rubric& rubric,
                       const std::string& submissionsDir, const std::string& outDir, const ClassOptions& options,
                       const std::function<void(const ClassProgress&)>& onProgress) {
    const auto start = std::chrono::steady_clock::now();
    ClassResult result;
    std::vector<std::string> ids;
    for (const FolderEntry& e : listFolder(submissionsDir, /*followFolder=*/true)) {
        if (e.name[0] == '.') result.skipped.push_back({e.name, "a hidden folder or file (its name starts with a dot)"});
        else if (e.type == EntryType::Directory) ids.push_back(e.name);
        else if (e.type == EntryType::Symlink) result.skipped.push_back({e.name, "a symbolic link, not a folder"});
        else result.skipped.push_back({e.name, "a file, not a student's folder"});
    }
    for (const std::string& id : options.only) {
        if (!std::binary_search(ids.begin(), ids.end(), id)) {
            throw UsageError("no student '" + printable(id) + "' in " + printable(submissionsDir));
        }
    }
    fs::create_directories(outDir + "/students");

    // What every grade depends on besides the student's files.
    Hash base;
    base.add(builder.graderKey(assignment)).add(readFile(rubric.path));
    const Limits limits = options.grade.limits.value_or(rubric.limits);
    for (double v : {limits.wallSeconds, limits.cpuSeconds, double(limits.memoryMiB), double(limits.outputKiB),
                     double(limits.fileMiB), double(limits.processes), double(limits.observationMiB),
                     double(limits.submissionKiB)}) {
        base.add(std::to_string(v));
    }
    base.add(options.grade.includeHidden ? "all tests" : "visible tests");

    std::map<std::string, StudentRecord> records;
    struct Pending {
        std::string id, key;
        Gathered gathered;
    };
    std::vector<Pending> pending;
    int reused = 0;
    for (const std::string& id : ids) {
        const bool wanted = options.only.empty() || std::count(options.only.begin(), options.only.end(), id);
        const std::string recordPath = outDir + "/students/" + id + "/record.json";
        std::optional<StudentRecord> kept;
        if (fs::exists(recordPath)) kept = fromJson(nlohmann::json::parse(readFile(recordPath), nullptr, false));
        if (kept) kept->id = id;
        if (kept && !wanted) {
            records[id] = *kept;
            continue;
        }
        if (!wanted) continue;
        // The key is made from the bytes that will be graded, read once, with care.
        Gathered gathered = gatherSubmission(submissionsDir + "/" + id, rubric, limits, false, false);
        Hash key = base;
        key.add(gathered.status).add(gathered.note).add(gathered.found.shown);
        if (gathered.files) {
            key.add(gathered.files->text);
            for (const std::string& name : rubric.extraFiles) {
                const auto extra = std::find_if(gathered.files->extras.begin(), gathered.files->extras.end(),
                                                [&](const HandedIn& h) { return h.name == name; });
                key.add(extra == gathered.files->extras.end() ? "(none)" : extra->ok ? extra->text : extra->refusal);
            }
        }
        if (kept && options.only.empty() && kept->key == key.hex()) {
            records[id] = *kept;
            ++reused;
        } else {
            pending.push_back({id, key.hex(), std::move(gathered)});
        }
    }

    std::mutex lock;
    ClassProgress progress;
    progress.total = static_cast<int>(options.only.empty() ? ids.size() : options.only.size());
    progress.reused = reused;
    auto publish = [&] {
        std::vector<StudentRecord> sorted;
        for (const auto& [id, r] : records) sorted.push_back(r);
        writeFileAtomically(outDir + "/gradebook.csv", gradebookCsv(rubric, sorted));
    };
    publish();
    for (const auto& [id, r] : records) {
        if (options.only.empty() || std::count(options.only.begin(), options.only.end(), id)) {
            ++progress.done;
            progress.last = &r;
            progress.lastReused = true;
            if (onProgress) onProgress(progress);
        }
    }

    std::atomic<std::size_t> next{0};
    std::atomic<bool> stop{false};
    const int alreadyDone = progress.done;
    auto finish = [&](StudentRecord record, bool writeRecord, const GradeReport* report) {
        const std::string dir = outDir + "/students/" + record.id;
        fs::create_directories(dir);
        if (report) {
            writeFileAtomically(dir + "/results.json", jsonText(toGradescope(*report)));
            std::string output;
            for (const TestResult& t : report->tests) {
                output += "=== " + t.name + " (" + outcomeName(t.outcome) + ")\n" + printable(t.output, true) + "\n";
            }
            if (!report->graderOutput.empty()) {
                output += "=== the grader's account of the tests\n" + printable(report->graderOutput, true) + "\n";
            }
            writeFileAtomically(dir + "/output.txt", output);
        }
        std::vector<std::string> attached;
        if (report) {
            for (const TestResult& t : report->tests) {
                for (const auto& [name, text] : t.attachments) {
                    writeFileAtomically(dir + "/" + name, text);
                    attached.push_back(name);
                }
            }
        }
        writeFileAtomically(dir + "/feedback.md", feedbackMarkdown(assignment, record, rubric.manual, attached));
        if (writeRecord) writeFileAtomically(dir + "/record.json", jsonText(toJson(record)));  // last: the commit

        std::lock_guard<std::mutex> guard(lock);
        records[record.id] = record;
        publish();
        ++progress.done;
        progress.elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const double graded = progress.done - alreadyDone;
        progress.eta = progress.elapsed / graded * (progress.total - progress.done);
        progress.last = &records[record.id];
        progress.lastReused = false;
        if (onProgress) onProgress(progress);
    };
    auto worker = [&](int slot) {
        for (std::size_t i = next++; i < pending.size() && !stop; i = next++) {
            const Pending& p = pending[i];
            GradeOptions grade = options.grade;
            grade.slot = slot;
            try {
                GradeReport report;
                if (p.gathered.files) {
                    report = gradeSubmission(builder, assignment, rubric, *p.gathered.files, grade);
                    if (report.status == "graded") report.status = p.gathered.status;
                    if (!p.gathered.note.empty()) {
                        report.note = p.gathered.note + (report.note.empty() ? "" : "; " + report.note);
                    }
                } else {
                    report = notGradedReport(assignment, rubric, p.gathered.status, p.gathered.note,
                                             grade.includeHidden);
                }
                finish(recordOf(p.id, p.key, report, p.gathered.found.shown), true, &report);
            } catch (const Interrupted&) {
                stop = true;  // this student has no outcome: the next run grades them
            } catch (const std::exception& e) {
                // simlab could not grade this one (a disk full, say): a row that says so, and a retry next run.
                StudentRecord failed;
                failed.id = p.id;
                failed.key = "retry";
                failed.status = "grader error";
                failed.note = e.what();
                failed.maxScore = rubric.totalPoints();
                try {
                    finish(failed, true, nullptr);
                } catch (const std::exception&) {
                    stop = true;  // nothing can be written: stop rather than lose grades silently
                }
                std::lock_guard<std::mutex> guard(lock);
                ++result.graderErrors;
            }
        }
    };
    std::vector<std::thread> workers;
    const int jobs = std::max(1, std::min<int>(options.jobs, static_cast<int>(pending.size())));
    for (int slot = 0; slot < jobs; ++slot) workers.emplace_back(worker, slot);
    for (std::thread& w : workers) w.join();

    for (const std::string& id : ids) {
        if (records.count(id)) result.records.push_back(records[id]);
    }
    writeFileAtomically(outDir + "/summary.csv", summaryCsv(rubric, result.records));
    if (childrenInterrupted()) throw Interrupted();
    return result;
}

std::string summaryCsv(const Rubric& rubric, const std::vector<StudentRecord>& records) {
    std::ostringstream out;
    out << "test,visibility,points,graded,passed,pass_rate,figure,median,min,max\n";
    for (const TestSummary& s : summarize(rubric, records)) {
        out << csvCell(s.test->name) << "," << s.test->visibility << "," << points(s.test->points) << ","
            << s.graded << "," << s.passed << "," << (s.graded ? number(double(s.passed) / s.graded) : "") << ","
            << csvCell(s.unit) << "," << number(s.figures.median) << "," << number(s.figures.min) << ","
            << number(s.figures.max) << "\n";
    }
    return out.str();
}

std::string summaryTable(const Rubric& rubric, const std::vector<StudentRecord>& records) {
    std::ostringstream out;
    std::vector<double> scores;
    for (const StudentRecord& r : records) scores.push_back(r.score);
    const Spread total = spreadOf(scores);
    out << "Class of " << records.size() << ": median " << number(total.median) << ", min " << number(total.min)
        << ", max " << number(total.max) << " of " << points(rubric.totalPoints()) << " points\n";
    char line[256];
    std::snprintf(line, sizeof line, "  %-6s %-6s  %-44s  %s\n", "passed", "points", "measured: median [min, max]",
                  "test");
    out << line;
    for (const TestSummary& s : summarize(rubric, records)) {
        const std::string rate = s.graded ? std::to_string(s.passed) + "/" + std::to_string(s.graded) : "-";
        std::string figure;
        if (s.figures.count > 0) {
            figure = number(s.figures.median) + " [" + number(s.figures.min) + ", " + number(s.figures.max) + "] " +
                     s.unit;
        }
        std::snprintf(line, sizeof line, "  %-6s %-6s  %-44s  %s\n", rate.c_str(), points(s.test->points).c_str(),
                      figure.substr(0, 44).c_str(), s.test->name.c_str());
        out << line;
    }
    return out.str();
}

std::string junitXml(const Assignment& assignment, const std::vector<StudentRecord>& records) {
    int tests = 0, failures = 0, errors = 0;
    std::ostringstream suites;
    for (const StudentRecord& r : records) {
        int f = 0, e = 0;
        std::ostringstream cases;
        for (const TestResult& t : r.tests) {
            cases << "    <testcase classname=\"" << xmlText(assignment.id + "." + r.id) << "\" name=\""
                  << xmlText(t.name) << "\" time=\"" << t.seconds << "\"";
            if (t.outcome == Outcome::Passed) {
                cases << "/>\n";
                continue;
            }
            const bool failed = t.outcome == Outcome::Failed;
            (failed ? f : e)++;
            const std::string tag = failed ? "failure" : "error";
            const std::string message = outcomeName(t.outcome) + (t.reason.empty() ? "" : ": " + t.reason);
            cases << ">\n      <" << tag << " type=\"" << xmlText(outcomeName(t.outcome)) << "\" message=\""
                  << xmlText(message) << "\">" << xmlText(message) << "</" << tag << ">\n    </testcase>\n";
        }
        tests += static_cast<int>(r.tests.size());
        failures += f;
        errors += e;
        suites << "  <testsuite name=\"" << xmlText(r.id) << "\" tests=\"" << r.tests.size() << "\" failures=\""
               << f << "\" errors=\"" << e << "\" time=\"" << r.seconds << "\">\n"
               << "    <properties><property name=\"score\" value=\"" << points(r.score) << "/"
               << points(r.maxScore) << "\"/><property name=\"status\" value=\"" << xmlText(r.status)
               << "\"/></properties>\n"
               << cases.str() << "  </testsuite>\n";
    }
    std::ostringstream out;
    out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"simlab " << xmlText(assignment.id)
        << "\" tests=\"" << tests << "\" failures=\"" << failures << "\" errors=\"" << errors << "\">\n"
        << suites.str() << "</testsuites>\n";
    return out.str();
}

std::string feedbackMarkdown(const Assignment& assignment, const StudentRecord& r, const std::vector<ManualItem>& manual,
                             const std::vector<std::string>& attached) {
    std::ostringstream out;
    out << "# " << markdownText(assignment.title) << ": " << markdownText(r.id) << "\n\n";
    out << "**Score: " << points(r.score) << "/" << points(r.maxScore) << "**";
    if (r.status != "graded") out << " (" << r.status << ")";
    out << "\n\n";
    if (!r.note.empty()) out << markdownText(r.note) << ".\n\n";
    const std::string file = r.file.empty() ? assignment.source : r.file;
    // A command to copy: in code when the file's name is plain, else as escaped text.
    const bool plain = std::all_of(file.begin(), file.end(), [](unsigned char c) {
        return std::isalnum(c) || c == '.' || c == '_' || c == '-' || c == '/' || c == '+';
    });
    auto command = [&](const std::string& rest) {
        const std::string text = "simlab check " + assignment.id + " " + file + rest;
        return plain ? "`" + text + "`" : markdownText(text);
    };
    if (!r.compiler.empty()) {
        // An indented block: shown as the compiler wrote it (escaped), and nothing in it can end the block.
        const char* title = r.status == "did not compile" ? "The compiler's message:"
                            : r.status == "did not link"  ? "The linker's message:"
                            : r.status == "forbidden code" ? "Why the file was refused:"
                                                           : "The compiler's warnings:";
        out << title << "\n\n";
        std::istringstream lines(printable(r.compiler, true));
        for (std::string line; std::getline(lines, line);) out << "    " << line << "\n";
        out << "\n";
    }
    out << "| points | outcome | test |\n| ---: | --- | --- |\n";
    for (const TestResult& t : r.tests) {
        out << "| " << points(t.score) << "/" << points(t.maxScore) << " | " << outcomeName(t.outcome) << " | "
            << markdownText(t.name) << " |\n";
    }
    out << "\n";
    for (const TestResult& t : r.tests) {
        if (t.outcome == Outcome::Passed && t.reason.empty()) continue;
        out << "## " << markdownText(t.name) << "\n\n" << points(t.score) << "/" << points(t.maxScore) << ", "
            << outcomeName(t.outcome);
        if (t.visibility == "hidden") {
            out << ". (A hidden test: your instructor has the details.)\n\n";
            continue;
        }
        out << (t.reason.empty() ? "" : ": " + markdownText(t.reason)) << "\n\n";
        for (const std::string& line : t.feedback) out << "- " << markdownText(line) << "\n";
        if (!t.feedback.empty()) out << "\n";
        if (t.outcome != Outcome::Passed && t.visibility == "visible") {
            out << "Reproduce: " << command(" --test \"" + t.name + "\"") << "\n\n";
        }
    }
    if (!attached.empty()) {
        out << "Drawn from your model, beside this file:";
        for (const std::string& name : attached) out << " " << markdownText(name);
        out << "\n\n";
    }
    if (!manual.empty()) {
        double pending = 0;
        for (const ManualItem& m : manual) pending += m.points;
        out << "Graded by hand, pending (" << points(pending) << " points):\n\n";
        for (const ManualItem& m : manual) out << "- " << markdownText(m.name) << " (" << points(m.points) << ")\n";
        out << "\n";
    }
    out << "Check your file on the visible tests with " << command("") << ".\n";
    return out.str();
}

}  // namespace simlab::engine
