#include "simlab/engine/batch.h"

#include <algorithm>
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

namespace fs = std::filesystem;

namespace simlab::engine {

namespace {

bool isCppFile(const fs::path& p) {
    const std::string e = p.extension().string();
    return e == ".cpp" || e == ".cc" || e == ".cxx" || e == ".c++" || e == ".C";
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

// --- Records ---------------------------------------------------------------------------------------------------

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
            {"seconds", r.seconds}, {"tests", tests}};
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
    r.tests = report.tests;
    return r;
}

// --- CSV ----------------------------------------------------------------------------------------------------------

std::string csvField(const std::string& s) {
    if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
    std::string quoted = "\"";
    for (char c : s) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

std::string gradebookCsv(const Rubric& rubric, const std::vector<StudentRecord>& records) {
    std::ostringstream out;
    out << "student,score,max,status";
    for (const RubricTest& t : rubric.tests) out << "," << csvField(t.name);
    out << "\n";
    for (const StudentRecord& r : records) {
        out << csvField(r.id) << "," << points(r.score) << "," << points(r.maxScore) << "," << csvField(r.status);
        for (const RubricTest& t : rubric.tests) {
            const auto found = std::find_if(r.tests.begin(), r.tests.end(),
                                            [&](const TestResult& x) { return x.name == t.name; });
            out << "," << (found == r.tests.end() ? "" : points(found->score));
        }
        out << "\n";
    }
    return out.str();
}

// --- Text --------------------------------------------------------------------------------------------------------

std::string xmlEscape(const std::string& s) {
    std::string out;
    for (unsigned char c : s) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&apos;"; break;
            default:
                if (c < 0x20 && c != '\n' && c != '\t') out += ' ';  // not allowed in XML 1.0
                else out += static_cast<char>(c);
        }
    }
    return out;
}

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

Submission findSubmission(const std::string& folder, const std::string& expected, bool recursive) {
    std::vector<fs::path> cpp;
    std::error_code error;
    auto consider = [&](const fs::directory_entry& e) {
        if (e.is_regular_file(error) && isCppFile(e.path())) cpp.push_back(e.path());
    };
    if (recursive) {
        for (auto it = fs::recursive_directory_iterator(folder, fs::directory_options::skip_permission_denied, error);
             it != fs::recursive_directory_iterator(); it.increment(error)) {
            consider(*it);
        }
    } else {
        for (const fs::directory_entry& e : fs::directory_iterator(folder, error)) consider(e);
    }
    std::sort(cpp.begin(), cpp.end());
    const auto relative = [&](const fs::path& p) { return fs::relative(p, folder, error).string(); };
    for (const fs::path& p : cpp) {
        if (p.filename() == expected) return {p.string(), "graded", ""};
    }
    for (const fs::path& p : cpp) {
        if (lower(p.filename().string()) == lower(expected)) {
            return {p.string(), "misnamed file", "graded " + relative(p) + "; expected " + expected};
        }
    }
    if (cpp.size() == 1) return {cpp[0].string(), "misnamed file", "graded " + relative(cpp[0]) + "; expected " + expected};
    if (cpp.empty()) return {"", "missing file", "no " + expected + " (no C++ file at all)"};
    std::string found;
    for (const fs::path& p : cpp) found += (found.empty() ? "" : ", ") + relative(p);
    return {"", "missing file", "no " + expected + " (found " + found + ")"};
}

GradeReport gradeFolder(const Builder& builder, const Assignment& assignment, const Rubric& rubric,
                        const std::string& folder, bool recursive, const GradeOptions& options) {
    const Submission found = findSubmission(folder, rubric.submission, recursive);
    if (found.file.empty()) return missingReport(assignment, rubric, found.note, options.includeHidden);
    GradeReport report = gradeSource(builder, assignment, rubric, found.file, options);
    if (report.status == "graded") report.status = found.status;
    report.note = found.note;
    return report;
}

