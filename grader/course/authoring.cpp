#include "simlab/course/authoring.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <toml++/toml.h>

#include "simlab/build/build.h"
#include "simlab/build/lab.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/common/parallel.h"
#include "simlab/common/text.h"
#include "simlab/course/batch.h"
#include "simlab/course/corpus.h"
#include "simlab/course/package.h"
#include "simlab/grading/report.h"
#include "simlab/isolation/process.h"
#include "simlab/rubric/rubric.h"

namespace simlab::engine {

namespace fs = std::filesystem;

namespace {

constexpr const char* kTemplateId = "mylab";
constexpr const char* kTemplateName = "MyLab";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
        text.replace(at, from.size(), to);
    }
    return text;
}

// "block_spring" -> "BlockSpring"
std::string camelCase(const std::string& id) {
    std::string out;
    bool upper = true;
    for (const char c : id) {
        if (c == '_' || c == '-') {
            upper = true;
        } else {
            out += upper ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
            upper = false;
        }
    }
    return out;
}

// A submission folder holding `file` as the assignment's source, beside the rubric's extra files found next to it.
GradeReport gradeFile(const Manifest& manifest, const Assignment& lab, const Rubric& rubric, const std::string& file,
                      const VerifyOptions& o, const std::optional<Limits>& limits = std::nullopt) {
    TempDir dir("simlab-verify-");
    const std::string student = dir.path() + "/student";
    fs::create_directories(student);
    fs::copy_file(file, student + "/" + lab.source);
    for (const std::string& extra : rubric.extraFiles) {
        const fs::path beside = fs::path(file).parent_path() / extra;
        if (fs::exists(beside)) fs::copy_file(beside, student + "/" + extra);
    }
    GradeOptions options;
    options.includeHidden = true;
    options.judges = o.judges;
    options.limits = limits;
    return gradeFolder(Builder(manifest), lab, rubric, student, false, false, options);
}

GradeReport gradeCase(const Manifest& manifest, const Assignment& lab, const Rubric& rubric, const CorpusCase& c,
                      const VerifyOptions& o, const std::optional<Limits>& limits = std::nullopt) {
    TempDir dir("simlab-verify-");
    writeCorpusCase(c, dir.path() + "/student", dir.path());
    GradeOptions options;
    options.includeHidden = true;
    options.judges = o.judges;
    options.limits = limits;
    return gradeFolder(Builder(manifest), lab, rubric, dir.path() + "/student", false, false, options);
}

// What a report shows: its text, and every test's reason (a hidden test's too, as an instructor reads it), alone
// and after its outcome as results.json's output gives it, and further lines (the feedback's).
std::string shown(const GradeReport& r) {
    std::string text = renderText(r);
    for (const TestResult& t : r.tests) {
        if (!t.reason.empty()) {
            text += t.name + ": " + t.reason + "\n";
            text += outcomeName(t.outcome) + ": " + t.reason + "\n";  // as the test's output in results.json has it
        }
        for (const std::string& line : t.feedback) text += line + "\n";
        if (t.figure) text += t.name + ": " + std::to_string(*t.figure) + " " + t.unit + "\n";
    }
    return text;
}

std::string scoreOf(const GradeReport& r) { return points(r.score()) + "/" + points(r.maxScore()); }

bool timedOut(const GradeReport& r) {
    return std::any_of(r.tests.begin(), r.tests.end(),
                       [](const TestResult& t) { return t.outcome == Outcome::TimedOut; });
}

// The tests whose outcome differs between two gradings of one submission.
std::vector<std::string> flipped(const GradeReport& a, const GradeReport& b) {
    std::vector<std::string> out;
    for (const TestResult& t : a.tests) {
        for (const TestResult& u : b.tests) {
            if (t.name == u.name && t.outcome != u.outcome) {
                out.push_back("'" + t.name + "' " + outcomeName(t.outcome) + " at 1x, " + outcomeName(u.outcome) +
                              " at 2x");
            }
        }
    }
    return out;
}

}  // namespace

