// Text from students, made safe for each format simlab writes (see text.h).
#include "simlab/common/text.h"

#include <cctype>

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string_view>

namespace simlab::engine {

namespace {

const char kReplacement[] = "\xEF\xBF\xBD";  // U+FFFD

// One step through UTF-8: the code point at `at` and its length in bytes, or, if no valid sequence starts there,
// valid == false and the length of the maximal subpart (the bytes that begin a sequence that never completes).
struct Unit {
    std::uint32_t cp;
    std::size_t length;
    bool valid;
};

Unit next(const std::string& s, std::size_t at) {
    const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(s[i]); };
    const unsigned char lead = byte(at);
    if (lead < 0x80) return {lead, 1, true};
    // The well-formed sequences (Unicode table 3-7): the second byte's range rules out overlong forms, surrogates
    // and code points past U+10FFFF; every later byte is 80..BF.
    std::size_t n = 0;
    std::uint32_t cp = 0;
    unsigned char low = 0x80, high = 0xBF;
    if (lead >= 0xC2 && lead <= 0xDF) {
        n = 2, cp = lead & 0x1F;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
        n = 3, cp = lead & 0x0F, low = lead == 0xE0 ? 0xA0 : 0x80, high = lead == 0xED ? 0x9F : 0xBF;
    } else if (lead >= 0xF0 && lead <= 0xF4) {
        n = 4, cp = lead & 0x07, low = lead == 0xF0 ? 0x90 : 0x80, high = lead == 0xF4 ? 0x8F : 0xBF;
    } else {
        return {0xFFFD, 1, false};
    }
    for (std::size_t i = 1; i < n; ++i) {
        if (at + i >= s.size() || byte(at + i) < (i == 1 ? low : 0x80) || byte(at + i) > (i == 1 ? high : 0xBF)) {
            return {0xFFFD, i, false};
        }
        cp = (cp << 6) | (byte(at + i) & 0x3F);
    }
    return {cp, n, true};
}

bool shownEscaped(std::uint32_t cp) {
    return cp < 0x20 || (cp >= 0x7F && cp <= 0x9F) || cp == 0x061C || cp == 0x200E || cp == 0x200F ||
           (cp >= 0x2028 && cp <= 0x202E) || (cp >= 0x2066 && cp <= 0x2069);
}

std::string escaped(std::uint32_t cp) {
    if (cp == '\t') return "\\t";
    if (cp == '\n') return "\\n";
    if (cp == '\r') return "\\r";
    char text[16];
    std::snprintf(text, sizeof text, cp < 0x80 ? "\\x%02x" : "\\u%04x", static_cast<unsigned>(cp));
    return text;
}

}  // namespace

std::string validUtf8(const std::string& bytes) {
    std::string out;
    out.reserve(bytes.size());
    for (std::size_t at = 0; at < bytes.size();) {
        const Unit u = next(bytes, at);
        if (u.valid) out.append(bytes, at, u.length);
        else out += kReplacement;
        at += u.length;
    }
    return out;
}

bool isValidUtf8(const std::string& bytes) {
    for (std::size_t at = 0; at < bytes.size();) {
        const Unit u = next(bytes, at);
        if (!u.valid) return false;
        at += u.length;
    }
    return true;
}

std::string printable(const std::string& bytes, bool keepNewlines) {
    std::string out;
    out.reserve(bytes.size());
    for (std::size_t at = 0; at < bytes.size();) {
        const Unit u = next(bytes, at);
        if (keepNewlines && u.cp == '\r' && at + 1 < bytes.size() && bytes[at + 1] == '\n') {
            ++at;  // CR LF: the LF is kept
            continue;
        }
        if (!u.valid) out += kReplacement;
        else if (keepNewlines && (u.cp == '\n' || u.cp == '\t')) out += static_cast<char>(u.cp);
        else if (shownEscaped(u.cp)) out += escaped(u.cp);
        else out.append(bytes, at, u.length);
        at += u.length;
    }
    return out;
}

