// `simlab study trade LAB`: the work-precision study of a lab's reference solution. The lab's study program
// (simlab/study.h) measures every point and prints it as a JSON line; this command writes them to trade.csv, draws
// digits against evaluations and against time with gnuplot, and prints the cheapest setting for each number of
// digits and the Pareto front.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cerrno>
#include <condition_variable>
#include <cmath>
#include <cstring>
#include <sys/wait.h>
#include <unistd.h>
#include <thread>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.h"
#include "simlab/build/build.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/build/manifest.h"
#include "simlab/isolation/process.h"
#include "simlab/cli_checks.h"
#include "simlab/common/text.h"
#include "simlab/trade_question.h"
#include "simlab/work_precision.h"
#include <optional>
#include <tuple>
#include <regex>
#include <toml++/toml.h>

namespace simlab::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct StudyOptions {
    bool minimal = false;  ///< `study minimal` rather than `study trade`
    std::string lab;
    std::string output = "study";
    bool quick = false;
    double maxEvaluations = 0;  // 0: the study program's default
    double cap = 0;   // 0: the study program's default
    int repeats = 0;  // 0: the study program's default
    int jobs = 2;     // labs studied at once
    bool plots = true;
    std::string file;  ///< a student file to study instead of the reference solution
    bool question = false;  ///< the trade question's scene (grading/trade-question.json), as the grader measures it
    bool fronts = false;    ///< measure the fronts of the question's data files and write them there
    std::string shard;      ///< "I/N": measure share I of N of the (lab, integrator) parts into OUTPUT/parts
    bool assemble = false;  ///< trade.csv and the plots from OUTPUT/parts, measuring only the parts missing
};

/// A subject's header line and its points, as the study program printed them (for `study minimal`, its rows).
struct SubjectRun {
    json subject;
    std::vector<json> points;
    std::vector<json> minimal;
};

const char* const kIntegrators[] = {"RungeKuttaMerson", "RungeKutta3", "RungeKutta2",   "RungeKuttaFeldberg",
                                    "ExplicitEuler",    "SemiExplicitEuler", "SemiExplicitEuler2", "Verlet",
                                    "CPodes"};

/// Runs `work` on `count` threads at once (at least one), and waits for them all; the first exception one of them
/// threw is thrown here, once they have ended.
void inWorkers(int count, const std::function<void()>& work) {
    std::mutex lock;
    std::exception_ptr failure;
    std::vector<std::thread> workers;
    for (int k = 0; k < std::max(1, count); ++k) {
        workers.emplace_back([&] {
            try {
                work();
            } catch (...) {
                std::lock_guard<std::mutex> guard(lock);
                if (!failure) failure = std::current_exception();
            }
        });
    }
    for (std::thread& w : workers) w.join();
    if (failure) std::rethrow_exception(failure);
}

/// A study program's line as simlab takes it - the type ("subject", "point", "minimal"), and for each field the
/// type it must have: what a program built from a student's file prints is data, never trusted. A subject's name
/// is a plain word (letters, digits, '.', '_', '-'), since it names files and plots; texts are made printable and
/// cut at 300 bytes; numbers are finite or null; an integrator, a mode and a status are among the known ones.
/// Empty, with `why` saying what is wrong, for a line no study prints.
std::optional<json> wellFormedLine(const json& line, std::string& why) {
    auto fail = [&](const std::string& what) -> std::optional<json> {
        why = what;
        return std::nullopt;
    };
    if (!line.is_object() || !line.contains("type") || !line["type"].is_string()) return fail("a line without a type");
    const std::string type = line["type"];
    if (type != "subject" && type != "point" && type != "minimal") return fail("a line of type '" + engine::printable(type) + "'");
    json out = {{"type", type}};
    auto textField = [&](const char* key) {
        const std::string value = line.contains(key) && line[key].is_string() ? line[key].get<std::string>() : "";
        out[key] = engine::printable(value.substr(0, 300));
    };
    auto numberField = [&](const char* key) {
        const bool finite = line.contains(key) && line[key].is_number() && std::isfinite(line[key].get<double>());
        out[key] = finite ? line[key] : json();
    };
    const std::string subject = line.contains("subject") && line["subject"].is_string() ? line["subject"].get<std::string>() : "";
    const bool plainWord = !subject.empty() && subject.size() <= 64 && subject[0] != '.' &&
                           std::all_of(subject.begin(), subject.end(), [](char c) {
                               return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
                           });
    if (!plainWord) return fail("a subject named '" + engine::printable(subject.substr(0, 80)) + "'");
    out["subject"] = subject;
    if (type == "subject") {
        for (const char* key : {"lab", "figure", "final_figure", "conserved", "reference"}) textField(key);
        for (const char* key : {"final_time", "reference_digits", "cap", "max_evaluations", "repeats", "starts", "points",
                                "sweeps"}) {
            numberField(key);
        }
        return out;
    }
    const std::string integrator = line.contains("integrator") && line["integrator"].is_string() ? line["integrator"].get<std::string>() : "";
    if (std::find(std::begin(kIntegrators), std::end(kIntegrators), integrator) == std::end(kIntegrators)) {
        return fail("an integrator named '" + engine::printable(integrator.substr(0, 80)) + "'");
    }
    out["integrator"] = integrator;
    const std::string mode = line.contains("mode") && line["mode"].is_string() ? line["mode"].get<std::string>() : "";
    if (mode != "accuracy" && mode != "fixed step") return fail("a mode named '" + engine::printable(mode.substr(0, 80)) + "'");
    out["mode"] = mode;
    const std::string status = line.contains("status") && line["status"].is_string() ? line["status"].get<std::string>() : "";
    static const char* const kStatuses[] = {"ok", "too costly", "failed", "blew up", "no error control"};
    if (std::find_if(std::begin(kStatuses), std::end(kStatuses), [&](const char* k) { return status == k; }) == std::end(kStatuses)) {
        return fail("a status '" + engine::printable(status.substr(0, 80)) + "'");
    }
    out["status"] = status;
    textField("message");
    for (const char* key : {"accuracy", "step", "reached", "final_digits", "worst_digits", "drift", "steps_taken",
                            "steps_attempted", "evaluations", "seconds", "repeats"}) {
        numberField(key);
    }
    if (type == "minimal") {
        textField("lab");
        textField("model");
        out["over_modelled"] = line.contains("over_modelled") && line["over_modelled"].is_boolean() && line["over_modelled"].get<bool>();
        numberField("dof");
        numberField("coordinates");
    }
    return out;
}

/// Held while a line goes to standard error: the study programs' lines and the progress come from several threads.
std::mutex stderrLock;

/// How far a study has come, on standard error at least every two seconds while it runs - "point n of N measured,
/// about S s left", the time left read from the pace so far - and once more when it ends.
class Progress {
public:
    using Clock = std::chrono::steady_clock;

    Progress() : began_(Clock::now()), ticker_([this] { tick(); }) {}
    ~Progress() { finish(false); }
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    /// The study's points in all; the lines begin once it is known.
    void setTotal(std::size_t total) { total_ = total; }
    void pointDone() { ++done_; }
    /// Stops the lines; a study that ended well says so in a last one.
    void finish(bool ended) {
        {
            std::lock_guard<std::mutex> guard(lock_);
            if (stopped_) return;
            stopped_ = true;
        }
        wake_.notify_all();
        ticker_.join();
        if (ended) say(true);
    }

private:
    void tick() {
        std::unique_lock<std::mutex> guard(lock_);
        while (!wake_.wait_for(guard, std::chrono::milliseconds(1500), [this] { return stopped_; })) say(false);
    }
    void say(bool ended) const {
        const std::size_t total = total_, done = std::min<std::size_t>(done_, total);
        if (total == 0) return;
        const double seconds = std::chrono::duration<double>(Clock::now() - began_).count();
        char line[160];
        if (ended) {
            std::snprintf(line, sizeof line, "  point %zu of %zu measured, in %.0f s\n", done, total, seconds);
        } else if (done == 0) {
            std::snprintf(line, sizeof line, "  point 0 of %zu measured\n", total);
        } else {
            const double left = std::max(1.0, seconds * static_cast<double>(total - done) / static_cast<double>(done));
            std::snprintf(line, sizeof line, "  point %zu of %zu measured, about %.0f s left\n", done, total, left);
        }
        std::lock_guard<std::mutex> guard(stderrLock);
        std::cerr << line << std::flush;
    }

    const Clock::time_point began_;
    std::atomic<std::size_t> total_{0}, done_{0};
    std::mutex lock_;
    std::condition_variable wake_;
    bool stopped_ = false;
    std::thread ticker_;
};