int writeLabSkeleton(const Manifest& manifest, const std::string& name, const std::string& dir) {
    if (!std::regex_match(name, std::regex("[a-z][a-z0-9_]{0,39}"))) {
        throw UsageError(
            "a lab's name is its id and its C++ namespace: a lowercase letter, then up to 39 lowercase "
            "letters, digits or '_' (got '" +
            printable(name) + "')");
    }
    const fs::path from = fs::path(manifest.sourceDir) / "examples/template";
    if (!fs::is_directory(from)) throw UsageError("this simlab has no lab template (" + from.string() + ")");
    std::error_code error;
    if (fs::exists(dir, error) && !fs::is_empty(dir, error)) {
        throw UsageError("'" + printable(dir) + "' exists and is not empty: name a new folder");
    }
    const std::string Name = camelCase(name);
    int files = 0;
    for (auto it = fs::recursive_directory_iterator(from); it != fs::recursive_directory_iterator(); ++it) {
        if (!it->is_regular_file()) continue;
        const std::string relative = it->path().lexically_relative(from).generic_string();
        const fs::path target = fs::path(dir) / replaced(replaced(relative, kTemplateName, Name), kTemplateId, name);
        fs::create_directories(target.parent_path());
        writeFileAtomically(target.string(),
                            replaced(replaced(readFile(it->path().string()), kTemplateName, Name), kTemplateId, name));
        ++files;
    }
    return files;
}

namespace {

// The checks of verifyLab, in order, each telling its verdicts as it knows them.
struct Verifier {
    const Manifest& manifest;
    const Assignment& lab;
    const Rubric& rubric;
    const VerifyOptions& o;
    std::function<void(const std::string&, const std::string&)> say;
    std::optional<GradeReport> reference, starter;
    std::vector<std::string> cases;
    std::vector<std::pair<CorpusCase, GradeReport>> timedOutCases;

    // The reference: every point of every test.
    void checkReference() {
        if (lab.solution.empty() || !fs::exists(lab.solution)) {
            say("FAIL", "reference: the lab has no solution (SOLUTION in its CMakeLists.txt)");
        } else {
            reference = gradeFile(manifest, lab, rubric, lab.solution, o);
            std::vector<std::string> short_;
            for (const TestResult& t : reference->tests) {
                if (t.outcome != Outcome::Passed || t.credit < 1)
                    short_.push_back("'" + t.name + "' " + outcomeName(t.outcome) + ": " + t.reason);
            }
            if (reference->status != SubmissionStatus::Graded || !reference->build.ok) {
                say("FAIL", "reference: " + statusName(reference->status) +
                                (reference->build.ok
                                     ? ""
                                     : ", it does not build: " + isolation::firstLines(reference->build.log, 1)));
            } else if (short_.empty() && reference->score() == reference->maxScore()) {
                say("ok", "reference: " + scoreOf(*reference) + ", every one of its " +
                              std::to_string(reference->tests.size()) + " tests in full");
            } else {
                std::string list;
                for (const std::string& s : short_) list += (list.empty() ? "" : "; ") + s;
                say("FAIL", "reference: " + scoreOf(*reference) + ", short on " + list);
            }
        }
    }

    // The starter: at most a share.
    void checkStarter() {
        starter = gradeFile(manifest, lab, rubric, lab.starter, o);
        const double share = starter->maxScore() > 0 ? starter->score() / starter->maxScore() : 0;
        say(share <= o.starterShare ? "ok" : "FAIL",
            "starter: " + scoreOf(*starter) + (share <= o.starterShare ? ", at most " : ", more than ") +
                points(100 * o.starterShare) + " % of the points" +
                (starter->build.ok ? "" : " (it does not build: a starter must compile and fail at its TODOs)"));
    }

    // The corpus: each case its score and outcomes.
    void checkCorpus() {
        std::error_code error;
        if (fs::is_directory(lab.corpus, error)) {
            for (const auto& entry : fs::directory_iterator(lab.corpus)) {
                if (entry.path().extension() == ".toml") cases.push_back(entry.path().string());
            }
        }
        std::sort(cases.begin(), cases.end());
        if (cases.empty())
            say("warn", "corpus: no cases (corpus/*.toml): add the submissions you expect, with their scores");
        // Graded as a class is, o.judges students at a time (each with one judge), told in the cases' order.
        struct Graded {
            std::optional<CorpusCase> c;
            std::optional<GradeReport> report;
            std::string error;
        };
        std::vector<Graded> graded(cases.size());
        VerifyOptions one = o;
        one.judges = 1;
        const std::size_t workers = std::min<std::size_t>(cases.size(), std::max(1, o.judges));
        forEachInParallel(cases.size(), static_cast<int>(workers), [&](std::size_t i) {
            try {
                graded[i].c = loadCorpusCase(lab, rubric, cases[i]);
                graded[i].report = gradeCase(manifest, lab, rubric, *graded[i].c, workers > 1 ? one : o);
            } catch (const std::exception& e) {
                graded[i].error = e.what();
            }
        });
        for (std::size_t i = 0; i < cases.size(); ++i) {
            const std::string name = fs::path(cases[i]).stem().string();
            if (!graded[i].report) {
                say("FAIL", "corpus " + name + ": " + graded[i].error);
                continue;
            }
            const CorpusCase& c = *graded[i].c;
            const GradeReport& report = *graded[i].report;
            const std::vector<std::string> mismatches =
                compareWithCase(c, report.tests, report.score(), report.status, shown(report));
            std::string list;
            for (const std::string& m : mismatches) list += (list.empty() ? "" : "; ") + m;
            say(mismatches.empty() ? "ok" : "FAIL",
                "corpus " + name + ": " + scoreOf(report) + (mismatches.empty() ? " as expected" : ": " + list));
            if (timedOut(report)) timedOutCases.emplace_back(c, report);
        }
    }

