#include "simlab/course/similarity.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <regex>
#include <set>
#include <sstream>

#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/isolation/process.h"
#include "simlab/common/text.h"
#include "simlab/writers/html.h"

namespace simlab::engine {

namespace {

constexpr const char* kSim = "/usr/bin/sim_c++";

std::set<std::string> linesOf(const std::string& text) {
    std::set<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (!trimmed(line).empty()) lines.insert(trimmed(line));
    }
    return lines;
}

double medianOf(std::vector<double> values) {
    if (values.empty()) return 0;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

// A file without the starter's lines, and for each line left the line it was in the file as handed in.
struct StudentLines {
    std::string text;
    std::vector<int> lines;
};

StudentLines studentLines(const std::string& text, const std::set<std::string>& given) {
    StudentLines out;
    std::istringstream in(text);
    int number = 0;
    for (std::string line; std::getline(in, line);) {
        ++number;
        if (trimmed(line).empty() || given.count(trimmed(line))) continue;
        out.text += line + "\n";
        out.lines.push_back(number);
    }
    return out;
}

// sim_c++ with `options` on the files `names` of `dir`, in the sandbox: its output.
std::string runSim(const std::string& dir, const std::vector<std::string>& options,
                   const std::vector<std::string>& names) {
    isolation::ProcessRequest request;
    request.argv = {kSim};
    request.argv.insert(request.argv.end(), options.begin(), options.end());
    request.argv.insert(request.argv.end(), names.begin(), names.end());
    request.env = isolation::childEnvironment({"LC_ALL=C"});
    request.workDir = dir;
    request.isolate = true;
    request.handOver = {dir};
    request.limits.cpuSeconds = 600;
    request.limits.wallSeconds = 1200;
    request.limits.outputKiB = 64 * 1024;
    request.keepOutput = 64 << 20;
    const isolation::ProcessResult run = isolation::runProcess(request);
    if (!run.exitedCleanly()) {
        throw UsageError("sim_c++ failed (" + (run.started ? "status " + std::to_string(run.exitCode) : run.error) +
                         ")");
    }
    return run.output;
}

// The stripped file's line `n` (1-based, as sim_c++ counts) as the line of the file handed in.
int handedInLine(const std::vector<int>& kept, int n) {
    if (kept.empty()) return 0;
    return kept[static_cast<std::size_t>(std::clamp(n, 1, static_cast<int>(kept.size())) - 1)];
}

// Each flagged pair's shared runs: sim_c++ once more, on the flagged pairs' files alone, printing its runs.
void addRuns(SimilarityReport& report, const std::string& dir, const std::vector<std::string>& names,
             const std::vector<std::vector<int>>& kept) {
    if (report.flagged.empty()) return;
    std::map<std::string, std::size_t> number;
    for (std::size_t i = 0; i < report.ids.size(); ++i) number[report.ids[i]] = i;
    std::set<std::size_t> involved;
    for (const SimilarPair& p : report.flagged) involved.insert({number[p.a], number[p.b]});
    std::vector<std::string> some;
    for (std::size_t i : involved) some.push_back(names[i]);
    const auto runs = parseSimRuns(runSim(dir, {"-n", "-e", "-s"}, some));
    for (SimilarPair& p : report.flagged) {
        const std::size_t a = number[p.a], b = number[p.b];
        const auto found = runs.find({a, b});
        if (found == runs.end()) continue;
        for (SharedRun run : found->second) {
            run.aFirst = handedInLine(kept[a], run.aFirst);
            run.aLast = handedInLine(kept[a], run.aLast);
            run.bFirst = handedInLine(kept[b], run.bFirst);
            run.bLast = handedInLine(kept[b], run.bLast);
            p.runs.push_back(run);
        }
    }
}

// A file as a column: its lines, those in a shared run marked (by the run, in turn of three colours), the
// starter's dimmed. `ranges` holds each run's first and last line, most tokens first.
std::string sideColumn(const std::string& id, const std::string& text, const std::set<std::string>& given,
                       const std::vector<std::pair<int, int>>& ranges) {
    std::ostringstream out;
    out << "<div class=\"side\"><h4>" << writers::htmlText(id) << "</h4><pre>";
    std::istringstream in(text);
    int number = 0;
    for (std::string line; std::getline(in, line);) {
        ++number;
        std::size_t run = 0;
        while (run < ranges.size() && (number < ranges[run].first || number > ranges[run].second)) ++run;
        if (given.count(trimmed(line))) out << "<span class=\"muted\">" << writers::htmlBlock(line) << "</span>";
        else if (run < ranges.size() && !trimmed(line).empty()) {
            out << "<mark class=\"r" << run % 3 << "\" title=\"shared run " << run + 1 << "\">"
                << writers::htmlBlock(line) << "</mark>";
        } else out << writers::htmlBlock(line);
        out << "\n";
    }
    out << "</pre></div>";
    return out.str();
}

// A flagged pair's section: its shared runs listed, then both files side by side.
std::string pairSection(std::size_t index, const SimilarPair& p, const std::map<std::string, std::string>& files,
                        const std::set<std::string>& given) {
    using writers::htmlText;
    char figure[64];
    std::snprintf(figure, sizeof figure, "%.0f %%", p.percent);
    std::ostringstream out;
    out << "<section id=\"pair" << index << "\">\n<h3>" << htmlText(p.a) << " and " << htmlText(p.b) << ": " << figure
        << ", flagged by " << flaggedBy(p) << "</h3>\n<p class=\"muted\">Shared runs: ";
    std::vector<std::pair<int, int>> a, b;
    for (std::size_t i = 0; i < p.runs.size(); ++i) {
        const SharedRun& r = p.runs[i];
        a.emplace_back(r.aFirst, r.aLast);
        b.emplace_back(r.bFirst, r.bLast);
        out << (i ? "; " : "") << i + 1 << ". lines " << r.aFirst << "-" << r.aLast << " of " << htmlText(p.a)
            << " and " << r.bFirst << "-" << r.bLast << " of " << htmlText(p.b) << ", " << r.tokens << " tokens";
    }
    if (p.runs.empty()) out << "none listed";
    out << ".</p>\n<div class=\"pair\">" << sideColumn(p.a, files.at(p.a), given, a)
        << sideColumn(p.b, files.at(p.b), given, b) << "</div>\n</section>\n";
    return out.str();
}

}  // namespace

double similarityThreshold(double median, double spread) {
    return std::clamp(median + 3 * spread, 50.0, 100.0);
}

std::string flaggedBy(const SimilarPair& pair) {
    if (pair.overFloor && pair.overClass) return "floor, class";
    return pair.overFloor ? "floor" : pair.overClass ? "class" : "";
}

std::string withoutStarter(const std::string& text, const std::string& starter) {
    return studentLines(text, linesOf(starter)).text;
}

std::map<std::pair<std::size_t, std::size_t>, std::vector<SharedRun>> parseSimRuns(const std::string& output) {
    static const std::regex line(R"(^(\d+)\.cpp: line (\d+)-(\d+)\s*\|(\d+)\.cpp: line (\d+)-(\d+)\s*\[(\d+)\]$)");
    std::map<std::pair<std::size_t, std::size_t>, std::vector<SharedRun>> runs;
    std::istringstream in(output);
    for (std::string text; std::getline(in, text);) {
        std::smatch m;
        if (!std::regex_match(text, m, line)) continue;
        std::size_t a = std::stoul(m[1]), b = std::stoul(m[4]);
        SharedRun run{std::stoi(m[2]), std::stoi(m[3]), std::stoi(m[5]), std::stoi(m[6]), std::stoi(m[7])};
        if (a == b) continue;
        if (a > b) {
            std::swap(a, b);
            std::swap(run.aFirst, run.bFirst);
            std::swap(run.aLast, run.bLast);
        }
        runs[{a, b}].push_back(run);
    }
    for (auto& [pair, list] : runs) {
        std::stable_sort(list.begin(), list.end(),
                         [](const SharedRun& x, const SharedRun& y) { return x.tokens > y.tokens; });
    }
    return runs;
}

SimilarityReport compareSubmissions(const std::map<std::string, std::string>& files, const std::string& starter,
                                    double floor) {
    if (::access(kSim, X_OK) != 0) {
        throw UsageError("similarity needs sim_c++ (Debian's similarity-tester): run scripts/install-deps");
    }
    SimilarityReport report;
    report.floor = floor;
    // The files go to sim_c++ under numbers (an id may hold any byte), the starter's lines removed.
    TempDir dir("simlab-similarity-");
    const std::set<std::string> given = linesOf(starter);
    std::vector<std::string> names;
    std::vector<std::vector<int>> kept;
    for (const auto& [id, text] : files) {
        report.ids.push_back(id);
        names.push_back(std::to_string(names.size()) + ".cpp");
        StudentLines s = studentLines(text, given);
        writeFileAtomically(dir.path() + "/" + names.back(), s.text);
        kept.push_back(std::move(s.lines));
    }
    if (report.ids.size() < 2) return report;
    // "3.cpp consists for 87 % of 5.cpp material": how much of 3.cpp lies in runs 5.cpp has too.
    static const std::regex line(R"(^(\d+)\.cpp consists for (\d+) % of (\d+)\.cpp material$)");
    std::map<std::pair<std::size_t, std::size_t>, double> share;
    std::istringstream out(runSim(dir.path(), {"-p", "-e", "-s", "-t", "1"}, names));
    for (std::string text; std::getline(out, text);) {
        std::smatch m;
        if (!std::regex_match(text, m, line)) continue;
        const std::size_t a = std::stoul(m[1]), b = std::stoul(m[3]);
        if (a >= report.ids.size() || b >= report.ids.size() || a == b) continue;
        double& s = share[{std::min(a, b), std::max(a, b)}];
        s = std::max(s, std::stod(m[2]));
    }
    std::vector<double> all;
    for (std::size_t a = 0; a < report.ids.size(); ++a) {
        for (std::size_t b = a + 1; b < report.ids.size(); ++b) {
            const auto found = share.find({a, b});
            all.push_back(found == share.end() ? 0.0 : found->second);
            if (found != share.end()) {
                SimilarPair pair;
                pair.a = report.ids[a];
                pair.b = report.ids[b];
                pair.percent = found->second;
                report.pairs.push_back(pair);
            }
        }
    }
    std::sort(report.pairs.begin(), report.pairs.end(), [](const SimilarPair& x, const SimilarPair& y) {
        return x.percent != y.percent ? x.percent > y.percent : std::tie(x.a, x.b) < std::tie(y.a, y.b);
    });
    report.median = medianOf(all);
    // The spread: the median absolute deviation, scaled to a standard deviation's size (1.4826 for a normal
    // class), robust to the few pairs that matter here.
    std::vector<double> deviations;
    for (double v : all) deviations.push_back(std::abs(v - report.median));
    report.spread = 1.4826 * medianOf(deviations);
    report.threshold = similarityThreshold(report.median, report.spread);
    for (SimilarPair& p : report.pairs) {
        p.overFloor = p.percent >= report.floor;
        p.overClass = p.percent >= report.threshold;
        if (p.overFloor || p.overClass) report.flagged.push_back(p);
    }
    addRuns(report, dir.path(), names, kept);
    return report;
}

std::string similarityHtml(const std::string& title, const SimilarityReport& report,
                           const std::map<std::string, std::string>& files, const std::string& starter) {
    using writers::htmlText;
    const std::set<std::string> given = linesOf(starter);
    char figure[64];
    std::ostringstream out;
    out << writers::pageStart(title + ": similar submissions");
    out << "<style>.pair{display:flex;gap:1em}.side{flex:1;min-width:0}.side pre{overflow-x:auto;font-size:85%}"
           ".side mark{color:inherit}mark.r0{background:#f5d76e80}mark.r1{background:#7fb2f080}"
           "mark.r2{background:#8fd19e80}@media (prefers-color-scheme: dark){mark.r0{background:#9a7b0080}"
           "mark.r1{background:#1f5fae80}mark.r2{background:#2e7d3c80}}</style>\n";
    out << "<header>\n<h1>" << htmlText(title) << ": similar submissions</h1>\n<p>"
        << report.ids.size() << " files compared in pairs by sim_c++ (similarity-tester), the starter's lines removed. ";
    char rules[256];
    std::snprintf(rules, sizeof rules,
                  "A pair is flagged when one file holds at least %.0f %% of the other in shared runs of tokens "
                  "(the floor), or at least %.0f %% (the class: its median pair, %.0f %%, and three times its "
                  "spread, %.0f %%, at least 50 %%).",
                  report.floor, report.threshold, report.median, report.spread);
    out << rules << "</p>\n</header>\n";
    out << "<section>\n<h2>Flagged pairs</h2>\n";
    if (report.flagged.empty()) out << "<p>No pair.</p>\n";
    else {
        out << "<table>\n<thead><tr><th>student</th><th>student</th><th class=\"num\">shared</th>"
               "<th>flagged by</th></tr></thead>\n<tbody>\n";
        for (std::size_t i = 0; i < report.flagged.size(); ++i) {
            const SimilarPair& p = report.flagged[i];
            std::snprintf(figure, sizeof figure, "%.0f %%", p.percent);
            out << "<tr><td class=\"name\"><a href=\"#pair" << i << "\">" << htmlText(p.a)
                << "</a></td><td class=\"name\">" << htmlText(p.b) << "</td><td class=\"num\">" << figure << "</td><td>"
                << flaggedBy(p) << "</td></tr>\n";
        }
        out << "</tbody>\n</table>\n";
    }
    out << "</section>\n";
    for (std::size_t i = 0; i < report.flagged.size(); ++i) out << pairSection(i, report.flagged[i], files, given);
    out << "<section>\n<h2>The most alike pairs</h2>\n<p class=\"muted\">At most 200, most alike first: ";
    for (std::size_t i = 0; i < report.pairs.size() && i < 200; ++i) {
        const SimilarPair& p = report.pairs[i];
        std::snprintf(figure, sizeof figure, " %.0f %%", p.percent);
        out << htmlText(p.a) << " &amp; " << htmlText(p.b) << figure << "; ";
    }
    out << "</p>\n</section>\n" << writers::pageEnd();
    return out.str();
}

}  // namespace simlab::engine