/// Runs a study program, handing each line it prints to `onLine` as it comes, made well formed (wellFormedLine; a
/// line that is not stops the study, saying what it was); what is not a JSON line (a progress line, an error) goes
/// to our standard error, printable. A student's study program runs in the sandbox, as a probe does
/// (its folder lent read-only, a scratch working directory, no network); the course's runs as a tool. Returns its
/// exit status (128 + N for signal N).
int runStudyProgram(const std::vector<std::string>& argv, bool sandboxed,
                    const std::function<void(const json&)>& onLine) {
    engine::TempDir scratch("simlab-study-run-");
    isolation::ProcessRequest request;
    request.argv = argv;
    request.env = isolation::childEnvironment({"LC_ALL=C", "SIMLAB_PROGRESS=1"});
    request.workDir = scratch.path();
    request.limits.cpuSeconds = 4 * 3600;  // a net: the points' evaluation caps bound the work
    request.limits.wallSeconds = 12 * 3600;
    request.limits.memoryMiB = 8192;
    request.limits.outputKiB = 1 << 20;
    request.limits.fileMiB = 64;
    request.limits.processes = 16;
    request.keepOutput = 0;
    std::string malformed;
    request.onOutputLine = [&](const std::string& line) {
        const json j = json::parse(line, nullptr, false);
        if (!j.is_discarded() && j.is_object()) {
            std::string why;
            if (const std::optional<json> taken = wellFormedLine(j, why)) onLine(*taken);
            else if (malformed.empty()) malformed = why;
        } else if (!line.empty()) {
            std::lock_guard<std::mutex> guard(stderrLock);
            std::cerr << engine::printable(line) << '\n';
        }
    };
    if (sandboxed) {
        // A student's file built into a study program: the students' system-call filter, as for a probe.
        request.isolate = true;
        request.studentCode = true;
        request.scratchWorkDir = true;
        request.readOnlyPaths = {fs::path(argv.front()).parent_path().string()};
    }
    const isolation::ProcessResult result = isolation::runProcess(request);
    if (!result.started) throw std::runtime_error("cannot run " + argv.front() + ": " + result.error);
    if (!malformed.empty()) {
        throw std::runtime_error(fs::path(argv.front()).filename().string() + " printed a line no study prints (" +
                                 malformed + "): the study stops");
    }
    if (result.cpuTimeout || result.wallTimeout) throw std::runtime_error(argv.front() + " ran past its time net");
    if (result.signal != 0) return 128 + result.signal;
    return result.exitCode;
}

/// The studies' programs and objects, built now where this tree's build leaves them out (SIMLAB_BUILD_STUDIES=OFF, or
/// a build configured before they were built by default): `cmake --build BUILD --target simlab_studies`, with the
/// build's lines on standard error.
void ensureStudiesBuilt(const engine::Manifest& m, const std::vector<const engine::Assignment*>& labs, bool ofAFile) {
    std::vector<std::string> needed;
    for (const engine::Assignment* a : labs) {
        if (ofAFile) needed.insert(needed.end(), a->studyObjects.begin(), a->studyObjects.end());
        else if (!a->studyProgramPath.empty()) needed.push_back(a->studyProgramPath);
    }
    if (ofAFile) needed.insert(needed.end(), m.studyLibraries.begin(), m.studyLibraries.end());
    if (std::all_of(needed.begin(), needed.end(), [](const std::string& p) { return fs::exists(p); })) return;
    if (m.installed) {
        throw engine::UsageError("this installation (" + engine::printable(m.prefix) + ") was made from a build without "
                                 "the studies: build them (cmake --build BUILD --target simlab_studies), then install");
    }
    if (m.studiesTarget.empty()) throw engine::UsageError("the studies are not built: run scripts/setup again");
    const std::string jobs = std::to_string(cores());
    const std::vector<std::string> argv = {m.cmake, "--build", m.buildDir, "--target", m.studiesTarget, "-j", jobs};
    std::cerr << "simlab study: building the studies first, once (" << m.cmake << " --build " << m.buildDir
              << " --target " << m.studiesTarget << "; about a minute)" << std::endl;
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error(std::string("cannot start cmake: ") + std::strerror(errno));
    if (pid == 0) {
        ::dup2(2, 1);  // the build's lines are progress, not the study's output
        std::vector<char*> args;
        for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
        args.push_back(nullptr);
        ::execvp(args[0], args.data());
        std::fprintf(stderr, "simlab study: cannot run %s: %s\n", args[0], std::strerror(errno));
        ::_exit(127);
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        throw std::runtime_error("building the studies failed (" + m.cmake + " --build " + m.buildDir +
                                 " --target " + m.studiesTarget + " says why)");
    }
}

std::string number(const json& value, const char* format = "%.6g") {
    if (!value.is_number()) return "";
    char text[32];
    std::snprintf(text, sizeof text, format, value.get<double>());
    return text;
}

std::string text(const json& value) { return value.is_string() ? value.get<std::string>() : std::string(); }

/// The one line a point's setting takes: "accuracy 1e-06" or "fixed step 0.004 s".
std::string setting(const json& p) {
    if (text(p["mode"]) == "accuracy") return "accuracy " + number(p["accuracy"], "%.0e");
    return "fixed step " + number(p["step"], "%.3g") + " s";
}

void writeCsv(const fs::path& path, const std::vector<SubjectRun>& runs) {
    std::ostringstream out;
    out << "lab,subject,integrator,mode,accuracy,step_s,status,reached_s,final_digits,worst_digits,drift,"
           "reference_digits,steps_taken,steps_attempted,evaluations,seconds,repeats,message\n";
    for (const SubjectRun& run : runs) {
        for (const json& p : run.points) {
            out << engine::csvCell(text(run.subject["lab"])) << ',' << engine::csvCell(text(p["subject"])) << ','
                << engine::csvCell(text(p["integrator"])) << ',' << engine::csvCell(text(p["mode"])) << ','
                << number(p["accuracy"]) << ',' << number(p["step"]) << ',' << engine::csvCell(text(p["status"]))
                << ',' << number(p["reached"]) << ',' << number(p["final_digits"], "%.2f") << ','
                << number(p["worst_digits"], "%.2f") << ',' << number(p["drift"], "%.3g") << ','
                << number(run.subject["reference_digits"], "%.2f") << ',' << number(p["steps_taken"], "%.0f") << ','
                << number(p["steps_attempted"], "%.0f") << ',' << number(p["evaluations"], "%.0f") << ','
                << number(p["seconds"], "%.6g") << ',' << number(p["repeats"], "%.0f") << ','
                << engine::csvCell(text(p["message"])) << '\n';
        }
    }
    engine::writeFileAtomically(path.string(), out.str());
}

/// Draws the subject's points from trade.csv: worst digits against evaluations and against time, one curve per
/// integrator (dashed: its fixed-step sweep), as PNG and SVG. Returns the files made, or says why none were.
std::vector<std::string> plot(const fs::path& dir, const std::string& name) {
    const std::string gnuplot = "/usr/bin/gnuplot";  // Debian's gnuplot-nox (scripts/install-deps)
    if (!fs::exists(gnuplot)) return {};
    // A subject's name is a plain word (wellFormedLine); quoted as gnuplot quotes (a ' doubled) all the same, and
    // never a path.
    std::string subject;
    for (const char c : name) {
        if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-') subject += c;
    }
    if (subject.empty() || subject[0] == '.') return {};
    std::string names;
    for (const char* n : kIntegrators) names += std::string(names.empty() ? "" : " ") + n;
    std::ostringstream gp;
    gp << "# Work-precision plots of " << subject << ", drawn from trade.csv by simlab study trade.\n"
       << "set datafile separator ','\nset logscale x\nset grid\nset key outside right\n"
       << "set ylabel 'worst digits over the run'\nset yrange [0:16]\n"
       << "set linetype 9 lc rgb '#8b4513' pt 9\n"  // nine integrators: a ninth colour, not the first again
       << "names = '" << names << "'\n"
       << "ok(mode, name) = strcol(2) eq '" << subject << "' && strcol(3) eq name && strcol(4) eq mode && "
       << "strcol(7) eq 'ok'\n";
    std::vector<std::string> made;
    const std::pair<const char*, const char*> axes[] = {{"evaluations", "15"}, {"time", "16"}};
    for (const auto& [axis, column] : axes) {
        gp << "set xlabel '" << (std::string(axis) == "time" ? "seconds (fastest repeat)" : "evaluations of the equations of motion")
           << "'\nset title '" << subject << ": digits against " << axis << "'\n";
        for (const char* format : {"pngcairo size 960,600", "svg size 960,600"}) {
            const std::string file = subject + "-" + axis + (std::string(format).rfind("svg", 0) == 0 ? ".svg" : ".png");
            gp << "set terminal " << format << "\nset output '" << file << "'\n"
               << "plot for [i=1:words(names)] 'trade.csv' every ::1 using (ok('accuracy', word(names, i)) ? $"
               << column << " : NaN):10 with linespoints lt i lw 2 title word(names, i), \\\n"
               << "     for [i=1:words(names)] 'trade.csv' every ::1 using (ok('fixed step', word(names, i)) ? $"
               << column << " : NaN):10 with linespoints lt i dt 2 notitle\n"
               << "set output\n";
            made.push_back(file);
        }
    }
    const fs::path script = dir / (subject + ".gp");
    engine::writeFileAtomically(script.string(), gp.str());
    try {
        isolation::runTool({gnuplot, script.filename().string()}, dir.string());
    } catch (const std::runtime_error&) {
        return {};  // the table says what was drawn; no plot is no error of the study
    }
    return made;
}

/// The table: the cheapest setting (fewest evaluations) whose worst digits reach each target, and the Pareto
/// front of evaluations against digits.
/// Whether a method's digits are not monotone about `target` as its setting tightens: once a setting of the method
/// keeps `target` (or half a digit less), a tighter one falls back below it. Then the digits of `chosen` (a setting
/// of that method) are luck more than a trend, and a neighbouring setting or another scene may keep fewer. Returns
/// the two settings ("accuracy 1e-11 keeps 8.1, accuracy 1e-12 keeps 7.8"), or "".
std::string notMonotone(const std::vector<const json*>& ok, const json& chosen, const char* key, double target) {
    std::vector<const json*> sweep;
    for (const json* p : ok) {
        if (text((*p)["integrator"]) == text(chosen["integrator"]) && text((*p)["mode"]) == text(chosen["mode"])) {
            sweep.push_back(p);
        }
    }
    const char* by = text(chosen["mode"]) == "accuracy" ? "accuracy" : "step";
    std::stable_sort(sweep.begin(), sweep.end(), [by](const json* a, const json* b) {
        return (*a)[by].get<double>() > (*b)[by].get<double>();  // loosest first
    });
    for (const double level : {target - 0.5, target}) {
        const json* reached = nullptr;
        for (const json* p : sweep) {
            const double digits = (*p)[key].get<double>();
            if (!reached && digits >= level) reached = p;
            else if (reached && digits < level) {
                return setting(*reached) + " keeps " + number((*reached)[key], "%.1f") + ", " + setting(*p) +
                       " keeps " + number((*p)[key], "%.1f");
            }
        }
    }
    return "";
}