std::string trimmed(const std::string& s) {
    const std::size_t first = s.find_first_not_of(" \t");
    if (first == std::string::npos) return "";
    return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

std::string csvCellValue(const std::string& cell) {
    const std::size_t first = cell.find_first_not_of(' ', 1);
    const bool neutralized = cell.size() > 1 && cell[0] == '\'' && first != std::string::npos &&
                             std::string_view("=+-@\t\r").find(cell[first]) != std::string_view::npos;
    return neutralized ? cell.substr(1) : cell;
}

std::string csvCell(const std::string& text) {
    std::string cell = printable(text);
    const std::size_t first = text.find_first_not_of(' ');
    const std::string_view formulaStart = "=+-@\t\r";  // what a spreadsheet reads as the start of a formula
    const bool formula = first != std::string::npos && formulaStart.find(text[first]) != formulaStart.npos;
    if (formula) cell.insert(0, 1, '\'');
    if (!formula && cell.find_first_of(",\";") == std::string::npos) return cell;
    std::string quoted = "\"";
    for (char c : cell) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

std::string markdownText(const std::string& text) {
    std::string out;
    const std::string shown = printable(text);
    for (std::size_t i = 0; i < shown.size(); ++i) {
        const char c = shown[i];
        // '&' starts a character reference only before a name or '#' ("&copy;", "&#60;"): "a && b" stays as
        // written, for the student who reads the file as text.
        const bool reference =
            i + 1 < shown.size() && (std::isalnum(static_cast<unsigned char>(shown[i + 1])) || shown[i + 1] == '#');
        // '<' starts a tag, a comment or an autolink only before a letter, '/', '!' or '?': "i < n" and a student's
        // "p->x" stay as written; '>' means nothing inline (a quote's marker only at a line's start, below).
        const bool markup = i + 1 < shown.size() && (std::isalpha(static_cast<unsigned char>(shown[i + 1])) ||
                                                     std::string_view("/!?").find(shown[i + 1]) != std::string_view::npos);
        switch (c) {
            case '<': out += markup ? "&lt;" : "<"; break;
            case '&':
                out += reference ? "&amp;" : "&";
                break;
            case '\\': case '`': case '|': case '*': case '_': case '[': case ']':
                out += '\\';
                out += c;
                break;
            default: out += c;
        }
    }
    // If the text starts a line: nothing that begins a block (a heading, a list item, a setext underline, a fence
    // or, after four spaces, an indented code block).
    const std::size_t digits = out.find_first_not_of("0123456789");
    if (!out.empty() && out[0] == ' ') out.replace(0, 1, "&#32;");
    else if (!out.empty() && std::string_view("#+-=~>").find(out[0]) != std::string::npos) out.insert(0, 1, '\\');
    else if (digits != 0 && digits != std::string::npos && (out[digits] == '.' || out[digits] == ')')) {
        out.insert(digits, 1, '\\');
    }
    return out;
}

std::string xmlText(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t at = 0; at < text.size();) {
        const Unit u = next(text, at);
        switch (u.valid ? u.cp : 0xFFFD) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&apos;"; break;
            case '\t': out += "&#9;"; break;
            case '\n': out += "&#10;"; break;
            case '\r': out += "&#13;"; break;
            default:
                if (!u.valid || u.cp < 0x20 || u.cp == 0xFFFE || u.cp == 0xFFFF) out += kReplacement;
                else out.append(text, at, u.length);
        }
        at += u.length;
    }
    return out;
}

std::string shellWord(const std::string& word) {
    if (!word.empty() &&
        word.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789/._+-=:,@%") ==
            std::string::npos) {
        return word;
    }
    std::string quoted = "'";
    for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

std::string filledTemplate(std::string text, const std::map<std::string, std::string>& values) {
    for (const auto& [name, value] : values) {
        const std::string word = "@" + name + "@";
        std::size_t at = text.find(word);
        if (at == std::string::npos) throw std::logic_error("the template holds no " + word);
        for (; at != std::string::npos; at = text.find(word, at)) {
            const bool alone = (at == 0 || text[at - 1] == '\n') &&
                               (at + word.size() == text.size() || text[at + word.size()] == '\n');
            if (alone && value.empty()) {
                text.erase(at, word.size() + (at + word.size() < text.size() ? 1 : 0));
                continue;
            }
            std::string put = value;
            if (alone && !put.empty() && put.back() == '\n') put.pop_back();
            text.replace(at, word.size(), put);
            at += put.size();
        }
    }
    for (std::size_t at = text.find('@'); at != std::string::npos; at = text.find('@', at + 1)) {
        const std::size_t end = text.find('@', at + 1);
        if (end == std::string::npos) break;
        const std::string name = text.substr(at + 1, end - at - 1);
        if (!name.empty() && name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZ_") == std::string::npos) {
            throw std::logic_error("the template's @" + name + "@ was given no value");
        }
    }
    return text;
}

}  // namespace simlab::engine