std::vector<StudentRecord> gradeClass(const Builder& builder, const Assignment& assignment, const Rubric& rubric,
                                      const std::string& submissionsDir, const std::string& outDir,
                                      const ClassOptions& options,
                                      const std::function<void(const ClassProgress&)>& onProgress) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::string> ids;
    for (const fs::directory_entry& e : fs::directory_iterator(submissionsDir)) {
        if (e.is_directory() && e.path().filename().string()[0] != '.') ids.push_back(e.path().filename().string());
    }
    std::sort(ids.begin(), ids.end());
    for (const std::string& id : options.only) {
        if (!std::binary_search(ids.begin(), ids.end(), id)) {
            throw UsageError("no student '" + id + "' in " + submissionsDir);
        }
    }
    fs::create_directories(outDir + "/students");

    // What every grade depends on besides the student's file.
    Hash base;
    base.add(builder.graderKey(assignment)).add(readFile(rubric.path));
    const Limits limits = options.grade.limits.value_or(rubric.limits);
    for (double v : {limits.wallSeconds, limits.cpuSeconds, double(limits.memoryMiB), double(limits.outputKiB),
                     double(limits.fileMiB), double(limits.processes)}) {
        base.add(std::to_string(v));
    }
    base.add(options.grade.includeHidden ? "all tests" : "visible tests");

    std::map<std::string, StudentRecord> records;
    struct Pending {
        std::string id, key;
    };
    std::vector<Pending> pending;
    int reused = 0;
    for (const std::string& id : ids) {
        const std::string folder = submissionsDir + "/" + id;
        const Submission found = findSubmission(folder, rubric.submission, false);
        Hash key = base;
        key.add(found.status).add(found.file.empty() ? found.note : fs::path(found.file).filename().string());
        if (!found.file.empty()) {
            key.add(readFile(found.file));
            for (const std::string& name : rubric.extraFiles) {
                const fs::path extra = fs::path(found.file).parent_path() / name;
                key.add(fs::is_regular_file(extra) ? readFile(extra.string()) : "(none)");
            }
        }
        const std::string recordPath = outDir + "/students/" + id + "/record.json";
        const bool wanted = options.only.empty() || std::count(options.only.begin(), options.only.end(), id);
        std::optional<StudentRecord> kept;
        if (fs::exists(recordPath)) {
            kept = fromJson(nlohmann::json::parse(readFile(recordPath), nullptr, false));
        }
        if (kept && (!wanted || (options.only.empty() && kept->key == key.hex()))) {
            records[id] = *kept;
            reused += wanted;
        } else if (wanted) {
            pending.push_back({id, key.hex()});
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
    std::exception_ptr failure;
    const int alreadyDone = progress.done;
    auto worker = [&](int slot) {
        for (std::size_t i = next++; i < pending.size() && !stop; i = next++) {
            const Pending& p = pending[i];
            const std::string folder = submissionsDir + "/" + p.id;
            const std::string dir = outDir + "/students/" + p.id;
            GradeOptions grade = options.grade;
            grade.slot = slot;
            try {
                const GradeReport report = gradeFolder(builder, assignment, rubric, folder, false, grade);
                const std::string file =
                    report.source.empty() ? "" : fs::relative(report.source, folder).string();
                StudentRecord record = recordOf(p.id, p.key, report, file);
                fs::create_directories(dir);
                writeFileAtomically(dir + "/results.json", toGradescope(report).dump(2) + "\n");
                writeFileAtomically(dir + "/feedback.md", feedbackMarkdown(assignment, record));
                std::string output;
                for (const TestResult& t : report.tests) {
                    output += "=== " + t.name + " (" + outcomeName(t.outcome) + ")\n" + t.output + "\n";
                }
                writeFileAtomically(dir + "/output.txt", output);
                writeFileAtomically(dir + "/record.json", toJson(record).dump(2) + "\n");  // last: the commit

                std::lock_guard<std::mutex> guard(lock);
                records[p.id] = record;
                publish();
                ++progress.done;
                progress.elapsed =
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                const double graded = progress.done - alreadyDone;
                progress.eta = progress.elapsed / graded * (progress.total - progress.done);
                progress.last = &records[p.id];
                progress.lastReused = false;
                if (onProgress) onProgress(progress);
            } catch (const Interrupted&) {
                stop = true;
            } catch (...) {
                std::lock_guard<std::mutex> guard(lock);
                if (!failure) failure = std::current_exception();
                stop = true;
            }
        }
    };
    std::vector<std::thread> workers;
    const int jobs = std::max(1, std::min<int>(options.jobs, static_cast<int>(pending.size())));
    for (int slot = 0; slot < jobs; ++slot) workers.emplace_back(worker, slot);
    for (std::thread& w : workers) w.join();
    if (failure) std::rethrow_exception(failure);

    std::vector<StudentRecord> sorted;
    for (const std::string& id : ids) {
        if (records.count(id)) sorted.push_back(records[id]);
    }
    writeFileAtomically(outDir + "/summary.csv", summaryCsv(rubric, sorted));
    if (childrenInterrupted()) throw Interrupted();
    return sorted;
}

std::string summaryCsv(const Rubric& rubric, const std::vector<StudentRecord>& records) {
    std::ostringstream out;
    out << "test,visibility,points,graded,passed,pass_rate,figure,median,min,max\n";
    for (const TestSummary& s : summarize(rubric, records)) {
        out << csvField(s.test->name) << "," << s.test->visibility << "," << points(s.test->points) << ","
            << s.graded << "," << s.passed << "," << (s.graded ? number(double(s.passed) / s.graded) : "") << ","
            << csvField(s.unit) << "," << number(s.figures.median) << "," << number(s.figures.min) << ","
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
            cases << "    <testcase classname=\"" << xmlEscape(assignment.id + "." + r.id) << "\" name=\""
                  << xmlEscape(t.name) << "\" time=\"" << t.seconds << "\"";
            if (t.outcome == Outcome::Passed) {
                cases << "/>\n";
                continue;
            }
            const bool failed = t.outcome == Outcome::Failed;
            (failed ? f : e)++;
            const std::string tag = failed ? "failure" : "error";
            const std::string message = outcomeName(t.outcome) + (t.reason.empty() ? "" : ": " + t.reason);
            cases << ">\n      <" << tag << " type=\"" << xmlEscape(outcomeName(t.outcome)) << "\" message=\""
                  << xmlEscape(message) << "\">" << xmlEscape(message) << "</" << tag << ">\n    </testcase>\n";
        }
        tests += static_cast<int>(r.tests.size());
        failures += f;
        errors += e;
        suites << "  <testsuite name=\"" << xmlEscape(r.id) << "\" tests=\"" << r.tests.size() << "\" failures=\""
               << f << "\" errors=\"" << e << "\" time=\"" << r.seconds << "\">\n"
               << "    <properties><property name=\"score\" value=\"" << points(r.score) << "/"
               << points(r.maxScore) << "\"/><property name=\"status\" value=\"" << xmlEscape(r.status)
               << "\"/></properties>\n"
               << cases.str() << "  </testsuite>\n";
    }
    std::ostringstream out;
    out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"simlab " << xmlEscape(assignment.id)
        << "\" tests=\"" << tests << "\" failures=\"" << failures << "\" errors=\"" << errors << "\">\n"
        << suites.str() << "</testsuites>\n";
    return out.str();
}