/// A lab's study table for one figure (`key`: worst_digits, the fewest kept at the measured steps; or
/// final_digits, the figure the lab reports at the end): the cheapest setting for 4 to 12 digits, a mark where the
/// method's digits are not monotone about the target (with the cheapest setting whose method's are), then the Pareto front
/// of evaluations against digits with the stretches of digits no measured setting keeps.
void printFigureTable(std::ostream& out, std::vector<const json*> ok, double referenceDigits, const char* key) {
    ok.erase(std::remove_if(ok.begin(), ok.end(), [key](const json* p) { return !(*p)[key].is_number(); }), ok.end());
    char line[320];
    std::snprintf(line, sizeof line, "  %-7s %-40s %12s %8s %12s\n", "digits", "cheapest setting", "evaluations",
                  "reached", "seconds");
    out << line;
    const auto row = [&](const char* label, const json& p, const char* mark) {
        const std::string how = text(p["integrator"]) + ", " + setting(p);
        std::snprintf(line, sizeof line, "  %-7s %-40s %12s %8s %12s%s\n", label, how.c_str(),
                      number(p["evaluations"], "%.0f").c_str(), number(p[key], "%.1f").c_str(),
                      number(p["seconds"], "%.3g").c_str(), mark);
        out << line;
    };
    for (const int target : {4, 6, 8, 10, 12}) {
        if (target > referenceDigits) {
            std::snprintf(line, sizeof line, "  %-7d beyond the reference's own accuracy: not judged\n", target);
            out << line;
            continue;
        }
        const auto reaches = [target, key](const json* p) { return (*p)[key].get<double>() >= target; };
        const auto found = std::find_if(ok.begin(), ok.end(), reaches);
        if (found == ok.end()) {
            std::snprintf(line, sizeof line, "  %-7d no setting reached it within the cap\n", target);
            out << line;
            continue;
        }
        const std::string label = std::to_string(target);
        const std::string dip = notMonotone(ok, **found, key, target);
        row(label.c_str(), **found, dip.empty() ? "" : "  *");
        if (dip.empty()) continue;
        out << "          * " << text((**found)["integrator"]) << "'s digits are not monotone in its setting (" << dip
            << "): a neighbouring setting or another scene may keep fewer\n";
        const auto steady = std::find_if(ok.begin(), ok.end(), [&](const json* p) {
            return reaches(p) && notMonotone(ok, *p, key, target).empty();
        });
        if (steady != ok.end()) row("", **steady, "  (cheapest whose method gains digits steadily)");
    }
    out << "  Pareto front (evaluations: digits, setting):";
    std::vector<const json*> front;
    double best = -1;
    for (const json* p : ok) {
        const double digits = (*p)[key].get<double>();
        if (digits <= best + 0.05) continue;
        best = digits;
        front.push_back(p);
    }
    for (std::size_t i = 0; i < front.size(); ++i) {
        const json& p = *front[i];
        out << (i % 3 == 0 ? "\n    " : "; ") << number(p["evaluations"], "%.0f") << ": " << number(p[key], "%.1f")
            << ", " << text(p["integrator"]) << " " << setting(p);
    }
    out << '\n';
    // Between two neighbours of the front more than a digit apart, no measured setting keeps the digits between:
    // a cost read there is the dearer neighbour's, never one a setting was seen to pay.
    for (std::size_t i = 1; i < front.size(); ++i) {
        const double low = (*front[i - 1])[key].get<double>(), high = (*front[i])[key].get<double>();
        if (high - low > 1) {
            out << "    no setting measured keeps " << number(json(low), "%.1f") << " to " << number(json(high), "%.1f")
                << " digits: that stretch of the front is reached by none\n";
        }
    }
}

/// A lab's study table: the subject and how its figures were measured, then a table and front for each figure.
void printTable(std::ostream& out, const SubjectRun& run) {
    const json& s = run.subject;
    const double referenceDigits = s["reference_digits"].is_number() ? s["reference_digits"].get<double>() : 0;
    const double starts = s["starts"].is_number() ? s["starts"].get<double>() : 1;
    // The reference's accuracy, floored to a tenth: a bound, never rounded up past what was measured.
    out << '\n'
        << engine::printable(text(s["subject"])) << ": " << engine::printable(text(s["figure"])) << "\n  reference: "
        << engine::printable(text(s["reference"])) << ", good to "
        << number(json(std::floor(referenceDigits * 10) / 10), "%.1f") << " digits at t = "
        << number(s["final_time"]) << " s\n  measured: the fewest digits kept at the run's steps (up to about a "
        << "thousand, spread over the run)" << (starts > 1 ? ", the worst of " + number(json(starts), "%.0f") + " starts" : "")
        << ", each setting's evaluations counted by Simbody\n";
    std::vector<const json*> ok, failed;
    int costly = 0;
    for (const json& p : run.points) {
        const std::string status = text(p["status"]);
        if (status == "ok") ok.push_back(&p);
        else if (status == "too costly") ++costly;
        else if (status != "no error control") failed.push_back(&p);
    }
    // By evaluations, a count the same on every machine; ties keep the study's order (the loosest setting first),
    // never the clock's.
    std::stable_sort(ok.begin(), ok.end(), [](const json* a, const json* b) {
        return (*a)["evaluations"].get<double>() < (*b)["evaluations"].get<double>();
    });
    printFigureTable(out, ok, referenceDigits, "worst_digits");
    if (!text(s["final_figure"]).empty()) {
        out << "  At the end of the run, " << engine::printable(text(s["final_figure"])) << ":\n";
        printFigureTable(out, ok, referenceDigits, "final_digits");
    }
    out << "  " << run.points.size() << " points: " << ok.size() << " ok, " << costly << " too costly (past "
        << number(s["max_evaluations"], "%.0f") << " evaluations), " << failed.size() << " failed or blew up"
        << (failed.empty() ? "" : ":") << '\n';
    for (const json* p : failed) {
        out << "    " << text((*p)["integrator"]) << ", " << setting(*p) << ": " << text((*p)["status"]) << ", "
            << engine::printable(text((*p)["message"])) << '\n';
    }
}

/// One row of `study minimal`: a scene's two models at the same digits, each read along its own curve.
struct EqualDigits {
    std::string lab, subject, integrator;
    double digits = 0;
    work_precision::Reading minimal, over;
};

/// A scene's rows of `study minimal`, for one model (over-modelled or not).
std::vector<work_precision::Point> curveOf(const std::vector<const json*>& rows, bool over) {
    std::vector<work_precision::Point> points;
    for (const json* r : rows) {
        if ((*r)["over_modelled"].get<bool>() != over || text((*r)["status"]) != "ok") continue;
        if (!(*r)["worst_digits"].is_number() || !(*r)["evaluations"].is_number()) continue;
        points.push_back({(*r)["worst_digits"].get<double>(), (*r)["evaluations"].get<double>(),
                          (*r)["seconds"].is_number() ? (*r)["seconds"].get<double>() : 0.0});
    }
    return work_precision::frontOf(points);
}

/// The digits at which a scene's two models are compared: whole digits from the most that either model's
/// cheapest point keeps (but at least 1) to the fewest that either's dearest keeps, at most five of them; where the two ranges do
/// not overlap by a digit (a motion every setting follows exactly), the digits both keep.
std::vector<double> comparedDigits(const std::vector<work_precision::Point>& a,
                                   const std::vector<work_precision::Point>& b) {
    const double lo = std::max(a.front().digits, b.front().digits);
    const double hi = std::min(a.back().digits, b.back().digits);
    if (std::floor(hi) < std::ceil(lo)) return {std::floor(hi * 10) / 10};
    const double first = std::max(std::ceil(lo), std::min(1.0, std::floor(hi))), last = std::floor(hi);
    const double step = std::max(1.0, std::ceil((last - first) / 4));
    std::vector<double> digits;
    for (int k = 0; first + k * step <= last; ++k) digits.push_back(first + k * step);
    return digits;
}

/// The rows of `study minimal` (the study program's curves) read at equal digits, scene by scene.
std::vector<EqualDigits> equalDigits(const std::vector<json>& rows) {
    std::vector<std::string> order;
    std::map<std::string, std::vector<const json*>> bySubject;
    for (const json& r : rows) {
        const std::string subject = text(r["subject"]);
        if (!bySubject.count(subject)) order.push_back(subject);
        bySubject[subject].push_back(&r);
    }
    std::vector<EqualDigits> result;
    for (const std::string& subject : order) {
        const std::vector<const json*>& scene = bySubject[subject];
        const std::vector<work_precision::Point> minimal = curveOf(scene, false), over = curveOf(scene, true);
        if (minimal.empty() || over.empty()) continue;
        for (const double d : comparedDigits(minimal, over)) {
            const std::optional<work_precision::Reading> m = work_precision::costAt(minimal, d);
            const std::optional<work_precision::Reading> v = work_precision::costAt(over, d);
            if (!m || !v) continue;
            result.push_back({text((*scene.front())["lab"]), subject, text((*scene.front())["integrator"]), d, *m, *v});
        }
    }
    return result;
}

std::string ratio(double a, double b) {
    if (!(a > 0) || !(b > 0)) return "";
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "x%.2f", a / b);
    return buffer;
}

