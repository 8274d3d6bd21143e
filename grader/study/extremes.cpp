// `simlab study extremes`: the lab programs on their extreme cases, each outcome named.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <toml++/toml.h>

#include "internal.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/build/manifest.h"
#include "simlab/common/text.h"
#include "simlab/isolation/process.h"

namespace simlab::study {

namespace {

/// Fewer digits than these, and a run that finished is called inaccurate, not accurate.
constexpr double kAccurateDigits = 3;

/// One extreme case from the lab's extremes.toml, and what became of it.
struct Extreme {
    std::string lab, name, expect;
    std::vector<std::string> args;
    std::vector<std::string> troubleWords;  ///< the lab's: a finished run that prints one of these names trouble
    std::vector<std::string> says;          ///< words the program's output must hold (a caveat, a cause)
    std::vector<std::string> lacks;         ///< words it must not (a claim the case disproves)
    bool slow = false;
    std::string outcome;  ///< accurate, inaccurate, rejected, trouble, or SILENT: ... (a defect)
    double digits = NAN;
    double seconds = 0;
    std::string line;    ///< the program's own words for it
    std::string output;  ///< all of them (as far as kept)
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
                                             {"says", &e.says},
                                             {"lacks", &e.lacks}}) {
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
    request.env =
        isolation::childEnvironment({"LC_ALL=C", "SIMLAB_LONG_RUN_SECONDS=" + std::to_string(std::max(1.0, cap / 4))});
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
        for (auto it = std::sregex_iterator(r.output.begin(), r.output.end(), claim); it != std::sregex_iterator();
             ++it) {
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

}  // namespace

void runExtremes(const ExtremesOptions& o) {
    const engine::Manifest manifest = engine::loadManifest();
    std::vector<const engine::Assignment*> labs;
    for (const engine::Assignment& a : manifest.assignments) {
        const bool chosen = o.lab == "all" ? fs::exists(fs::path(a.dir) / "study" / "extremes.toml") : a.id == o.lab;
        if (chosen) labs.push_back(&a);
    }
    if (labs.empty()) labs.push_back(&manifest.find(o.lab));  // a lab's folder, or an unknown lab's one-line error
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
        std::cout << '\n'
                  << a->id << ": " << cases.size() << " extreme cases, each under a " << o.cap
                  << " s cap of CPU time\n";
        std::snprintf(line, sizeof line, "  %-10s %6s %8s  %s\n", "outcome", "digits", "seconds",
                      "case: the program's words");
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
                if (e.output.find(w) == std::string::npos)
                    broke += (broke.empty() ? "" : "; ") + ("says \"" + w + "\"");
            }
            for (const std::string& w : e.lacks) {
                if (e.output.find(w) != std::string::npos) broke += (broke.empty() ? "" : "; ") + ("not \"" + w + "\"");
            }
            const bool promise = broke.empty();
            if (silent || !promise) ++broken;
            std::snprintf(
                line, sizeof line, "  %-10s %6s %8.2f  %s%s%s%s\n", silent ? "SILENT" : e.outcome.c_str(),
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

}  // namespace simlab::study
