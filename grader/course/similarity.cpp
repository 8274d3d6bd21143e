#include "simlab/course/similarity.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
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

// The starter's code is found in a file as runs of at least this many tokens, identifiers, numbers and strings
// compared by kind (a renamed starter is still the starter). Short runs are left: a student's own `x.f(y);` is
// not the starter's.
constexpr std::size_t kStarterRun = 8;

const std::set<std::string>& cppKeywords() {
    static const std::set<std::string> words = {
        "alignas",     "alignof",   "and",        "and_eq",    "asm",      "auto",         "bitand",
        "bitor",       "bool",      "break",      "case",      "catch",    "char",         "char8_t",
        "char16_t",    "char32_t",  "class",      "compl",     "concept",  "const",        "consteval",
        "constexpr",   "constinit", "const_cast", "continue",  "co_await", "co_return",    "co_yield",
        "decltype",    "default",   "delete",     "do",        "double",   "dynamic_cast", "else",
        "enum",        "explicit",  "export",     "extern",    "false",    "float",        "for",
        "friend",      "goto",      "if",         "inline",    "int",      "long",         "mutable",
        "namespace",   "new",       "noexcept",   "not",       "not_eq",   "nullptr",      "operator",
        "or",          "or_eq",     "private",    "protected", "public",   "register",     "reinterpret_cast",
        "requires",    "return",    "short",      "signed",    "sizeof",   "static",       "static_assert",
        "static_cast", "struct",    "switch",     "template",  "this",     "thread_local", "throw",
        "true",        "try",       "typedef",    "typeid",    "typename", "union",        "unsigned",
        "using",       "virtual",   "void",       "volatile",  "wchar_t",  "while",        "xor",
        "xor_eq"};
    return words;
}

// The alternative tokens (and, or, not_eq, ...) and the digraphs (<% %> <: :> %: %:%:), each with the
// punctuator it is: a copy that spells its braces or its logic so is read as the file it copies.
const std::map<std::string, std::string>& alternativeTokens() {
    static const std::map<std::string, std::string> words = {
        {"and", "&&"},    {"and_eq", "&="}, {"bitand", "&"}, {"bitor", "|"}, {"compl", "~"},  {"not", "!"},
        {"not_eq", "!="}, {"or", "||"},     {"or_eq", "|="}, {"xor", "^"},   {"xor_eq", "^="}};
    return words;
}

const std::vector<std::pair<std::string, std::string>>& digraphs() {
    static const std::vector<std::pair<std::string, std::string>> pairs = {{"%:%:", "##"}, {"<%", "{"}, {"%>", "}"},
                                                                           {"<:", "["},    {":>", "]"}, {"%:", "#"}};
    return pairs;
}

bool identifierStart(unsigned char c) { return std::isalpha(c) || c == '_' || c >= 0x80; }
bool identifierPart(unsigned char c) { return std::isalnum(c) || c == '_' || c >= 0x80; }

// The lines as the compiler reads them: a backslash at the end of a line (spaces after it allowed, as g++ allows
// them) joins it to the next, so that a name or keyword cut in two is still the one token. `lineOf` gets the line
// of the file each character came from, and one more entry for the end.
std::string joinedLines(const std::string& source, std::vector<int>& lineOf) {
    std::string text;
    text.reserve(source.size());
    lineOf.clear();
    lineOf.reserve(source.size() + 1);
    int line = 1;
    for (std::size_t k = 0; k < source.size(); ++k) {
        if (source[k] == '\\') {
            std::size_t after = k + 1;
            while (after < source.size() && (source[after] == ' ' || source[after] == '\t' || source[after] == '\r'))
                ++after;
            if (after < source.size() && source[after] == '\n') {
                k = after;
                ++line;
                continue;
            }
        }
        text += source[k];
        lineOf.push_back(line);
        line += source[k] == '\n';
    }
    lineOf.push_back(line);
    return text;
}