/// `study minimal`: each scene's two models at equal digits, then what did not run.
void printMinimal(std::ostream& out, const std::vector<json>& rows, const std::vector<EqualDigits>& compared) {
    char line[256];
    std::vector<std::string> order;
    for (const json& r : rows) {
        if (std::find(order.begin(), order.end(), text(r["subject"])) == order.end()) order.push_back(text(r["subject"]));
    }
    for (const std::string& subject : order) {
        const json *minimal = nullptr, *over = nullptr;
        std::vector<const json*> failed;
        int measured = 0, timedRuns = 0;
        for (const json& r : rows) {
            if (text(r["subject"]) != subject) continue;
            const bool isOver = r["over_modelled"].get<bool>();
            const json*& first = isOver ? over : minimal;
            if (!first) first = &r;
            if (text(r["status"]) != "ok") failed.push_back(&r);
            if (!isOver) ++measured;
            if (r["repeats"].is_number()) timedRuns = std::max(timedRuns, r["repeats"].get<int>());
        }
        if (!minimal || !over) continue;
        out << '\n' << subject << " with " << text((*minimal)["integrator"]) << ", the same scene minimal and "
            << "over-modelled, at equal digits:\n";
        auto describe = [](const json& r) {
            const std::string q = number(r["coordinates"], "%.0f");
            return text(r["model"]) + ": " + number(r["dof"], "%.0f") + " dof in " + q +
                   (q == "1" ? " coordinate" : " coordinates");
        };
        out << "  minimal:       " << describe(*minimal) << "\n  over-modelled: " << describe(*over) << '\n';
        std::snprintf(line, sizeof line, "  %6s  %-24s  %-24s\n", "", "minimal", "over-modelled");
        out << line;
        std::snprintf(line, sizeof line, "  %6s  %12s %11s  %12s %11s  %s\n", "digits", "evaluations", "s/run",
                      "evaluations", "s/run", "over-modelled against minimal");
        out << line;
        bool loosest = false;
        for (const EqualDigits& e : compared) {
            if (e.subject != subject) continue;
            const bool mark = !e.minimal.interpolated || !e.over.interpolated;
            loosest = loosest || mark;
            char d[16], me[24], ms[24], oe[24], os[24];
            std::snprintf(d, sizeof d, "%.1f%s", e.digits, mark ? "*" : "");
            std::snprintf(me, sizeof me, "%.0f", e.minimal.cost);
            std::snprintf(ms, sizeof ms, "%.3g", e.minimal.seconds);
            std::snprintf(oe, sizeof oe, "%.0f", e.over.cost);
            std::snprintf(os, sizeof os, "%.3g", e.over.seconds);
            std::snprintf(line, sizeof line, "  %6s  %12s %11s  %12s %11s  %s evaluations, %s time\n", d, me, ms, oe, os,
                          ratio(e.over.cost, e.minimal.cost).c_str(), ratio(e.over.seconds, e.minimal.seconds).c_str());
            out << line;
        }
        out << "  Each model's cost is read along its own curve of " << measured << " accuracies (1e-1 to 1e-12):\n"
            << "  digits kept all the way; seconds per run, the fastest of alternating batches of runs at least\n"
            << "  0.02 s long"
            << " (up to " << timedRuns << " runs timed per accuracy).\n";
        if (loosest) out << "  * the loosest accuracy already keeps these digits: its cost is what they cost at most.\n";
        for (const json* p : failed) {
            out << "    " << text((*p)["model"]) << ", " << setting(*p) << ": " << text((*p)["status"]) << ", "
                << engine::printable(text((*p)["message"])) << '\n';
        }
    }
}

/// minimal.csv: each scene's two models at equal digits.
void writeMinimalCsv(const fs::path& path, const std::vector<EqualDigits>& compared) {
    std::ostringstream out;
    out << "lab,subject,integrator,digits,read,minimal_evaluations,minimal_seconds,over_evaluations,over_seconds,"
           "evaluations_ratio,time_ratio\n";
    char line[512];
    for (const EqualDigits& e : compared) {
        const bool interpolated = e.minimal.interpolated && e.over.interpolated;
        std::snprintf(line, sizeof line, "%.1f,%s,%.6g,%.6g,%.6g,%.6g,%.4f,%.4f\n", e.digits,
                      interpolated ? "along both curves" : "at a loosest accuracy", e.minimal.cost, e.minimal.seconds,
                      e.over.cost, e.over.seconds, e.over.cost / e.minimal.cost,
                      e.minimal.seconds > 0 ? e.over.seconds / e.minimal.seconds : NAN);
        out << engine::csvCell(e.lab) << ',' << engine::csvCell(e.subject) << ',' << engine::csvCell(e.integrator) << ','
            << line;
    }
    engine::writeFileAtomically(path.string(), out.str());
}

/// minimal-points.csv: each model's curve, a row per accuracy, as the study program measured it.
void writeMinimalPointsCsv(const fs::path& path, const std::vector<json>& rows) {
    std::ostringstream out;
    out << "lab,subject,model,over_modelled,dof,coordinates,integrator,accuracy,status,steps_taken,evaluations,"
           "seconds,timed_runs,worst_digits,final_digits,message\n";
    for (const json& r : rows) {
        out << engine::csvCell(text(r["lab"])) << ',' << engine::csvCell(text(r["subject"])) << ','
            << engine::csvCell(text(r["model"])) << ',' << (r["over_modelled"].get<bool>() ? "yes" : "no") << ','
            << number(r["dof"], "%.0f") << ',' << number(r["coordinates"], "%.0f") << ','
            << engine::csvCell(text(r["integrator"])) << ',' << number(r["accuracy"]) << ','
            << engine::csvCell(text(r["status"])) << ',' << number(r["steps_taken"], "%.0f") << ','
            << number(r["evaluations"], "%.0f") << ',' << number(r["seconds"], "%.6g") << ','
            << number(r["repeats"], "%.0f") << ',' << number(r["worst_digits"], "%.2f") << ','
            << number(r["final_digits"], "%.2f") << ',' << engine::csvCell(text(r["message"])) << '\n';
    }
    engine::writeFileAtomically(path.string(), out.str());
}

/// A lab's trade question as its data file states it: `kind` is "question" (grading/trade-question.json) or
/// "hidden" (grading/trade-hidden.json, absent from the student bundle).
simlab::trade::Question tradeQuestionOf(const engine::Assignment& a, const std::string& kind) {
    const fs::path file = fs::path(a.dir) / "grading" / ("trade-" + kind + ".json");
    if (!fs::exists(file)) throw engine::UsageError(a.id + " has no trade question (" + file.string() + ")");
    try {
        return simlab::trade::parseQuestion(engine::readFile(file.string()), file.string());
    } catch (const std::runtime_error& e) {
        throw engine::UsageError(e.what());
    }
}

/// The study program's arguments for scene `s` of `q`: the scene, its final time, the starts and what they move,
/// and the integrators the question allows.
std::vector<std::string> sceneArguments(const simlab::trade::Question& q, const simlab::trade::Scene& s) {
    char finalTime[32];
    std::snprintf(finalTime, sizeof finalTime, "%.17g", s.finalTime);
    std::vector<std::string> argv = {"--scene", s.scene.dump(), "--final-time", finalTime, "--name",
                                     s.name == "question" ? q.lab + "-question" : q.lab + ": " + s.name,
                                     "--starts", std::to_string(q.starts)};
    if (!q.nudge.empty()) argv.insert(argv.end(), {"--nudge", q.nudge});
    if (!q.integrators.empty()) {
        std::string names;
        for (const std::string& name : q.integrators) names += (names.empty() ? "" : ",") + name;
        argv.insert(argv.end(), {"--integrators", names});
    }
    if (q.fixedStepOnly) argv.push_back("--fixed-steps-only");
    return argv;
}

/// The most evaluations an answer to `q` may take on its scene, where the grader stops its run and gives it nothing
/// (trade::cap, with the rubric's beyond and none_past of the visible trade test); 0 where the tree does not say.
double questionCap(const engine::Assignment& a, const simlab::trade::Question& q, double* beyond, double* nonePast) {
    const Rubric rubric = loadRubric(a.rubric);
    for (const RubricTest& t : rubric.tests) {
        if (!t.visible() || !t.params.count("beyond") || !t.params.count("none_past")) continue;
        *beyond = t.params.at("beyond");
        *nonePast = t.params.at("none_past");
        const std::vector<work_precision::Point>& front = q.scenes.at(0).front;
        return front.empty() ? 0 : simlab::trade::cap(front, q.digits, *beyond, *nonePast);
    }
    return 0;
}

/// The study of a question's scene, one sweep (the study program's --sweep: an integrator's accuracies or its fixed
/// steps) per run of `argv`, as many runs at once as the machine has cores, with a progress line every few seconds.
/// The first sweep's subject line says how many sweeps and points the study has; each sweep's points are kept in
/// its place, so that they come in the order one run prints them.
SubjectRun runSweeps(const std::vector<std::string>& argv, bool sandboxed, const std::string& lab) {
    std::mutex lock;
    std::condition_variable counted;
    std::optional<json> subject;
    std::size_t sweeps = 0;
    bool firstEnded = false;
    std::vector<std::vector<json>> points;
    std::vector<int> statuses;
    Progress progress;
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        for (std::size_t k = next++;; k = next++) {
            if (k > 0) {
                std::unique_lock<std::mutex> guard(lock);
                counted.wait(guard, [&] { return sweeps > 0 || firstEnded; });
                if (k >= sweeps) return;
            }
            std::vector<std::string> args = argv;
            args.insert(args.end(), {"--sweep", std::to_string(k)});
            std::vector<json> mine;
            // The other runs wait for the first's subject line, or for its end, whatever ends it.
            struct Ended {
                std::function<void()> tell;
                ~Ended() { tell(); }
            } ended{[&, k] {
                if (k != 0) return;
                std::lock_guard<std::mutex> guard(lock);
                firstEnded = true;
                counted.notify_all();
            }};
            const int status = runStudyProgram(args, sandboxed, [&](const json& j) {
                if (text(j["type"]) == "point") {
                    mine.push_back(j);
                    progress.pointDone();
                    return;
                }
                if (text(j["type"]) != "subject" || k != 0) return;
                // What a student's program says is data: counts out of reason stop the study below.
                const double n = j["sweeps"].is_number() ? j["sweeps"].get<double>() : 0;
                const double total = j["points"].is_number() ? j["points"].get<double>() : 0;
                std::lock_guard<std::mutex> guard(lock);
                if (subject || !(n >= 1 && n <= 1000 && total >= n && total <= 100000)) return;
                subject = j;
                sweeps = static_cast<std::size_t>(n);
                points.resize(sweeps);
                statuses.assign(sweeps, 0);
                progress.setTotal(static_cast<std::size_t>(total));
                counted.notify_all();
            });
            std::lock_guard<std::mutex> guard(lock);
            if (!subject) {
                statuses.assign(1, status);
                return;
            }
            points[k] = std::move(mine);
            statuses[k] = status;
        }
    };
    inWorkers(cores(), work);
    for (const int status : statuses) {
        if (status != 0) throw std::runtime_error("the study of " + lab + " stopped with status " + std::to_string(status));
    }
    if (!subject) {
        throw std::runtime_error(fs::path(argv.front()).filename().string() + " did not say how many points and sweeps "
                                 "its study has");
    }
    progress.finish(true);
    SubjectRun run{*subject, {}, {}};
    for (std::vector<json>& sweep : points) run.points.insert(run.points.end(), sweep.begin(), sweep.end());
    return run;
}

