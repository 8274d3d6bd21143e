#include "simlab/messages.h"

#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace simlab {

namespace {

// An integrator's failed step, "Integrator step failed at time T apparently because: REASON", said with its cause
// (what a user can change) instead of Simbody's internal names; any other message is returned as it is.
std::string namedStepFailure(const std::string& message) {
    const std::string head = "Integrator step failed at time ", because = " apparently because: ";
    const std::size_t at = message.find(head);
    const std::size_t reasonAt = message.find(because);
    if (at == std::string::npos || reasonAt == std::string::npos || reasonAt < at) return message;
    const std::string time = message.substr(at + head.size(), reasonAt - at - head.size());
    const std::string reason = message.substr(reasonAt + because.size());
    char t[32];
    std::snprintf(t, sizeof t, "%.6g", std::strtod(time.c_str(), nullptr));
    if (reason.find("Unable to advance time past") != std::string::npos) {
        return std::string("the integrator could not advance past t = ") + t + " s: the steps its accuracy asks "
               "for there are too small for time to move in double precision (too fine an accuracy for its order); "
               "give a coarser accuracy or a higher-order integrator";
    }
    if (reason.find("CPodes::step() returned an error") != std::string::npos) {
        return std::string("CPodes gave up at t = ") + t + " s: no step it can take there meets the accuracy "
               "asked for; give a coarser accuracy or another integrator";
    }
    return std::string("the integrator's step failed at t = ") + t + " s: " + reason;
}

}  // namespace

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
    out = namedStepFailure(out);
    if (out.size() > maxLength) out = out.substr(0, maxLength) + "...";
    return out;
}

std::string shortNumber(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

std::string durationText(double seconds) {
    char text[64];
    if (seconds < 10) std::snprintf(text, sizeof text, "%.1f s", seconds);
    else if (seconds < 120) std::snprintf(text, sizeof text, "%.0f s", seconds);
    else if (seconds < 7200) std::snprintf(text, sizeof text, "%.0f min", seconds / 60);
    else std::snprintf(text, sizeof text, "%.1f h", seconds / 3600);
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