// The length of the punctuator at `at` in `text` (1 for a character of its own); for a digraph, `spelling` gets the
// punctuator it stands for.
std::size_t punctuatorAt(const std::string& text, std::size_t at, std::string& spelling) {
    // The punctuators of two and three characters, longest first.
    static const std::vector<std::string> punctuators = {"<=>", "<<=", ">>=", "...", "->*", "::", "->", "++", "--",
                                                         "<<",  ">>",  "<=",  ">=",  "==",  "!=", "&&", "||", "+=",
                                                         "-=",  "*=",  "/=",  "%=",  "&=",  "|=", "^=", ".*", "##"};
    // A digraph, but for <:: not followed by : or >, which is < and :: (std::vector<::T>).
    const bool lessScope =
        text.compare(at, 3, "<::") == 0 && (at + 3 >= text.size() || (text[at + 3] != ':' && text[at + 3] != '>'));
    for (const auto& [digraph, usual] : digraphs()) {
        if (!lessScope && text.compare(at, digraph.size(), digraph) == 0) {
            spelling = usual;
            return digraph.size();
        }
    }
    for (const std::string& p : punctuators) {
        if (text.compare(at, p.size(), p) == 0) return p.size();
    }
    return 1;
}

double medianOf(std::vector<double> values) {
    if (values.empty()) return 0;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

// A file without the starter's code, as sim_c++ reads it: its tokens on their own lines (so that the lines of a
// shared run are the file's), each string and character literal as an empty one (sim_c++ compares them all
// alike), and the lines of the starter's code that were removed.
struct StudentTokens {
    std::string text;
    std::set<int> starterLines;  // lines the starter's code took whole
};

StudentTokens studentTokens(const std::string& text, const std::vector<CppToken>& starter) {
    const std::vector<CppToken> tokens = cppTokens(text);
    std::vector<bool> given(tokens.size(), false);
    if (starter.size() >= kStarterRun && tokens.size() >= kStarterRun) {
        // The starter's runs of kStarterRun tokens, by their kinds; each place the file has one is the starter's.
        std::set<std::vector<std::string>> runs;
        for (std::size_t i = 0; i + kStarterRun <= starter.size(); ++i) {
            std::vector<std::string> run;
            for (std::size_t j = i; j < i + kStarterRun; ++j) run.push_back(starter[j].kind);
            runs.insert(std::move(run));
        }
        std::vector<std::string> window;
        for (std::size_t i = 0; i + kStarterRun <= tokens.size(); ++i) {
            window.clear();
            for (std::size_t j = i; j < i + kStarterRun; ++j) window.push_back(tokens[j].kind);
            if (runs.count(window))
                std::fill(given.begin() + static_cast<std::ptrdiff_t>(i),
                          given.begin() + static_cast<std::ptrdiff_t>(i + kStarterRun), true);
        }
    }
    StudentTokens out;
    std::map<int, std::string> lines;
    std::map<int, bool> whole;  // each line's tokens were all the starter's
    for (std::size_t i = 0; i < tokens.size(); ++i) {
        const CppToken& t = tokens[i];
        whole.emplace(t.line, true);
        if (given[i]) continue;
        whole[t.line] = false;
        std::string& line = lines[t.line];
        line += (line.empty() ? "" : " ") + (t.kind == "STR" ? std::string("\"\"") : t.kind == "CHR" ? "'c'" : t.text);
    }
    for (const auto& [line, all] : whole) {
        if (all) out.starterLines.insert(line);
    }
    int at = 1;
    for (const auto& [line, code] : lines) {
        for (; at < line; ++at) out.text += "\n";
        out.text += code + "\n";
        ++at;
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

// Each flagged pair's shared runs: sim_c++ once more, on the flagged pairs' files alone, printing its runs (by the
// files' own lines: the tokens kept their lines).
void addRuns(SimilarityReport& report, const std::string& dir, const std::vector<std::string>& names) {
    if (report.flagged.empty()) return;
    std::map<std::string, std::size_t> number;
    for (std::size_t i = 0; i < report.ids.size(); ++i) number[report.ids[i]] = i;
    std::set<std::size_t> involved;
    for (const SimilarPair& p : report.flagged) involved.insert({number[p.a], number[p.b]});
    std::vector<std::string> some;
    for (std::size_t i : involved) some.push_back(names[i]);
    const auto runs = parseSimRuns(runSim(dir, {"-n", "-e", "-s"}, some));
    for (SimilarPair& p : report.flagged) {
        const auto found = runs.find({number[p.a], number[p.b]});
        if (found != runs.end()) p.runs = found->second;
    }
}

// A file as a column: its lines, those in a shared run marked (by the run, in turn of three colours), those of the
// starter's code dimmed. `ranges` holds each run's first and last line, most tokens first.
std::string sideColumn(const std::string& id, const std::string& text, const std::set<int>& given,
                       const std::vector<std::pair<int, int>>& ranges) {
    std::ostringstream out;
    out << "<div class=\"side\"><h4>" << writers::htmlText(id) << "</h4><pre>";
    std::istringstream in(text);
    int number = 0;
    for (std::string line; std::getline(in, line);) {
        ++number;
        std::size_t run = 0;
        while (run < ranges.size() && (number < ranges[run].first || number > ranges[run].second)) ++run;
        if (given.count(number)) out << "<span class=\"muted\">" << writers::htmlBlock(line) << "</span>";
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
                        const std::map<std::string, std::set<int>>& given) {
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
    static const std::set<int> none;
    const auto starterOf = [&](const std::string& id) -> const std::set<int>& {
        const auto found = given.find(id);
        return found == given.end() ? none : found->second;
    };
    out << ".</p>\n<div class=\"pair\">" << sideColumn(p.a, files.at(p.a), starterOf(p.a), a)
        << sideColumn(p.b, files.at(p.b), starterOf(p.b), b) << "</div>\n</section>\n";
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

std::vector<CppToken> cppTokens(const std::string& source) {
    std::vector<int> lineOf;
    const std::string text = joinedLines(source, lineOf);
    std::vector<CppToken> tokens;
    const std::size_t n = text.size();
    std::size_t i = 0;
    bool lineStart = true;  // only spaces so far on this line: a '#' here begins a directive
    auto advance = [&](std::size_t to) { i = std::min(to, n); };
    while (i < n) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if (c == '\n') {
            ++i;
            lineStart = true;
            continue;
        }
        if (std::isspace(c)) {
            ++i;
            continue;
        }
        if (text.compare(i, 2, "//") == 0) {
            advance(std::min(n, text.find('\n', i)));
            continue;
        }
        if (text.compare(i, 2, "/*") == 0) {
            const std::size_t end = text.find("*/", i + 2);
            advance(end == std::string::npos ? n : end + 2);
            continue;
        }
        const bool directive = lineStart && (c == '#' || text.compare(i, 2, "%:") == 0);
        lineStart = false;
        if (directive) {
            // A directive: #include lines are no one's work (sim_c++ skips them too); the others are read as code.
            std::size_t at = i + (c == '#' ? 1 : 2);
            while (at < n && (text[at] == ' ' || text[at] == '\t')) ++at;
            if (text.compare(at, 7, "include") == 0) {
                std::size_t end = i;
                while (end < n && text[end] != '\n') end += text[end] == '\\' && end + 1 < n ? 2 : 1;
                advance(end);
                continue;
            }
        }
        const int first = lineOf[i];
        const std::size_t start = i;
        std::string spelling;  // the token's usual spelling, where it was written another way
        std::string kind;
        // A string or character literal, with its prefix (u8, u, U, L, R): raw strings to their delimiter.
        std::size_t prefix = 0;
        while (prefix < 3 && i + prefix < n && std::strchr("u8ULR", text[i + prefix]) && text[i + prefix] != '\0')
            ++prefix;
        const bool raw = prefix > 0 && text[i + prefix - 1] == 'R';
        if (i + prefix < n && (text[i + prefix] == '"' || text[i + prefix] == '\'') &&
            (prefix == 0 || !identifierPart(static_cast<unsigned char>(start > 0 ? text[start - 1] : ' ')))) {
            const char quote = text[i + prefix];
            std::size_t at = i + prefix + 1;
            if (raw && quote == '"') {
                const std::size_t open = text.find('(', at);
                const std::string close =
                    ")" + (open == std::string::npos ? std::string() : text.substr(at, open - at)) + "\"";
                const std::size_t end = open == std::string::npos ? std::string::npos : text.find(close, open);
                at = end == std::string::npos ? n : end + close.size();
            } else {
                while (at < n && text[at] != quote && text[at] != '\n') at += text[at] == '\\' && at + 1 < n ? 2 : 1;
                if (at < n && text[at] == quote) ++at;
            }
            kind = quote == '"' ? "STR" : "CHR";
            advance(at);
        } else if (identifierStart(c)) {
            std::size_t at = i;
            while (at < n && identifierPart(static_cast<unsigned char>(text[at]))) ++at;
            const std::string word = text.substr(i, at - i);
            const auto alternative = alternativeTokens().find(word);
            if (alternative != alternativeTokens().end()) kind = spelling = alternative->second;
            else kind = cppKeywords().count(word) ? word : "ID";
            i = at;
        } else if (std::isdigit(c) ||
                   (c == '.' && i + 1 < n && std::isdigit(static_cast<unsigned char>(text[i + 1])))) {
            // A pp-number: digits, letters, '.', digit separators, and a sign after an exponent.
            std::size_t at = i + 1;
            while (at < n) {
                const char d = text[at];
                if (std::strchr("eEpP", d) && at + 1 < n && (text[at + 1] == '+' || text[at + 1] == '-')) at += 2;
                else if (std::isalnum(static_cast<unsigned char>(d)) || d == '.' || d == '_' ||
                         (d == '\'' && at + 1 < n && std::isalnum(static_cast<unsigned char>(text[at + 1]))))
                    ++at;
                else break;
            }
            kind = "NUM";
            i = at;
        } else {
            const std::size_t length = punctuatorAt(text, i, spelling);
            kind = spelling.empty() ? text.substr(i, length) : spelling;
            i += length;
        }
        tokens.push_back({spelling.empty() ? text.substr(start, i - start) : spelling, kind, first});
    }
    return tokens;
}

std::string withoutStarter(const std::string& text, const std::string& starter) {
    return studentTokens(text, cppTokens(starter)).text;
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
    // The files go to sim_c++ under numbers (an id may hold any byte), the starter's code removed by its tokens.
    TempDir dir("simlab-similarity-");
    const std::vector<CppToken> given = cppTokens(starter);
    std::vector<std::string> names;
    for (const auto& [id, text] : files) {
        report.ids.push_back(id);
        names.push_back(std::to_string(names.size()) + ".cpp");
        StudentTokens s = studentTokens(text, given);
        writeFileAtomically(dir.path() + "/" + names.back(), s.text);
        report.starterLines[id] = std::move(s.starterLines);
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
    addRuns(report, dir.path(), names);
    return report;
}

std::string similarityHtml(const std::string& title, const SimilarityReport& report,
                           const std::map<std::string, std::string>& files) {
    using writers::htmlText;
    char figure[64];
    std::ostringstream out;
    out << writers::pageStart(title + ": similar submissions");
    out << "<style>.pair{display:flex;gap:1em}.side{flex:1;min-width:0}.side pre{overflow-x:auto;font-size:85%}"
           ".side mark{color:inherit}mark.r0{background:#f5d76e80}mark.r1{background:#7fb2f080}"
           "mark.r2{background:#8fd19e80}@media (prefers-color-scheme: dark){mark.r0{background:#9a7b0080}"
           "mark.r1{background:#1f5fae80}mark.r2{background:#2e7d3c80}}</style>\n";
    out << "<header>\n<h1>" << htmlText(title) << ": similar submissions</h1>\n<p>" << report.ids.size()
        << " files compared in pairs by sim_c++ (similarity-tester), the starter's code removed by its tokens "
           "(whatever its names). ";
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
    for (std::size_t i = 0; i < report.flagged.size(); ++i)
        out << pairSection(i, report.flagged[i], files, report.starterLines);
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