/// `simlab study trade LAB --fronts`: every scene of the lab's trade question (and of its hidden variants, where the
/// tree has them) studied on the reference solution as the grader measures an answer, and each scene's front -
/// the points no cheaper point matches in digits - written into its data file.
void writeFronts(const StudyOptions& o, const std::vector<const engine::Assignment*>& labs) {
    struct Task {
        const engine::Assignment* lab;
        fs::path file;
        json data;
        std::size_t scene;
        std::vector<work_precision::Point> points;
        int status = 0;
    };
    std::vector<Task> tasks;
    for (const engine::Assignment* a : labs) {
        for (const std::string kind : {"question", "hidden"}) {
            const fs::path file = fs::path(a->dir) / "grading" / ("trade-" + kind + ".json");
            if (!fs::exists(file)) continue;
            const json data = json::parse(engine::readFile(file.string()));
            for (std::size_t i = 0; i < data.at("scenes").size(); ++i) tasks.push_back({a, file, data, i, {}, 0});
        }
    }
    if (tasks.empty()) throw engine::UsageError("no trade question here to make fronts for");
    std::atomic<std::size_t> next{0};
    std::mutex told;
    auto work = [&] {
        for (std::size_t i = next++; i < tasks.size(); i = next++) {
            Task& t = tasks[i];
            const simlab::trade::Question q = simlab::trade::parseQuestion(t.data.dump(), t.file.string());
            std::vector<std::string> argv = {t.lab->studyProgramPath};
            const std::vector<std::string> scene = sceneArguments(q, q.scenes.at(t.scene));
            argv.insert(argv.end(), scene.begin(), scene.end());
            argv.insert(argv.end(), {"--repeats", "1"});
            if (o.quick) argv.push_back("--quick");
            if (o.maxEvaluations > 0) argv.insert(argv.end(), {"--max-evaluations", std::to_string(o.maxEvaluations)});
            if (o.cap > 0) argv.insert(argv.end(), {"--cap", std::to_string(o.cap)});
            {
                std::lock_guard<std::mutex> guard(told);
                std::cerr << "fronts: " << t.lab->id << ", " << q.scenes.at(t.scene).name << " ("
                          << t.file.filename().string() << ")\n";
            }
            t.status = runStudyProgram(argv, false, [&t](const json& j) {
                if (text(j["type"]) != "point" || text(j["status"]) != "ok") return;
                if (!j["worst_digits"].is_number() || !j["evaluations"].is_number()) return;
                t.points.push_back({j["worst_digits"].get<double>(), j["evaluations"].get<double>(), 0});
            });
        }
    };
    inWorkers(std::min<int>(o.jobs, static_cast<int>(tasks.size())), work);
    // Each file once, with every scene's front in it.
    std::map<std::string, json> written;
    for (Task& t : tasks) {
        if (t.status != 0) {
            throw std::runtime_error("the study of " + t.lab->id + " stopped with status " + std::to_string(t.status));
        }
        json& data = written.count(t.file.string()) ? written[t.file.string()] : (written[t.file.string()] = t.data);
        json& scene = data["scenes"][t.scene];
        const std::vector<work_precision::Point> front = work_precision::frontOf(t.points);
        const double digits = data.at("digits").get<double>();
        if (front.empty() || front.back().digits < digits) {
            throw engine::UsageError(t.lab->id + ": no setting keeps " + number(data["digits"], "%g") + " digits on '" +
                                     text(scene["name"]) + "' under the cap: the question cannot be answered there");
        }
        scene["front"] = json::array();
        for (const work_precision::Point& p : front) {
            char d[32];
            std::snprintf(d, sizeof d, "%.4f", p.digits);
            scene["front"].push_back({std::stod(d), p.cost});
        }
        std::cout << t.lab->id << ", " << text(scene["name"]) << ": " << front.size() << " points on the front; "
                  << number(data["digits"], "%g") << " digits cost "
                  << number(json(work_precision::costAt(front, digits)->cost), "%.0f") << " evaluations\n";
    }
    for (const auto& [file, data] : written) {
        engine::writeFileAtomically(file, data.dump(2) + "\n");
        std::cout << "Written: " << engine::printable(file) << '\n';
    }
}

/// trade.csv, the tables and (unless --no-plots) the plots of `runs`, into `dir`.
void writeTrade(const StudyOptions& o, const fs::path& dir, const std::vector<SubjectRun>& runs) {
    writeCsv(dir / "trade.csv", runs);
    for (const SubjectRun& run : runs) {
        printTable(std::cout, run);
        if (o.plots) {
            const std::vector<std::string> files = plot(dir, text(run.subject["subject"]));
            if (files.empty()) std::cout << "  (no plots: gnuplot failed or is not installed)\n";
        }
    }
    std::cout << "\nWritten to " << engine::printable(dir.string()) << ": trade.csv"
              << (o.plots ? ", and for each scene its .gp script with -evaluations and -time plots (PNG, SVG)" : "")
              << '\n';
}

/// The study in parts, one per lab and integrator, for machines that share OUTPUT (a cluster's job array): with
/// --shard I/N, parts I, I + N, ... of the labs' parts in order are measured into OUTPUT/parts; with --assemble,
/// the parts missing (or measured with other options or another build's study program) are measured here, and
/// trade.csv and the plots are written from all of them, the points in the order one run prints them.
void runTradeInParts(const StudyOptions& o, const std::vector<const engine::Assignment*>& labs) {
    struct Part {
        const engine::Assignment* lab;
        std::string integrator;
        std::size_t integratorIndex;
        fs::path file;
    };
    const fs::path dir = fs::absolute(o.output);
    const fs::path partsDir = dir / "parts";
    fs::create_directories(partsDir);
    std::vector<Part> parts;
    for (const engine::Assignment* a : labs) {
        std::size_t k = 0;
        for (const char* name : kIntegrators) {
            parts.push_back({a, name, k++, partsDir / (a->id + "." + name + ".json")});
        }
    }
    std::vector<std::size_t> mine;
    const auto [shard, shards] = o.shard.empty() ? std::pair<int, int>{1, 1} : parseShard(o.shard);
    for (std::size_t i = static_cast<std::size_t>(shard - 1); i < parts.size(); i += static_cast<std::size_t>(shards)) {
        mine.push_back(i);
    }
    // What a part is measured with: the study program's bytes and the options that change its points.
    const auto keyOf = [&](const Part& p) {
        engine::Hash h;
        h.addFileContent(p.lab->studyProgramPath).add(p.integrator).add(o.quick ? "quick" : "full");
        h.add(std::to_string(o.maxEvaluations)).add(std::to_string(o.cap)).add(std::to_string(o.repeats));
        return h.hex();
    };
    const auto kept = [&](const Part& p) -> std::optional<json> {
        if (!fs::exists(p.file)) return std::nullopt;
        const json j = json::parse(engine::readFile(p.file.string()), nullptr, false);
        if (j.is_discarded() || !j.is_object() || !j.contains("lines") || text(j["key"]) != keyOf(p)) return std::nullopt;
        return j;
    };
    std::mutex lock;
    std::atomic<std::size_t> next{0};
    std::atomic<int> measured{0}, reused{0};
    std::string failure;
    auto work = [&] {
        for (std::size_t i = next++; i < mine.size(); i = next++) {
            const Part& p = parts[mine[i]];
            if (kept(p)) {
                ++reused;
                continue;
            }
            std::vector<std::string> argv = {p.lab->studyProgramPath, "--integrators", p.integrator};
            if (o.quick) argv.push_back("--quick");
            if (o.cap > 0) argv.insert(argv.end(), {"--cap", std::to_string(o.cap)});
            if (o.maxEvaluations > 0) argv.insert(argv.end(), {"--max-evaluations", std::to_string(o.maxEvaluations)});
            if (o.repeats > 0) argv.insert(argv.end(), {"--repeats", std::to_string(o.repeats)});
            json lines = json::array();
            const auto start = std::chrono::steady_clock::now();
            const int status = runStudyProgram(argv, false, [&lines](const json& j) { lines.push_back(j); });
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            std::lock_guard<std::mutex> guard(lock);
            if (status != 0) {
                if (failure.empty()) {
                    failure = "the study of " + p.lab->id + " with " + p.integrator + " stopped with status " +
                              std::to_string(status);
                }
                continue;
            }
            const json part = {{"key", keyOf(p)}, {"lab", p.lab->id}, {"integrator", p.integrator}, {"lines", lines}};
            engine::writeFileDurably(p.file.string(), part.dump() + "\n");
            ++measured;
            std::printf("  part %s %s: %zu lines in %.1f s\n", p.lab->id.c_str(), p.integrator.c_str(), lines.size(),
                        seconds);
            std::fflush(stdout);
        }
    };
    inWorkers(std::min<int>(o.jobs, static_cast<int>(mine.size())), work);
    std::cout << measured << " part(s) measured, " << reused << " up to date and kept, of "
              << (o.shard.empty() ? "the study's " : "shard " + o.shard + "'s ") << mine.size() << '\n';
    if (!failure.empty()) throw std::runtime_error(failure);
    if (!o.assemble) {
        std::cout << "Wrote " << engine::printable(partsDir.string()) << "; once every shard has finished, the same "
                  << "command with --assemble instead of --shard writes trade.csv and the plots\n";
        return;
    }
    // Each lab's scenes in the order its parts first name them; each scene's points as one run orders them: the
    // accuracy sweeps integrator by integrator, then the fixed steps.
    std::vector<SubjectRun> runs;
    for (const engine::Assignment* a : labs) {
        std::vector<SubjectRun> labRuns;
        std::vector<std::vector<std::tuple<int, std::size_t, std::size_t, json>>> keyed;
        for (const Part& p : parts) {
            if (p.lab != a) continue;
            const std::optional<json> part = kept(p);
            if (!part) throw std::runtime_error("the part " + p.file.string() + " is missing or unreadable");
            std::size_t current = labRuns.size(), seq = 0;
            for (const json& line : (*part)["lines"]) {
                if (text(line["type"]) == "subject") {
                    current = labRuns.size();
                    for (std::size_t k = 0; k < labRuns.size(); ++k) {
                        if (text(labRuns[k].subject["subject"]) == text(line["subject"])) current = k;
                    }
                    if (current == labRuns.size()) {
                        labRuns.push_back({line, {}, {}});
                        keyed.emplace_back();
                    }
                } else if (text(line["type"]) == "point" && current < labRuns.size()) {
                    keyed[current].emplace_back(text(line["mode"]) == "accuracy" ? 0 : 1, p.integratorIndex, seq++, line);
                }
            }
        }
        for (std::size_t k = 0; k < labRuns.size(); ++k) {
            std::stable_sort(keyed[k].begin(), keyed[k].end(), [](const auto& x, const auto& y) {
                return std::tie(std::get<0>(x), std::get<1>(x), std::get<2>(x)) <
                       std::tie(std::get<0>(y), std::get<1>(y), std::get<2>(y));
            });
            for (auto& entry : keyed[k]) labRuns[k].points.push_back(std::get<3>(entry));
        }
        runs.insert(runs.end(), labRuns.begin(), labRuns.end());
    }
    writeTrade(o, dir, runs);
}

