#include "simlab/writers/html.h"

#include <cstdio>
#include <sstream>

#include "simlab/common/text.h"

namespace simlab::engine::writers {

namespace {

// Readable on screen and on paper, light or dark by the reader's setting; no web fonts.
const char kStyle[] = R"(
:root { color-scheme: light dark; --fg: #1b1f24; --muted: #57606a; --line: #d0d7de; --soft: #f6f8fa;
        --pass: #1a7f37; --pass-bg: #dafbe1; --fail: #b42318; --fail-bg: #ffebe9; --error: #9a6700;
        --error-bg: #fff8c5; --bar: #3b6fb6; --accent: #0b57d0; }
@media (prefers-color-scheme: dark) {
  :root { --fg: #e6edf3; --muted: #9da7b1; --line: #3d444d; --soft: #161b22; --pass: #56d364; --pass-bg: #12361f;
          --fail: #ff7b72; --fail-bg: #3d1414; --error: #e3b341; --error-bg: #3a2d05; --bar: #6ea0e6;
          --accent: #79b8ff; } }
* { box-sizing: border-box; }
body { font: 15px/1.5 system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif; color: var(--fg);
       max-width: 1100px; margin: 0 auto; padding: 24px 28px 48px; }
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

}  // namespace simlab::engine::writers