    // The extremes: each names the outcome the lab promises.
    void checkExtremes() {
        const std::string extremes = lab.dir + "/study/extremes.toml";
        if (!fs::exists(extremes)) {
            say("skip", "extremes: none declared (study/extremes.toml)");
        } else {
            try {
                const toml::table t = toml::parse_file(extremes);
                int count = 0, open = 0;
                std::vector<std::string> unnamed;
                if (const toml::array* list = t["case"].as_array()) {
                    for (const toml::node& node : *list) {
                        ++count;
                        const toml::table* c = node.as_table();
                        const std::string expect = c ? (*c)["expect"].value_or(std::string()) : "";
                        if (c && !c->contains("expect")) {
                            ++open;  // any outcome it names will do: a silent or crashed run still fails the study
                        } else if (expect != "accurate" && expect != "inaccurate" && expect != "rejected" && expect != "trouble") {
                            unnamed.push_back(c ? (*c)["name"].value_or(std::string("case ") + std::to_string(count))
                                                : std::to_string(count));
                        }
                    }
                }
                if (unnamed.empty()) {
                    say("ok", open ? "extremes: " + std::to_string(count) + " cases, " + std::to_string(count - open) +
                                         " promising an outcome and " + std::to_string(open) + " any named one"
                                   : "extremes: each of " + std::to_string(count) + " cases names its outcome");
                } else {
                    say("FAIL", "extremes: " + std::to_string(unnamed.size()) +
                                    " cases name no outcome (expect = accurate, "
                                    "inaccurate, rejected or trouble), the first '" +
                                    unnamed.front() + "'");
                }
            } catch (const toml::parse_error& e) {
                say("FAIL", "extremes: " + extremes + ": " + std::string(e.description()));
            }
        }
    }

    // A trade the rubric grades: its fronts measured.
    void checkTrade() {
        std::error_code error;
        const bool gradesTrade = std::any_of(rubric.tests.begin(), rubric.tests.end(),
                                             [](const RubricTest& t) { return t.params.count("full_within") > 0; });
        std::vector<std::string> trades;
        if (fs::is_directory(lab.dir + "/grading", error)) {
            for (const auto& entry : fs::directory_iterator(lab.dir + "/grading")) {
                const std::string name = entry.path().filename().string();
                if (name.rfind("trade-", 0) == 0 && entry.path().extension() == ".json")
                    trades.push_back(entry.path().string());
            }
        }
        if (!gradesTrade) {
            say("skip", "trade: the rubric grades no trade (no test with full_within)");
        } else if (trades.empty()) {
            say("FAIL",
                "trade: the rubric grades a trade, but grading/ has no trade-*.json with its fronts (simlab study "
                "trade DIR --fronts measures them)");
        } else {
            for (const std::string& path : trades) {
                try {
                    const nlohmann::json j = nlohmann::json::parse(readFile(path));
                    std::size_t scenes = 0, measured = 0;
                    for (const nlohmann::json& scene : j.at("scenes")) {
                        ++scenes;
                        if (scene.contains("front") && !scene.at("front").empty()) ++measured;
                    }
                    say(scenes > 0 && measured == scenes ? "ok" : "FAIL",
                        "trade " + fs::path(path).filename().string() + ": " + std::to_string(measured) + " of " +
                            std::to_string(scenes) + " scenes have a measured front");
                } catch (const std::exception& e) {
                    say("FAIL", "trade " + fs::path(path).filename().string() + ": " + e.what());
                }
            }
        }
    }