void runTrade(const StudyOptions& o) {
    const engine::Manifest manifest = engine::loadManifest();
    std::vector<const engine::Assignment*> labs;
    if (o.lab == "all") {
        for (const engine::Assignment& a : manifest.assignments) {
            if (!a.studyProgramPath.empty()) labs.push_back(&a);
        }
    } else {
        const engine::Assignment& a = manifest.find(o.lab);
        if (a.studyProgramPath.empty() && (o.file.empty() || a.studyObjects.empty())) {
            throw engine::UsageError("no study of " + o.lab + "'s reference solution, which is not in this tree: study "
                                     "your own file with --file");
        }
        labs.push_back(&a);
    }
    if (labs.empty()) throw engine::UsageError("no lab here has a study (their reference solutions are not in this tree)");
    if ((o.question || o.fronts) && labs.front()->id == "biosim") {
        throw engine::UsageError("biosim has no trade question: each project's is its own");
    }
    if (o.question && o.lab == "all") throw engine::UsageError("--question studies one lab: apple, projectile or book");
    if (o.fronts && !o.file.empty()) throw engine::UsageError("--fronts measures the reference solution, not --file");
    if (o.question) {
        const simlab::trade::Question q = tradeQuestionOf(*labs.front(), "question");
        std::cout << "The trade question of " << q.lab << ": " << q.digits << " digits at every step to "
                  << q.scenes.at(0).finalTime << " s of this scene (the rest as the lab's default one)";
        if (!q.integrators.empty() || q.fixedStepOnly) {
            std::string names;
            for (const std::string& name : q.integrators) names += (names.empty() ? "" : ", ") + name;
            std::cout << ", with " << (names.empty() ? "any integrator" : names) << (q.fixedStepOnly ? " at fixed steps" : "");
        }
        std::cout << ":\n  " << q.scenes.at(0).scene.dump() << "\n";
        if (q.starts > 1) {
            // "/w_B0/0" reads w_B0[0].
            std::string moved;
            for (std::size_t at = 1, next; at <= q.nudge.size(); at = next + 1) {
                next = std::min(q.nudge.find('/', at), q.nudge.size());
                const std::string part = q.nudge.substr(at, next - at);
                const bool index = !part.empty() && part.find_first_not_of("0123456789") == std::string::npos;
                moved += index ? "[" + part + "]" : moved.empty() ? part : "." + part;
            }
            std::cout << "Each point is measured from " << q.starts << " starts (" << moved
                      << " moved in its last digit) and kept at its worst, as the grader measures an answer; one short "
                      << "of " << q.digits << " digits from the first is no answer, measured from that start alone.\n";
        }
        double beyond = 0, nonePast = 0;
        const double cap = questionCap(*labs.front(), q, &beyond, &nonePast);
        const std::string why = number(json(nonePast), "%g") + " times the front's cost at " +
                                number(json(q.digits + beyond), "%g") + " digits";
        if (cap > 0 && o.maxEvaluations > 0 && o.maxEvaluations < cap) {
            std::cout << "Each point is stopped past " << number(json(o.maxEvaluations), "%.0f")
                      << " evaluations (--max-evaluations), short of where the grader stops an answer: "
                      << number(json(cap), "%.0f") << ", " << why << ".\n";
        } else if (cap > 0) {
            std::cout << "Each point is stopped past " << number(json(cap), "%.0f") << " evaluations, where the grader "
                      << "stops an answer: " << why << ", past which it earns nothing.\n";
        }
    }
    if (!o.shard.empty() || o.assemble) {
        const char* clash = !o.file.empty() ? "--file" : o.question ? "--question" : o.fronts ? "--fronts" : nullptr;
        if (clash) throw engine::UsageError(std::string("--shard and --assemble study the reference solutions, not ") + clash);
        if (!o.shard.empty() && o.assemble) throw engine::UsageError("--shard measures parts, --assemble gathers them: give one");
        if (!o.shard.empty()) parseShard(o.shard);  // a bad I/N stops before anything is built
    }
    ensureStudiesBuilt(manifest, labs, !o.file.empty());
    if (!o.shard.empty() || o.assemble) {
        runTradeInParts(o, labs);
        return;
    }
    if (o.fronts) {
        std::vector<const engine::Assignment*> withQuestions;
        for (const engine::Assignment* a : labs) {
            if (a->id != "biosim" && !a->studyProgramPath.empty()) withQuestions.push_back(a);
        }
        writeFronts(o, withQuestions);
        return;
    }

    // A student's file: its own study program, built as `simlab build` builds its lab program, with grading's object
    // check, and run in grading's sandbox.
    std::unique_ptr<engine::TempDir> built;
    std::string studyProgram;
    if (!o.file.empty()) {
        if (o.lab == "all" || labs.front()->id == "biosim") {
            throw engine::UsageError("--file studies one lab's file: apple, projectile or book (biosim's study is the "
                                     "baby boot's)");
        }
        const engine::Assignment& a = *labs.front();
        engine::requireCppSource(o.file);
        const Rubric rubric = loadRubric(a.rubric);
        const engine::SubmissionFiles files = readSubmission(o.file, rubric, rubric.limits);
        if (const std::string closed = engine::sandboxCannotReach(manifest, a); !closed.empty()) {
            throw engine::UsageError(closed);
        }
        built = std::make_unique<engine::TempDir>("simlab-study-");
        studyProgram = built->path() + "/" + a.program + "-study";
        const engine::BuildResult result = engine::Builder(manifest).buildStudy(a, files.name, files.text, studyProgram);
        if (!result.ok) {
            std::cerr << engine::printable(isolation::firstLines(result.log, 30), true);
            throw engine::UsageError(engine::printable(o.file) + (result.stage == "link"    ? " did not link"
                                                                  : result.stage == "check" ? " is refused (forbidden code)"
                                                                                            : " did not compile"));
        }
        // Grading's sandbox, where the program can read nothing but the system and its own folder.
        fs::permissions(built->path(), fs::perms::owner_all | fs::perms::group_exec | fs::perms::others_exec);
    }
    const fs::path dir = fs::absolute(o.output);
    fs::create_directories(dir);
    if (o.question) {
        // Its sweeps on every core, each point under the grader's cap on an answer and measured from the grader's
        // starts where it could be one.
        const engine::Assignment& a = *labs.front();
        const simlab::trade::Question q = tradeQuestionOf(a, "question");
        std::vector<std::string> argv = {studyProgram.empty() ? a.studyProgramPath : studyProgram};
        const std::vector<std::string> scene = sceneArguments(q, q.scenes.at(0));
        argv.insert(argv.end(), scene.begin(), scene.end());
        char value[32];
        std::snprintf(value, sizeof value, "%.17g", q.digits);
        argv.insert(argv.end(), {"--answer-digits", value});
        if (o.quick) argv.push_back("--quick");
        if (o.cap > 0) argv.insert(argv.end(), {"--cap", std::to_string(o.cap)});
        double beyond = 0, nonePast = 0;
        const double cap = questionCap(a, q, &beyond, &nonePast);
        const double evaluations = cap > 0 && o.maxEvaluations > 0 ? std::min(cap, o.maxEvaluations)
                                   : cap > 0                       ? cap
                                                                   : o.maxEvaluations;
        if (evaluations > 0) {
            std::snprintf(value, sizeof value, "%.17g", evaluations);
            argv.insert(argv.end(), {"--max-evaluations", value});
        }
        if (o.repeats > 0) argv.insert(argv.end(), {"--repeats", std::to_string(o.repeats)});
        std::cout << std::flush;  // the question's lines before the progress lines on a shared terminal or log
        writeTrade(o, dir, {runSweeps(argv, !studyProgram.empty(), a.id)});
        return;
    }
    std::vector<SubjectRun> runs;
    std::vector<json> minimalRows;
    // Each lab's study program runs on its own core (--jobs at once); each measures its points one at a time.
    struct LabRun {
        std::vector<SubjectRun> runs;
        std::vector<json> minimal;
        int status = 0;
    };
    std::vector<LabRun> results(labs.size());
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        for (std::size_t i = next++; i < labs.size(); i = next++) {
            const engine::Assignment* a = labs[i];
            std::vector<std::string> argv = {studyProgram.empty() ? a->studyProgramPath : studyProgram};
            if (o.question) {
                const simlab::trade::Question q = tradeQuestionOf(*a, "question");
                const std::vector<std::string> scene = sceneArguments(q, q.scenes.at(0));
                argv.insert(argv.end(), scene.begin(), scene.end());
            }
            if (o.minimal) argv.push_back("--minimal");
            if (o.quick) argv.push_back("--quick");
            if (o.cap > 0) argv.insert(argv.end(), {"--cap", std::to_string(o.cap)});
            if (o.maxEvaluations > 0) argv.insert(argv.end(), {"--max-evaluations", std::to_string(o.maxEvaluations)});
            if (o.repeats > 0) argv.insert(argv.end(), {"--repeats", std::to_string(o.repeats)});
            LabRun& r = results[i];
            r.status = runStudyProgram(argv, !studyProgram.empty(), [&r](const json& j) {
                if (text(j["type"]) == "subject") r.runs.push_back({j, {}, {}});
                else if (text(j["type"]) == "point" && !r.runs.empty()) r.runs.back().points.push_back(j);
                else if (text(j["type"]) == "minimal") r.minimal.push_back(j);
            });
        }
    };
    inWorkers(std::min<int>(o.jobs, static_cast<int>(labs.size())), work);
    for (std::size_t i = 0; i < labs.size(); ++i) {
        if (results[i].status != 0) {
            throw std::runtime_error("the study of " + labs[i]->id + " stopped with status " +
                                     std::to_string(results[i].status));
        }
        runs.insert(runs.end(), results[i].runs.begin(), results[i].runs.end());
        minimalRows.insert(minimalRows.end(), results[i].minimal.begin(), results[i].minimal.end());
    }
    if (o.minimal) {
        const std::vector<EqualDigits> compared = equalDigits(minimalRows);
        writeMinimalCsv(dir / "minimal.csv", compared);
        writeMinimalPointsCsv(dir / "minimal-points.csv", minimalRows);
        printMinimal(std::cout, minimalRows, compared);
        if (minimalRows.empty()) std::cout << "No over-modelled variant of this lab's scene is built.\n";
        std::cout << "\nWritten to " << engine::printable(dir.string()) << ": minimal.csv (equal digits), "
                  << "minimal-points.csv (each model's curve)\n";
        return;
    }
    writeTrade(o, dir, runs);
}

