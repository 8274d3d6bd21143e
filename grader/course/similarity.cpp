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

}  // namespace

double similarityThreshold(double median, double spread) {
    return std::clamp(median + 3 * spread, 50.0, 100.0);
}

std::string withoutStarter(const std::string& text, const std::string& starter) {
    const std::set<std::string> given = linesOf(starter);
    std::string out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (!trimmed(line).empty() && !given.count(trimmed(line))) out += line + "\n";
    }
    return out;
}

SimilarityReport compareSubmissions(const std::map<std::string, std::string>& files, const std::string& starter) {
    if (::access(kSim, X_OK) != 0) {
        throw UsageError("similarity needs sim_c++ (Debian's similarity-tester): run scripts/install-deps");
    }
    SimilarityReport report;
    // The files go to sim_c++ under numbers (an id may hold any byte), the starter's lines removed.
    TempDir dir("simlab-similarity-");
    std::vector<std::string> names;
    for (const auto& [id, text] : files) {
        report.ids.push_back(id);
        names.push_back(std::to_string(names.size()) + ".cpp");
        writeFileAtomically(dir.path() + "/" + names.back(), withoutStarter(text, starter));
    }
    if (report.ids.size() < 2) return report;
    isolation::ProcessRequest request;
    request.argv = {kSim, "-p", "-e", "-s", "-t", "1"};
    request.argv.insert(request.argv.end(), names.begin(), names.end());
    request.env = isolation::childEnvironment({"LC_ALL=C"});
    request.workDir = dir.path();
    request.isolate = true;
    request.handOver = {dir.path()};
    request.limits.cpuSeconds = 600;
    request.limits.wallSeconds = 1200;
    request.limits.outputKiB = 64 * 1024;
    request.keepOutput = 64 << 20;
    const isolation::ProcessResult run = isolation::runProcess(request);
    if (!run.exitedCleanly()) {
        throw UsageError("sim_c++ failed (" + (run.started ? "status " + std::to_string(run.exitCode) : run.error) + ")");
    }
    // "3.cpp consists for 87 % of 5.cpp material": how much of 3.cpp lies in runs 5.cpp has too.
    static const std::regex line(R"(^(\d+)\.cpp consists for (\d+) % of (\d+)\.cpp material$)");
    std::map<std::pair<std::size_t, std::size_t>, double> share;
    std::istringstream out(run.output);
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
            if (found != share.end()) report.pairs.push_back({report.ids[a], report.ids[b], found->second});
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
    for (const SimilarPair& p : report.pairs) {
        if (p.percent >= report.threshold) report.flagged.push_back(p);
    }
    return report;
}

std::string similarityHtml(const std::string& title, const SimilarityReport& report,
                           const std::map<std::string, std::string>& files, const std::string& starter) {
    using writers::htmlText;
    const std::set<std::string> given = linesOf(starter);
    // A file as a column: its lines, those the starter has dimmed.
    auto column = [&](const std::string& id) {
        std::ostringstream out;
        out << "<div class=\"side\"><h4>" << htmlText(id) << "</h4><pre>";
        std::istringstream in(files.at(id));
        for (std::string line; std::getline(in, line);) {
            const bool starterLine = given.count(trimmed(line)) > 0;
            out << (starterLine ? "<span class=\"muted\">" : "") << writers::htmlBlock(line)
                << (starterLine ? "</span>" : "") << "\n";
        }
        out << "</pre></div>";
        return out.str();
    };
    char figure[64];
    std::ostringstream out;
    out << writers::pageStart(title + ": similar submissions");
    out << "<style>.pair{display:flex;gap:1em}.side{flex:1;min-width:0}.side pre{overflow-x:auto;font-size:85%}</style>\n";
    out << "<header>\n<h1>" << htmlText(title) << ": similar submissions</h1>\n<p>"
        << report.ids.size() << " files compared in pairs by sim_c++ (similarity-tester), the starter's lines removed. ";
    char spread[96];
    std::snprintf(figure, sizeof figure, "%.0f %%", report.threshold);
    std::snprintf(spread, sizeof spread, "the class's median pair, %.0f %%, and three times its spread, %.0f %%",
                  report.median, report.spread);
    out << "A pair is listed when one file holds at least " << figure
        << " of the other in shared runs of tokens: " << spread << ", at least 50 %.</p>\n</header>\n";
    out << "<section>\n<h2>Far more alike than the class</h2>\n";
    if (report.flagged.empty()) out << "<p>No pair.</p>\n";
    else {
        out << "<table>\n<thead><tr><th>student</th><th>student</th><th class=\"num\">shared</th></tr></thead>\n<tbody>\n";
        for (std::size_t i = 0; i < report.flagged.size(); ++i) {
            const SimilarPair& p = report.flagged[i];
            std::snprintf(figure, sizeof figure, "%.0f %%", p.percent);
            out << "<tr><td class=\"name\"><a href=\"#pair" << i << "\">" << htmlText(p.a) << "</a></td><td class=\"name\">"
                << htmlText(p.b) << "</td><td class=\"num\">" << figure << "</td></tr>\n";
        }
        out << "</tbody>\n</table>\n";
    }
    out << "</section>\n";
    for (std::size_t i = 0; i < report.flagged.size(); ++i) {
        const SimilarPair& p = report.flagged[i];
        std::snprintf(figure, sizeof figure, "%.0f %%", p.percent);
        out << "<section id=\"pair" << i << "\">\n<h3>" << htmlText(p.a) << " and " << htmlText(p.b) << ": " << figure
            << "</h3>\n<div class=\"pair\">" << column(p.a) << column(p.b) << "</div>\n</section>\n";
    }
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
