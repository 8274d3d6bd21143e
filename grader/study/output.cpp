// What a study writes: trade.csv and the plots, the tables of the cheapest settings and the front, and `study
// minimal`'s comparison at equal digits.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <iterator>
#include <map>
#include <optional>
#include <sstream>

#include "internal.h"
#include "simlab/common/files.h"
#include "simlab/common/text.h"
#include "simlab/isolation/process.h"
#include "simlab/work_precision.h"

namespace simlab::study {

std::string number(const json& value, const char* format) {
    if (!value.is_number()) return "";
    char text[32];
    std::snprintf(text, sizeof text, format, value.get<double>());
    return text;
}

std::string text(const json& value) { return value.is_string() ? value.get<std::string>() : std::string(); }

namespace {

/// The one line a point's setting takes: "accuracy 1e-06" or "fixed step 0.004 s", and for a fixed step that reads
/// the accuracy too (Verlet's: the study program gives it its accuracy), "fixed step 0.04 s at accuracy 1e-03".
std::string setting(const json& p) {
    if (text(p["mode"]) == "accuracy") return "accuracy " + number(p["accuracy"], "%.0e");
    const bool reads = p["accuracy"].is_number() && p["accuracy"].get<double>() > 0;
    return "fixed step " + number(p["step"], "%.3g") + " s" +
           (reads ? " at accuracy " + number(p["accuracy"], "%.0e") : "");
}

void writeCsv(const fs::path& path, const std::vector<SubjectRun>& runs) {
    std::ostringstream out;
    out << "lab,subject,integrator,mode,accuracy,step_s,status,reached_s,final_digits,worst_digits,drift,"
           "reference_digits,steps_taken,steps_attempted,evaluations,seconds,repeats,message\n";
    for (const SubjectRun& run : runs) {
        for (const json& p : run.points) {
            out << engine::csvCell(text(run.subject["lab"])) << ',' << engine::csvCell(text(p["subject"])) << ','
                << engine::csvCell(text(p["integrator"])) << ',' << engine::csvCell(text(p["mode"])) << ','
                << number(p["accuracy"]) << ',' << number(p["step"]) << ',' << engine::csvCell(text(p["status"])) << ','
                << number(p["reached"]) << ',' << number(p["final_digits"], "%.2f") << ','
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
/// integrator and sweep that measured a point (dashed: a fixed-step sweep), each named in the key, as PNG and SVG.
/// Returns the files made, or says why none were.
std::vector<std::string> plot(const fs::path& dir, const SubjectRun& run) {
    const std::string name = text(run.subject["subject"]);
    const std::string gnuplot = "/usr/bin/gnuplot";  // Debian's gnuplot-nox (scripts/install-deps)
    if (!fs::exists(gnuplot)) return {};
    // A subject's name is a plain word (wellFormedLine); quoted as gnuplot quotes (a ' doubled) all the same, and
    // never a path.
    std::string subject;
    for (const char c : name) {
        if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-') subject += c;
    }
    if (subject.empty() || subject[0] == '.') return {};
    // The curves: each integrator's accuracy sweep, then each one's fixed steps, where the sweep has a point ok.
    struct Curve {
        int integrator;  // 1-based, its colour
        const char* mode;
    };
    std::vector<Curve> curves;
    for (const char* mode : {"accuracy", "fixed step"}) {
        for (int i = 0; i < static_cast<int>(std::size(kIntegrators)); ++i) {
            const bool measured = std::any_of(run.points.begin(), run.points.end(), [&](const json& p) {
                return text(p["integrator"]) == kIntegrators[i].name && text(p["mode"]) == mode && text(p["status"]) == "ok";
            });
            if (measured) curves.push_back({i + 1, mode});
        }
    }
    if (curves.empty()) return {};
    std::ostringstream gp;
    gp << "# Work-precision plots of " << subject << ", drawn from trade.csv by simlab study trade.\n"
       << "set datafile separator ','\nset logscale x\nset grid\nset key outside right\n"
       << "set ylabel 'worst digits over the run'\nset yrange [0:16]\n"
       << "set linetype 9 lc rgb '#8b4513' pt 9\n"  // nine integrators: a ninth colour, not the first again
       << "ok(mode, name) = strcol(2) eq '" << subject << "' && strcol(3) eq name && strcol(4) eq mode && "
       << "strcol(7) eq 'ok'\n";
    std::vector<std::string> made;
    const std::pair<const char*, const char*> axes[] = {{"evaluations", "15"}, {"time", "16"}};
    for (const auto& [axis, column] : axes) {
        gp << "set xlabel '"
           << (std::string(axis) != "time"                            ? "evaluations of the equations of motion"
               : text(run.subject["timing"]) == "measured run" ? "seconds (the measured run, timed once)"
                                                               : "seconds (fastest repeat)")
           << "'\nset title '" << subject << ": digits against " << axis << "'\n";
        for (const char* format : {"pngcairo size 960,600", "svg size 960,600"}) {
            const std::string file =
                subject + "-" + axis + (std::string(format).rfind("svg", 0) == 0 ? ".svg" : ".png");
            gp << "set terminal " << format << "\nset output '" << file << "'\nplot ";
            for (std::size_t c = 0; c < curves.size(); ++c) {
                const std::string integrator = kIntegrators[curves[c].integrator - 1].name;
                const bool fixed = std::string(curves[c].mode) == "fixed step";
                gp << (c ? ", \\\n     " : "") << "'trade.csv' every ::1 using (ok('" << curves[c].mode << "', '"
                   << integrator << "') ? $" << column << " : NaN):10 with linespoints lt " << curves[c].integrator
                   << " lw 2" << (fixed ? " dt 2" : "") << " title '" << integrator << (fixed ? ", fixed steps" : "")
                   << "'";
            }
            gp << "\nset output\n";
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
/// final_digits, the figure the lab reports at the end): the cheapest setting for each of `targets`, a mark where the
/// method's digits are not monotone about the target (with the cheapest setting whose method's are), then the Pareto
/// front of evaluations against digits with the stretches of digits no measured setting keeps.
void printFigureTable(std::ostream& out, std::vector<const json*> ok, double referenceDigits, const char* key,
                      const std::vector<double>& targets) {
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
    for (const double target : targets) {
        const std::string label = number(json(target), "%g");
        if (target > referenceDigits) {
            std::snprintf(line, sizeof line, "  %-7s beyond the reference's own accuracy: not judged\n", label.c_str());
            out << line;
            continue;
        }
        const auto reaches = [target, key](const json* p) { return (*p)[key].get<double>() >= target; };
        const auto found = std::find_if(ok.begin(), ok.end(), reaches);
        if (found == ok.end()) {
            std::snprintf(line, sizeof line, "  %-7s no setting reached it within the cap\n", label.c_str());
            out << line;
            continue;
        }
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

/// How the subject's seconds were timed, a line of its table's note.
std::string timedNote(const json& subject) {
    if (text(subject["timing"]) == "measured run") {
        return "  timed: once, the measured run's own steps (its checks against the reference left out): rougher than "
               "the full study's seconds\n";
    }
    const double repeats = subject["repeats"].is_number() ? subject["repeats"].get<double>() : 1;
    return repeats > 1 ? "  timed: each point's fastest of up to " + number(json(repeats), "%.0f") +
                             " runs to the end, reporting only there (trade.csv's repeats column says how many)\n"
                       : std::string("  timed: each point's one run to the end, reporting only there\n");
}

/// A lab's study table: the subject and how its figures were measured, then a table and front for each figure.
void printTable(std::ostream& out, const SubjectRun& run, const std::vector<double>& targets) {
    const json& s = run.subject;
    const double referenceDigits = s["reference_digits"].is_number() ? s["reference_digits"].get<double>() : 0;
    const double starts = s["starts"].is_number() ? s["starts"].get<double>() : 1;
    // The reference's accuracy, floored to a tenth: a bound, never rounded up past what was measured.
    out << '\n'
        << engine::printable(text(s["subject"])) << ": " << engine::printable(text(s["figure"]))
        << "\n  reference: " << engine::printable(text(s["reference"])) << ", good to "
        << number(json(std::floor(referenceDigits * 10) / 10), "%.1f") << " digits at t = " << number(s["final_time"])
        << " s\n  measured: the fewest digits kept at the run's steps (up to about a "
        << "thousand, spread over the run)"
        << (starts > 1 ? ", the worst of " + number(json(starts), "%.0f") + " starts" : "")
        << ", each setting's evaluations counted by Simbody\n"
        << timedNote(s) << "  replay: the lab program takes a row's steps at its setting with --dt equal to the final time (a fixed "
        << "step: --fixed-step --dt STEP, and --accuracy where the row names one); a smaller --dt ends steps at its "
        << "samples\n";
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
    printFigureTable(out, ok, referenceDigits, "worst_digits", targets);
    if (!text(s["final_figure"]).empty()) {
        out << "  At the end of the run, " << engine::printable(text(s["final_figure"])) << ":\n";
        printFigureTable(out, ok, referenceDigits, "final_digits", targets);
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
/// cheapest point keeps (but at least 1) to the fewest that either's dearest keeps, at most five of them; where the two
/// ranges do not overlap by a digit (a motion every setting follows exactly), the digits both keep.
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
        if (std::find(order.begin(), order.end(), text(r["subject"])) == order.end())
            order.push_back(text(r["subject"]));
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
        out << '\n'
            << subject << " with " << text((*minimal)["integrator"]) << ", the same scene minimal and "
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
            std::snprintf(line, sizeof line, "  %6s  %12s %11s  %12s %11s  %s evaluations, %s time\n", d, me, ms, oe,
                          os, ratio(e.over.cost, e.minimal.cost).c_str(),
                          ratio(e.over.seconds, e.minimal.seconds).c_str());
            out << line;
        }
        out << "  Each model's cost is read along its own curve of " << measured << " accuracies (1e-1 to 1e-12):\n"
            << "  digits kept all the way; seconds per run, the fastest of alternating batches of runs at least\n"
            << "  0.02 s long"
            << " (up to " << timedRuns << " runs timed per accuracy).\n";
        if (loosest)
            out << "  * the loosest accuracy already keeps these digits: its cost is what they cost at most.\n";
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
        out << engine::csvCell(e.lab) << ',' << engine::csvCell(e.subject) << ',' << engine::csvCell(e.integrator)
            << ',' << line;
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

}  // namespace

/// trade.csv, the tables and (unless --no-plots) the plots of `runs`, into `dir`.
void writeTrade(const StudyOptions& o, const fs::path& dir, const std::vector<SubjectRun>& runs,
                const std::vector<double>& targets) {
    writeCsv(dir / "trade.csv", runs);
    for (const SubjectRun& run : runs) {
        printTable(std::cout, run, targets);
        if (o.plots) {
            const std::vector<std::string> files = plot(dir, run);
            if (files.empty()) std::cout << "  (no plots: gnuplot failed or is not installed)\n";
        }
    }
    std::cout << "\nWritten to " << engine::printable(dir.string()) << ": trade.csv"
              << (o.plots ? ", and for each scene its .gp script with -evaluations and -time plots (PNG, SVG)" : "")
              << '\n';
}

void writeMinimal(const fs::path& dir, const std::vector<json>& rows) {
    const std::vector<EqualDigits> compared = equalDigits(rows);
    writeMinimalCsv(dir / "minimal.csv", compared);
    writeMinimalPointsCsv(dir / "minimal-points.csv", rows);
    printMinimal(std::cout, rows, compared);
    if (rows.empty()) std::cout << "No over-modelled variant of this lab's scene is built.\n";
    std::cout << "\nWritten to " << engine::printable(dir.string()) << ": minimal.csv (equal digits), "
              << "minimal-points.csv (each model's curve)\n";
}

}  // namespace simlab::study