// ---- study extremes -------------------------------------------------------------------------------------------

struct ExtremesOptions {
    std::string lab;
    std::string output = "study";
    bool quick = false;
    double cap = 20;
};

/// Fewer digits than these, and a run that finished is called inaccurate, not accurate.
constexpr double kAccurateDigits = 3;

/// One extreme case from the lab's extremes.toml, and what became of it.
struct Extreme {
    std::string lab, name, expect;
    std::vector<std::string> args;
    std::vector<std::string> troubleWords;  ///< the lab's: a finished run that prints one of these names trouble
    std::vector<std::string> says;   ///< words the program's output must hold (a caveat, a cause)
    std::vector<std::string> lacks;  ///< words it must not (a claim the case disproves)
    bool slow = false;
    std::string outcome;  ///< accurate, inaccurate, rejected, trouble, or SILENT: ... (a defect)
    double digits = NAN;
    double seconds = 0;
    std::string line;     ///< the program's own words for it
    std::string output;   ///< all of them (as far as kept)
};

std::vector<Extreme> readExtremes(const engine::Assignment& a) {
    const fs::path file = fs::path(a.dir) / "study" / "extremes.toml";
    if (!fs::exists(file)) throw engine::UsageError("no extreme cases for " + a.id + " (" + file.string() + ")");
    toml::table t;
    try {
        t = toml::parse_file(file.string());
    } catch (const toml::parse_error& e) {
        throw engine::UsageError(file.string() + ": " + std::string(e.description()));
    }
    std::vector<Extreme> cases;
    std::vector<std::string> troubleWords;
    if (const toml::array* words = t["trouble"].as_array()) {
        for (const toml::node& w : *words) troubleWords.push_back(w.value_or(std::string()));
    }
    if (const toml::array* list = t["case"].as_array()) {
        for (const toml::node& node : *list) {
            const toml::table* c = node.as_table();
            if (!c) continue;
            Extreme e;
            e.lab = a.id;
            e.name = (*c)["name"].value_or(std::string());
            e.expect = (*c)["expect"].value_or(std::string());
            e.slow = (*c)["slow"].value_or(false);
            e.troubleWords = troubleWords;
            for (const auto& [name, list] : {std::pair<const char*, std::vector<std::string>*>{"args", &e.args},
                                             {"says", &e.says}, {"lacks", &e.lacks}}) {
                if (const toml::array* values = (*c)[name].as_array()) {
                    for (const toml::node& v : *values) list->push_back(v.value_or(std::string()));
                }
            }
            cases.push_back(e);
        }
    }
    return cases;
}

/// The line of the program's output that holds `word`, or "".
std::string lineWith(const std::string& output, const std::string& word) {
    std::istringstream in(output);
    std::string line;
    while (std::getline(in, line)) {
        if (line.find(word) != std::string::npos) return line;
    }
    return "";
}

/// Runs one case under the cap and names its outcome. A silent one (a run that says nothing of a failure, prints
/// a non-finite number, leaves one in its results file, crashes, or runs past the cap without warning) is a
/// defect of the lab program.
void runExtreme(const std::string& program, double cap, Extreme& e) {
    engine::TempDir dir("simlab-extreme-");
    isolation::ProcessRequest request;
    request.argv = {program};
    request.argv.insert(request.argv.end(), e.args.begin(), e.args.end());
    const std::string results = dir.path() + "/results.txt";
    request.argv.insert(request.argv.end(), {"--quiet", "--output", results});
    // The program is asked to announce any run longer than a quarter of the cap, so that a case that reaches the
    // cap without a word is one the program itself did not see coming.
    request.env = isolation::childEnvironment(
        {"LC_ALL=C", "SIMLAB_LONG_RUN_SECONDS=" + std::to_string(std::max(1.0, cap / 4))});
    request.workDir = dir.path();
    // CPU time decides, as in grading, so that a busy machine names the same outcomes; wall time is a net.
    request.limits.cpuSeconds = cap;
    request.limits.wallSeconds = 5 * cap;
    request.limits.memoryMiB = 4096;
    request.limits.fileMiB = 1024;
    request.limits.processes = 64;
    request.keepOutput = 256 * 1024;
    const isolation::ProcessResult r = isolation::runProcess(request);
    e.seconds = r.wallSeconds;
    e.output = r.output;
    const std::regex nonFinite(R"((^|[^A-Za-z_])(nan|-?inf)([^A-Za-z_]|$))", std::regex::icase);
    if (!r.started) {
        e.outcome = "SILENT: did not start";
        e.line = r.error;
    } else if (r.wallTimeout || r.cpuTimeout) {
        std::string warned = lineWith(r.output, "will take about");
        if (warned.empty()) warned = lineWith(r.output, "no sample after");
        e.outcome = warned.empty() ? "SILENT: ran past the cap without a word" : "trouble";
        e.line = warned.empty() ? "" : "expected run time past the cap: " + warned;
    } else if (r.signal != 0) {
        e.outcome = "SILENT: crashed (" + isolation::signalName(r.signal) + ")";
    } else if (r.exitCode == 2) {
        e.outcome = "rejected";
        e.line = lineWith(r.output, "error:");
    } else if (r.exitCode == 1) {
        e.outcome = "trouble";
        e.line = lineWith(r.output, "error:");
    } else if (r.exitCode != 0) {
        e.outcome = "SILENT: exit status " + std::to_string(r.exitCode);
    } else {
        // Finished: the figure is the fewest digits the program claims; a number it cannot stand behind is a defect.
        const std::regex claim(R"(([0-9]+\.[0-9]) accurate digits)");
        for (auto it = std::sregex_iterator(r.output.begin(), r.output.end(), claim); it != std::sregex_iterator(); ++it) {
            const double d = std::stod((*it)[1].str());
            e.digits = std::isnan(e.digits) ? d : std::min(e.digits, d);
        }
        std::ifstream file(results);
        std::string row, badRow;
        while (std::getline(file, row)) {
            if (!row.empty() && row[0] != '#' && std::regex_search(row, nonFinite)) {
                badRow = row;
                break;
            }
        }
        std::istringstream out(r.output);
        std::string line, badLine;
        while (std::getline(out, line)) {
            if (std::regex_search(line, nonFinite)) {
                badLine = line;
                break;
            }
        }
        std::string named;
        for (const std::string& word : e.troubleWords) {
            if (named.empty() && !word.empty()) named = lineWith(r.output, word);
        }
        if (!named.empty()) {
            e.outcome = "trouble";
            e.line = named;
        } else if (!badLine.empty()) {
            e.outcome = "SILENT: printed a non-finite number";
            e.line = badLine;
        } else if (!badRow.empty()) {
            e.outcome = "SILENT: a non-finite row in the results file";
            e.line = badRow.substr(0, 120);
        } else if (std::isnan(e.digits)) {
            e.outcome = "SILENT: finished without a figure";
        } else {
            // The label says what the digits say: a run that finished with fewer than kAccurateDigits is honest
            // about its figure, and inaccurate.
            e.outcome = e.digits >= kAccurateDigits ? "accurate" : "inaccurate";
            e.line = lineWith(r.output, "accurate digits");
        }
    }
    if (e.line.size() > 160) e.line = e.line.substr(0, 160) + "...";
}