std::string feedbackMarkdown(const Assignment& assignment, const StudentRecord& r) {
    std::ostringstream out;
    out << "# " << assignment.title << ": " << r.id << "\n\n";
    out << "**Score: " << points(r.score) << "/" << points(r.maxScore) << "**";
    if (r.status != "graded") out << " (" << r.status << ")";
    out << "\n\n";
    if (!r.note.empty()) out << r.note << ".\n\n";
    const std::string file = r.file.empty() ? assignment.source : r.file;
    out << "| points | outcome | test |\n| ---: | --- | --- |\n";
    for (const TestResult& t : r.tests) {
        out << "| " << points(t.score) << "/" << points(t.maxScore) << " | " << outcomeName(t.outcome) << " | "
            << t.name << " |\n";
    }
    out << "\n";
    for (const TestResult& t : r.tests) {
        if (t.outcome == Outcome::Passed && t.reason.empty()) continue;
        out << "## " << t.name << "\n\n" << points(t.score) << "/" << points(t.maxScore) << ", "
            << outcomeName(t.outcome);
        if (t.visibility == "hidden") {
            out << ". (A hidden test: your instructor has the details.)\n\n";
            continue;
        }
        out << (t.reason.empty() ? "" : ": " + t.reason) << "\n\n";
        for (const std::string& line : t.feedback) out << "- " << line << "\n";
        if (!t.feedback.empty()) out << "\n";
        if (t.outcome != Outcome::Passed && t.visibility == "visible") {
            out << "Reproduce: `simlab check " << assignment.id << " " << file << " --test \"" << t.name
                << "\"`\n\n";
        }
    }
    out << "Check your file on the visible tests with `simlab check " << assignment.id << " " << file << "`.\n";
    return out.str();
}

}  // namespace simlab::engine
