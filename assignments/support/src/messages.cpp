#include "simlab/messages.h"

#include <cstdio>
#include <sstream>

namespace simlab {

std::string oneLineMessage(const std::string& message, std::size_t maxLength) {
    // Simbody's messages read "SimTK Exception thrown at File.cpp:123:\n  Error detected by Simbody method
    // X::f: what went wrong\n  (Required condition ... was not met.)\n..."; CPodes adds its own lines after.
    std::istringstream lines(message);
    std::string line, first;
    while (std::getline(lines, line)) {
        const std::size_t begin = line.find_first_not_of(" \t");
        if (begin == std::string::npos) continue;
        line = line.substr(begin, line.find_last_not_of(" \t\r") - begin + 1);
        if (line.rfind("SimTK Exception thrown at", 0) == 0) continue;
        const std::string detected = "Error detected by Simbody method ";
        if (line.rfind(detected, 0) == 0) {
            // "Error detected by Simbody method X::f: what went wrong" -> "X::f: what went wrong"
            line = line.substr(detected.size());
        }
        if (first.empty()) first = line;
        // A line that only names the method ("X::f:") is followed by the reason: keep both.
        if (line.back() == ':' && first == line) continue;
        if (first != line) first += " " + line;
        break;
    }
    if (first.empty()) first = message;
    // Whatever whitespace is left (tabs, a lone message's own newlines) becomes single spaces.
    std::string out;
    for (const char c : first) {
        const bool space = c == '\n' || c == '\t' || c == '\r' || c == ' ';
        if (!space) out += c;
        else if (!out.empty() && out.back() != ' ') out += ' ';
    }
    while (!out.empty() && out.back() == ' ') out.pop_back();
    if (out.size() > maxLength) out = out.substr(0, maxLength) + "...";
    return out;
}

std::string shortNumber(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

std::string markupEscaped(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += c;
        }
    }
    return out;
}

}  // namespace simlab