void runExtremes(const ExtremesOptions& o) {
    const engine::Manifest manifest = engine::loadManifest();
    std::vector<const engine::Assignment*> labs;
    for (const engine::Assignment& a : manifest.assignments) {
        const bool chosen = o.lab == "all" ? fs::exists(fs::path(a.dir) / "study" / "extremes.toml") : a.id == o.lab;
        if (chosen) labs.push_back(&a);
    }
    if (labs.empty()) manifest.find(o.lab);  // an unknown lab: its one-line error
    const fs::path dir = fs::absolute(o.output);
    fs::create_directories(dir);
    std::vector<Extreme> all;
    int broken = 0;
    char line[512];
    for (const engine::Assignment* a : labs) {
        if (a->referenceProgramPath.empty()) {
            throw engine::UsageError("no extremes for " + a->id + ": its reference solution is not in this tree");
        }
        std::vector<Extreme> cases = readExtremes(*a);
        int skipped = 0;
        std::cout << '\n' << a->id << ": " << cases.size() << " extreme cases, each under a " << o.cap << " s cap of CPU time\n";
        std::snprintf(line, sizeof line, "  %-10s %6s %8s  %s\n", "outcome", "digits", "seconds", "case: the program's words");
        std::cout << line;
        for (Extreme& e : cases) {
            if (o.quick && e.slow) {
                ++skipped;
                continue;
            }
            runExtreme(a->referenceProgramPath, o.cap, e);
            const bool silent = e.outcome.rfind("SILENT", 0) == 0;
            // What the case promises: its outcome, and the words the program must and must not say.
            std::string broke = e.expect.empty() || e.outcome == e.expect ? "" : e.expect;
            for (const std::string& w : e.says) {
                if (e.output.find(w) == std::string::npos) broke += (broke.empty() ? "" : "; ") + ("says \"" + w + "\"");
            }
            for (const std::string& w : e.lacks) {
                if (e.output.find(w) != std::string::npos) broke += (broke.empty() ? "" : "; ") + ("not \"" + w + "\"");
            }
            const bool promise = broke.empty();
            if (silent || !promise) ++broken;
            std::snprintf(line, sizeof line, "  %-10s %6s %8.2f  %s%s%s%s\n", silent ? "SILENT" : e.outcome.c_str(),
                          std::isnan(e.digits) ? "" : number(json(e.digits), "%.1f").c_str(), e.seconds,
                          engine::printable(e.name).c_str(), e.line.empty() ? "" : ": ",
                          engine::printable(silent ? e.outcome + (e.line.empty() ? "" : " - " + e.line) : e.line).c_str(),
                          promise ? "" : ("  [expected " + broke + "]").c_str());
            std::cout << line << std::flush;
            all.push_back(e);
        }
        if (skipped) std::cout << "  (" << skipped << " slow cases not run: --quick)\n";
    }
    std::ostringstream csv;
    csv << "lab,case,arguments,expected,outcome,digits,seconds,message\n";
    for (const Extreme& e : all) {
        std::string args;
        for (const std::string& a : e.args) args += (args.empty() ? "" : " ") + a;
        csv << engine::csvCell(e.lab) << ',' << engine::csvCell(e.name) << ',' << engine::csvCell(args) << ','
            << engine::csvCell(e.expect) << ',' << engine::csvCell(e.outcome) << ','
            << (std::isnan(e.digits) ? "" : number(json(e.digits), "%.1f")) << ',' << number(json(e.seconds), "%.3f")
            << ',' << engine::csvCell(e.line) << '\n';
    }
    engine::writeFileAtomically((dir / "extremes.csv").string(), csv.str());
    std::cout << "\nWritten to " << engine::printable(dir.string()) << ": extremes.csv\n";
    if (broken > 0) {
        throw std::runtime_error(std::to_string(broken) + " extreme case(s) ended silently or not as the lab promises");
    }
}

}  // namespace

void addStudy(CLI::App& app) {
    CLI::App* study = app.add_subcommand("study", "Measure the labs' numerics: what accuracy costs.");
    study->require_subcommand(1);
    auto options = std::make_shared<StudyOptions>();
    CLI::App* trade = study->add_subcommand(
        "trade", "Work-precision study of a lab's reference solution: every integrator at accuracies 1e-1 ... "
                 "1e-14 and fixed steps, each point under a cost cap; writes trade.csv and plots, prints the "
                 "cheapest setting for 4 to 12 digits.");
    trade->add_option("lab", options->lab, "apple, projectile, book, biosim (the baby boot) or all")->required();
    trade->add_option("--output,-o", options->output, "folder for trade.csv and the plots")->capture_default_str();
    trade->add_flag("--quick", options->quick, "fewer step sizes, one timed repeat, a cap of 2e5 evaluations");
    trade->add_option("--max-evaluations", options->maxEvaluations,
                      "the cost cap: evaluations one point may take (default 5e5; 2e5 with --quick; with --question, "
                      "the grader's cap on an answer, or this if lower)")
        ->check(simlab::between(100.0, 1e9));
    trade->add_option("--cap", options->cap,
                      "seconds of CPU time one point may take (default 600): a net for a run that would not end, "
                      "never the cost cap (a point it stops is failed, and says so)")
        ->check(simlab::between(0.01, 3600.0));
    trade->add_option("--repeats", options->repeats, "timed runs per point, the fastest kept (default 3)")
        ->check(CLI::Range(1, 100));
    trade->add_flag("!--no-plots", options->plots, "write trade.csv and the table only");
    trade->add_option("--jobs,-j", options->jobs, "labs studied at once, one core each (with all)")
        ->check(CLI::Range(1, 64))
        ->capture_default_str();
    trade->add_option("--file", options->file,
                      "study this student file instead of the reference solution: it is built with grading's object "
                      "check and run in grading's sandbox");
    trade->add_flag("--question", options->question,
                    "study the scene of the lab's graded trade question (not the lab's default one) as the grader "
                    "measures an answer: the integrators it allows, each point stopped at the grader's cap on an "
                    "answer and measured from the grader's starts where it keeps the digits asked for; its sweeps "
                    "run on every core, with a progress line every few seconds");
    trade->add_flag("--fronts", options->fronts,
                    "for those who keep the course: measure the front of every scene of the trade question and its "
                    "hidden variants on the reference solution and write it into grading/trade-*.json");
    trade->add_option("--shard", options->shard,
                      "I/N: measure share I of N of the study's parts (one per lab and integrator) into "
                      "OUTPUT/parts, beside the other shards on a shared OUTPUT (a cluster's job array)")
        ->type_name("I/N");
    trade->add_flag("--assemble", options->assemble,
                    "write trade.csv and the plots from OUTPUT/parts, measuring here any part no shard finished");
    trade->callback([options] { runTrade(*options); });

    CLI::App* minimal = study->add_subcommand(
        "minimal", "What over-modelling costs: each scene with its minimal mobilizers and over-modelled (a Free "
                   "mobilizer, say), each model's work-precision curve measured with RungeKuttaMerson at accuracies "
                   "1e-1 to 1e-12, and the two read at equal digits (evaluations, and seconds per run timed in "
                   "batches).");
    minimal->add_option("lab", options->lab, "apple, projectile, book or all")->required();
    minimal->add_option("--output,-o", options->output, "folder for minimal.csv and minimal-points.csv")->capture_default_str();
    minimal->add_option("--repeats", options->repeats, "timed batches per accuracy, the fastest kept (default 3)")
        ->check(CLI::Range(1, 100));
    minimal->add_option("--file", options->file,
                        "study this student file's minimal model instead of the solution's (built with grading's "
                        "object check, run in grading's sandbox)");
    minimal->callback([options] {
        options->minimal = true;
        runTrade(*options);
    });

    auto extremes = std::make_shared<ExtremesOptions>();
    CLI::App* extreme = study->add_subcommand(
        "extremes", "Runs the lab program on its extreme cases (assignments/LAB/study/extremes.toml: tiny, huge, zero and "
                    "degenerate scenes, settings at their limits), each under a time cap, and names each outcome: "
                    "accurate (with digits; inaccurate below 3), rejected or trouble (with the program's one line). "
                    "Exits 1 if any "
                    "ends silently or not as the lab promises.");
    extreme->add_option("lab", extremes->lab, "apple, projectile, book or all")->required();
    extreme->add_option("--output,-o", extremes->output, "folder for extremes.csv")->capture_default_str();
    extreme->add_flag("--quick", extremes->quick, "skip the cases marked slow");
    extreme->add_option("--cap", extremes->cap, "seconds of CPU time one case may take (wall time: five times as many)")
        ->check(simlab::between(1.0, 3600.0))
        ->capture_default_str();
    extreme->callback([extremes] { runExtremes(*extremes); });

    addStudyLongRun(*study, [](const engine::Manifest& m, const engine::Assignment& a) { ensureStudiesBuilt(m, {&a}, false); });
}

}  // namespace simlab::cli