    // The students' copy: no hidden test, solution or corpus file, by name or by content.
    void checkHidden() {
        {
            TempDir dir("simlab-verify-");
            writeStudentLab(lab, dir.path());
            std::map<std::string, std::string> secret;  // content -> what it is
            for (const std::string& h : lab.hiddenTests) {
                if (fs::is_regular_file(h)) secret[readFile(h)] = fs::path(h).lexically_relative(lab.dir).string();
            }
            if (!lab.solution.empty() && fs::exists(lab.solution)) secret[readFile(lab.solution)] = "the solution";
            for (const std::string& c : cases) secret[readFile(c)] = fs::path(c).lexically_relative(lab.dir).string();
            std::vector<std::string> found;
            int files = 0;
            for (auto it = fs::recursive_directory_iterator(dir.path()); it != fs::recursive_directory_iterator();
                 ++it) {
                if (!it->is_regular_file()) continue;
                ++files;
                const std::string relative = it->path().lexically_relative(dir.path()).string();
                const auto s = secret.find(readFile(it->path().string()));
                if (s != secret.end()) found.push_back(relative + " (" + s->second + ")");
                if (relative.find("/corpus/") != std::string::npos || relative.find("hidden") != std::string::npos) {
                    found.push_back(relative);
                }
            }
            say(found.empty() ? "ok" : "FAIL",
                found.empty() ? "hidden: the students' copy of the lab (" + std::to_string(files) +
                                    " files) holds no hidden test, solution or corpus case"
                              : "hidden: the students' copy of the lab holds " + found.front() +
                                    (found.size() > 1 ? " and " + std::to_string(found.size() - 1) + " more" : ""));
        }
    }

    // The time limit: a margin over the reference's slowest test, and no verdict that a doubled limit changes.
    void checkTimeLimit() {
        if (reference) {
            double slowest = 0;
            std::string slowestTest;
            for (const TestResult& t : reference->tests) {
                if (t.cpuSeconds > slowest) {
                    slowest = t.cpuSeconds;
                    slowestTest = t.name;
                }
            }
            const double limit = rubric.limits.cpuSeconds;
            const double suggested = std::max(1.0, std::ceil(5 * slowest));
            std::ostringstream line;
            line.precision(3);
            line << "time limit: cpu_seconds = " << limit << "; the reference's slowest test ('" << slowestTest
                 << "') used " << slowest << " s of CPU";
            if (slowest * 2 > limit) {
                line << ", less than half the limit: set cpu_seconds = " << suggested << " ([limits] in the rubric)";
                say("FAIL", line.str());
            } else {
                line << " (" << (slowest > 0 ? limit / slowest : 0) << " x; 5 x it, at least 1 s, would be "
                     << suggested << ")";
                say("ok", line.str());
            }
            Limits doubled = rubric.limits;
            doubled.cpuSeconds *= 2;
            doubled.wallSeconds *= 2;
            const auto twice = [&](const std::string& what, const GradeReport& once, const GradeReport& again) {
                const std::vector<std::string> changes = flipped(once, again);
                if (!changes.empty())
                    say("warn",
                        "time limit: " + what + "'s verdict changes between 1x and 2x the limit: " + changes.front());
            };
            if (starter && timedOut(*starter))
                twice("the starter", *starter, gradeFile(manifest, lab, rubric, lab.starter, o, doubled));
            for (const auto& [c, report] : timedOutCases)
                twice("corpus " + c.name, report, gradeCase(manifest, lab, rubric, c, o, doubled));
        }
    }
};

}  // namespace

int verifyLab(const Manifest& manifest, const std::string& dir, const VerifyOptions& o,
              const std::function<void(const VerifyLine&)>& print) {
    int failures = 0;
    const auto say = [&](const std::string& status, const std::string& text) {
        if (status == "FAIL") ++failures;
        print({status, text});
    };
    const auto started = std::chrono::steady_clock::now();
    const Assignment* found = nullptr;
    try {
        found = &manifest.find(isLabFolder(dir) ? dir : "./" + dir);
    } catch (const std::exception& e) {
        say("FAIL", std::string("build: ") + e.what());
        return failures;
    }
    const Assignment& lab = *found;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    std::ostringstream built;
    built.precision(2);
    built << std::fixed << seconds;
    say("ok", "build: " + lab.id + " (" + lab.title + ") builds against simlab " + manifest.version + " (" +
                  built.str() + " s)");
    Rubric rubric;
    try {
        rubric = loadRubric(lab.rubric);
    } catch (const std::exception& e) {
        say("FAIL", std::string("rubric: ") + e.what());
        return failures;
    }
    Verifier v{manifest, lab, rubric, o, say, {}, {}, {}, {}};
    v.checkReference();
    v.checkStarter();
    v.checkCorpus();
    v.checkExtremes();
    v.checkTrade();
    v.checkHidden();
    v.checkTimeLimit();
    return failures;
}

}  // namespace simlab::engine
