#include "simlab/writers/html.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "simlab/common/text.h"

namespace simlab::engine::writers {

namespace {

// Readable on screen and on paper, light or dark by the reader's setting; no web fonts.
const char kStyle[] = R"(
:root { color-scheme: light dark; --bg: #ffffff; --fg: #1b1f24; --muted: #57606a; --line: #d0d7de; --soft: #f6f8fa;
        --pass: #1a7f37; --pass-bg: #dafbe1; --fail: #b42318; --fail-bg: #ffebe9; --error: #9a6700;
        --error-bg: #fff8c5; --bar: #3b6fb6; --accent: #0b57d0; }
@media (prefers-color-scheme: dark) {
  :root { --bg: #0d1117; --fg: #e6edf3; --muted: #9da7b1; --line: #3d444d; --soft: #161b22; --pass: #56d364; --pass-bg: #12361f;
          --fail: #ff7b72; --fail-bg: #3d1414; --error: #e3b341; --error-bg: #3a2d05; --bar: #6ea0e6;
          --accent: #79b8ff; } }
* { box-sizing: border-box; }
html { background: var(--bg); }
body { font: 15px/1.5 system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif; color: var(--fg);
       background: var(--bg); max-width: 1100px; margin: 0 auto; padding: 24px 28px 48px; }
h1 { font-size: 1.6em; margin: 0 0 4px; overflow-wrap: anywhere; }
h2 { font-size: 1.25em; margin: 32px 0 8px; padding-bottom: 4px; border-bottom: 1px solid var(--line); }
h3 { font-size: 1.05em; margin: 18px 0 6px; overflow-wrap: anywhere; }
section.test h3 { margin-top: 0; }
p { margin: 6px 0 10px; }
a { color: var(--accent); }
.muted { color: var(--muted); }
.score { font-size: 1.3em; margin: 8px 0 12px; }
.score strong { font-size: 1.3em; }
nav a { margin-right: 14px; }
table { border-collapse: collapse; width: 100%; margin: 8px 0 16px; }
th, td { text-align: left; vertical-align: top; padding: 6px 10px; border-bottom: 1px solid var(--line); }
th { font-weight: 600; color: var(--muted); font-size: 0.9em; border-bottom-width: 2px; }
td.num, th.num { text-align: right; white-space: nowrap; font-variant-numeric: tabular-nums; }
td.name { overflow-wrap: anywhere; }
tbody tr:hover { background: var(--soft); }
.badge { display: inline-block; padding: 1px 8px; border-radius: 10px; font-size: 0.85em; white-space: nowrap;
         border: 1px solid currentColor; }
.pass { color: var(--pass); background: var(--pass-bg); }
.fail { color: var(--fail); background: var(--fail-bg); }
.error { color: var(--error); background: var(--error-bg); }
pre, code { font: 13px/1.45 ui-monospace, "DejaVu Sans Mono", Menlo, Consolas, monospace; }
pre { background: var(--soft); border: 1px solid var(--line); border-radius: 6px; padding: 10px 12px;
      overflow-x: auto; white-space: pre-wrap; overflow-wrap: anywhere; }
code { background: var(--soft); padding: 1px 5px; border-radius: 4px; overflow-wrap: anywhere; }
section.test { border: 1px solid var(--line); border-left-width: 4px; border-radius: 6px; padding: 12px 16px;
               margin: 12px 0; }
section.test.pass { border-left-color: var(--pass); }
section.test.fail { border-left-color: var(--fail); }
section.test.error { border-left-color: var(--error); }
section.test.pass, section.test.fail, section.test.error { color: var(--fg); background: none; }
section.test ul { margin: 6px 0 10px; padding-left: 22px; }
section.test > :last-child { margin-bottom: 0; }
.figure { white-space: nowrap; }
svg { display: block; overflow: visible; }
td svg { margin-top: 4px; }
svg text { fill: var(--muted); font: 11px system-ui, sans-serif; }
svg .bar { fill: var(--bar); }
svg .track { fill: var(--soft); stroke: var(--line); }
svg .passbar { fill: var(--pass); }
svg .axis { stroke: var(--line); }
svg .median { stroke: var(--fg); stroke-width: 2; }
svg .count { fill: var(--fg); }
figure { margin: 12px 0 8px; }
figcaption { color: var(--muted); max-width: 60em; }
details.data { margin: 0 0 16px; }
details.data summary { cursor: pointer; color: var(--accent); }
details.data table { width: auto; margin: 8px 0 12px; }
caption { text-align: left; font-weight: 600; padding: 4px 0; }
.skip { position: absolute; left: -10000px; }
.skip:focus { position: static; }
footer { margin-top: 36px; color: var(--muted); font-size: 0.9em; }
)";

}  // namespace

// printable leaves no control character but, in a block, newlines and tabs; XML's escapes are HTML's too.
std::string htmlText(const std::string& text) { return xmlText(printable(text)); }

std::string htmlBlock(const std::string& text) { return xmlText(printable(text, true)); }

std::string urlSegment(const std::string& bytes) {
    std::string out;
    for (unsigned char c : bytes) {
        const bool unreserved = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
                                c == '-' || c == '.' || c == '_' || c == '~';
        if (unreserved) {
            out += static_cast<char>(c);
        } else {
            char hex[4];
            std::snprintf(hex, sizeof hex, "%%%02X", c);
            out += hex;
        }
    }
    return out;
}

std::string pageStart(const std::string& title) {
    std::ostringstream out;
    out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
        // Nothing fetched and no script: inline style, and pictures only from data URIs inside the page.
        << "<meta http-equiv=\"Content-Security-Policy\" "
           "content=\"default-src 'none'; style-src 'unsafe-inline'; img-src data:\">\n"
        << "<title>" << htmlText(title) << "</title>\n<style>" << kStyle << "</style>\n</head>\n<body>\n";
    return out.str();
}

std::string pageEnd() { return "</body>\n</html>\n"; }

const char* outcomeClass(const std::string& outcome) {
    if (outcome == "passed") return "pass";
    if (outcome == "failed") return "fail";
    return "error";
}

std::string outcomeBadge(const std::string& outcome) {
    const std::string kind = outcomeClass(outcome);
    const char* symbol = kind == "pass" ? "\u2713" : kind == "fail" ? "\u2717" : "\u26A0";
    return "<span class=\"badge " + kind + "\"><span aria-hidden=\"true\">" + symbol + "</span> " + htmlText(outcome) +
           "</span>";
}

namespace {

// The text of the first <NAME ...>...</NAME> element in `svg` (its character data, entities replaced), or "".
std::string svgElementText(const std::string& svg, const std::string& name, const std::string& attributes = "") {
    const std::string open = "<" + name + attributes + ">", close = "</" + name + ">";
    const std::size_t start = svg.find(open);
    if (start == std::string::npos) return "";
    const std::size_t end = svg.find(close, start + open.size());
    if (end == std::string::npos) return "";
    const std::string raw = svg.substr(start + open.size(), end - start - open.size());
    std::string text;
    for (std::size_t i = 0; i < raw.size(); ++i) {
        if (raw[i] != '&') {
            text += raw[i];
            continue;
        }
        const std::size_t semicolon = raw.find(';', i);
        if (semicolon == std::string::npos || semicolon - i > 10) {
            text += raw[i];
            continue;
        }
        const std::string entity = raw.substr(i + 1, semicolon - i - 1);
        static const std::pair<const char*, const char*> named[] = {
            {"amp", "&"}, {"lt", "<"}, {"gt", ">"}, {"quot", "\""}, {"apos", "'"}};
        bool replaced = false;
        for (const auto& [n, c] : named) {
            if (entity == n) text += c, replaced = true;
        }
        if (!replaced && entity.size() > 1 && entity[0] == '#') {
            const long code = entity[1] == 'x' ? std::strtol(entity.c_str() + 2, nullptr, 16)
                                                : std::strtol(entity.c_str() + 1, nullptr, 10);
            if (code > 0 && code < 0x80) text += static_cast<char>(code), replaced = true;
        }
        if (!replaced) {
            text += raw[i];
            continue;
        }
        i = semicolon;
    }
    return text;
}

// The words a drawing shows (the character data of its <text> elements, in its order, each once), for a picture
// that says nothing of itself: at most 60 of them, joined by "; ".
std::string drawnWords(const std::string& svg) {
    std::vector<std::string> words;
    for (std::size_t at = svg.find("<text"); at != std::string::npos && words.size() < 60; at = svg.find("<text", at)) {
        const std::size_t open = svg.find('>', at), close = svg.find("</text>", at);
        if (open == std::string::npos || close == std::string::npos || close < open) break;
        std::string inner = svg.substr(open + 1, close - open - 1);
        std::string plain;  // without the tags inside (<tspan>)
        bool tag = false;
        for (const char c : inner) {
            if (c == '<') tag = true;
            else if (c == '>') tag = false;
            else if (!tag) plain += c;
        }
        const std::string text = svgElementText("<t>" + plain + "</t>", "t");
        const std::size_t first = text.find_first_not_of(" \t\n");
        if (first != std::string::npos) {
            const std::string word = text.substr(first, text.find_last_not_of(" \t\n") - first + 1);
            if (std::find(words.begin(), words.end(), word) == words.end()) words.push_back(word);
        }
        at = close + 7;
    }
    std::string out;
    for (const std::string& w : words) out += (out.empty() ? "" : "; ") + w;
    return out;
}

// A value of the points' JSON as a table shows it: up to 10 significant digits, as the plot was drawn from.
std::string cellNumber(const nlohmann::json& v) {
    if (!v.is_number()) return "";
    const double x = v.get<double>();
    if (!std::isfinite(x)) return "";
    char text[32];
    std::snprintf(text, sizeof text, "%.10g", x == 0 ? 0.0 : x);
    return text;
}

std::string jsonText(const nlohmann::json& object, const char* key) {
    const auto it = object.find(key);
    return it != object.end() && it->is_string() ? it->get<std::string>() : std::string();
}

// The tables of a plot's points (simlab/plot.h's plotDataJson): per panel, the curves that share their x in one table,
// a column each, then the points marked. Empty when `data` is not such a document.
std::string pointTables(const nlohmann::json& data) {
    using nlohmann::json;
    std::ostringstream out;
    const auto panels = data.find("panels");
    if (panels == data.end() || !panels->is_array()) return "";
    for (const json& panel : *panels) {
        if (!panel.is_object()) continue;
        const std::string xLabel = jsonText(panel, "x"), yLabel = jsonText(panel, "y");
        const auto curves = panel.find("curves");
        std::vector<const json*> pending;
        if (curves != panel.end() && curves->is_array()) {
            for (const json& c : *curves) {
                if (c.is_object() && c.contains("x") && c["x"].is_array() && c.contains("y") && c["y"].is_array() &&
                    c["x"].size() == c["y"].size() && !c["x"].empty()) {
                    pending.push_back(&c);
                }
            }
        }
        while (!pending.empty()) {
            // The first curve left, and those after it drawn at the same x.
            std::vector<const json*> group{pending.front()};
            std::vector<const json*> rest;
            for (std::size_t i = 1; i < pending.size(); ++i) {
                ((*pending[i])["x"] == (*pending.front())["x"] ? group : rest).push_back(pending[i]);
            }
            pending = rest;
            const json& first = *group.front();
            const std::size_t rows = first["x"].size();
            const std::size_t drawn = first.contains("points") && first["points"].is_number_unsigned()
                                          ? first["points"].get<std::size_t>()
                                          : rows;
            std::string names;
            for (std::size_t i = 0; i < group.size(); ++i) {
                names += (i == 0 ? "" : i + 1 == group.size() ? " and " : ", ") + jsonText(*group[i], "title");
            }
            const bool samples = first.value("samples", false);
            out << "<table>\n<caption>" << htmlText(names) << ": " << htmlText(yLabel) << " against "
                << htmlText(xLabel) << ", " << (samples ? "samples" : "points of the line");
            if (drawn > rows) out << ", " << rows << " of " << drawn << " evenly spread";
            out << "</caption>\n<thead><tr><th scope=\"col\">" << htmlText(xLabel) << "</th>";
            for (const json* c : group) out << "<th scope=\"col\">" << htmlText(jsonText(*c, "title")) << "</th>";
            out << "</tr></thead>\n<tbody>\n";
            for (std::size_t r = 0; r < rows; ++r) {
                out << "<tr><th scope=\"row\" class=\"num\">" << cellNumber(first["x"][r]) << "</th>";
                for (const json* c : group) out << "<td class=\"num\">" << cellNumber((*c)["y"][r]) << "</td>";
                out << "</tr>\n";
            }
            out << "</tbody>\n</table>\n";
        }
        const auto marks = panel.find("marks");
        if (marks != panel.end() && marks->is_array() && !marks->empty()) {
            out << "<table>\n<caption>Marked on " << htmlText(yLabel) << " against " << htmlText(xLabel)
                << "</caption>\n<thead><tr><th scope=\"col\">point</th><th scope=\"col\">" << htmlText(xLabel)
                << "</th><th scope=\"col\">" << htmlText(yLabel) << "</th></tr></thead>\n<tbody>\n";
            for (const json& m : *marks) {
                if (!m.is_object()) continue;
                out << "<tr><th scope=\"row\">" << htmlText(jsonText(m, "label")) << "</th><td class=\"num\">"
                    << cellNumber(m.value("x", json())) << "</td><td class=\"num\">" << cellNumber(m.value("y", json()))
                    << "</td></tr>\n";
            }
            out << "</tbody>\n</table>\n";
        }
    }
    return out.str();
}

}  // namespace

std::string figureHtml(const std::string& id, const std::string& src, const std::string& svg, const std::string& alt,
                       const std::string& link) {
    std::string title, description, tables;
    const std::string data = svgElementText(svg, "metadata", " id=\"simlab-plot-data\"");
    if (!data.empty()) {
        const nlohmann::json points = nlohmann::json::parse(data, nullptr, false);
        if (points.is_object()) {
            tables = pointTables(points);
            title = svgElementText(svg, "title");
        }
    }
    description = svgElementText(svg, "desc");
    if (description.rfind("Produced by GNUPLOT", 0) == 0) description.clear();  // gnuplot's own, not a description
    std::string shownAlt = alt;
    if (data.empty() && !svg.empty()) {
        // A drawing (a model's schematic): its own title where it is a phrase (graphviz titles a graph by its id),
        // and, where it says nothing of itself, the words it shows.
        const std::string own = svgElementText(svg, "title");
        if (own.find(' ') != std::string::npos) shownAlt = alt + ": " + own;
        if (description.empty()) {
            const std::string words = drawnWords(svg);
            if (!words.empty()) description = "The words in the drawing, in its order: " + words + ".";
        }
    }
    std::ostringstream out;
    const std::string about = id + "-about", table = id + "-data";
    out << "<figure id=\"" << htmlText(id) << "\"><img src=\"" << src << "\" alt=\""
        << htmlText(title.empty() ? shownAlt : "Plot: " + title) << "\""
        << (description.empty() ? "" : " aria-describedby=\"" + htmlText(about) + "\"")
        << " style=\"max-width: 100%\">";
    if (!description.empty() || !tables.empty() || !link.empty()) {
        out << "<figcaption>";
        if (!description.empty()) out << "<p id=\"" << htmlText(about) << "\">" << htmlText(description) << "</p>";
        std::string links;
        if (!tables.empty()) links += "<a href=\"#" + htmlText(table) + "\">Its points as tables</a> (below)";
        if (!link.empty()) {
            links += std::string(links.empty() ? "" : "; the picture: ") + "<a href=\"" + urlSegment(link) + "\">" +
                     htmlText(link) + "</a>";
        }
        if (!links.empty()) out << "<p>" << links << "</p>";
        out << "</figcaption>";
    }
    out << "</figure>\n";
    if (!tables.empty()) {
        out << "<details class=\"data\" id=\"" << htmlText(table) << "\"><summary>The points of "
            << htmlText(title.empty() ? alt : title) << ", as tables</summary>\n"
            << tables << "</details>\n";
    }
    return out.str();
}

}  // namespace simlab::engine::writers
