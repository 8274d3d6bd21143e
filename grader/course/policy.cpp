#include "simlab/course/policy.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <regex>

#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/common/text.h"
#include "simlab/grading/report.h"
#include "simlab/writers/roster.h"

namespace fs = std::filesystem;

namespace simlab::engine {

namespace {

// Days from 1970-01-01 to the civil date y-m-d (proleptic Gregorian), as in Howard Hinnant's date algorithms.
long long daysFromCivil(long long y, unsigned m, unsigned d) {
    y -= m <= 2;
    const long long era = (y >= 0 ? y : y - 399) / 400;
    const unsigned yoe = static_cast<unsigned>(y - era * 400);
    const unsigned doy = (153 * (m > 2 ? m - 3 : m + 9) + 2) / 5 + d - 1;
    const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + static_cast<long long>(doe) - 719468;
}

std::time_t epochOf(long long y, unsigned mo, unsigned d, unsigned h, unsigned mi, unsigned s, long offsetMinutes) {
    return static_cast<std::time_t>(daysFromCivil(y, mo, d) * 86400 + h * 3600 + mi * 60 + s - offsetMinutes * 60);
}

// A TOML date-time with its offset, in seconds since 1970; a clear error without the offset.
std::time_t tomlTime(const toml::node* node, const std::string& where) {
    const auto* dt = node ? node->as_date_time() : nullptr;
    if (!dt) {
        throw UsageError(where + " is not a date-time (write it as 2026-10-02T23:59:00-07:00, with its offset)");
    }
    const toml::date_time& t = dt->get();
    if (!t.offset) throw UsageError(where + " has no offset: write Z or the zone's, as in 2026-10-02T23:59:00-07:00");
    return epochOf(t.date.year, t.date.month, t.date.day, t.time.hour, t.time.minute, t.time.second, t.offset->minutes);
}

double number(const toml::table& table, const std::string& key, double fallback, double low, double high,
              const std::string& where) {
    const toml::node* node = table.get(key);
    if (!node) return fallback;
    const std::optional<double> value = node->value<double>();
    if (!value || !std::isfinite(*value) || *value < low || *value > high) {
        throw UsageError(where + ": " + key + " must be a number from " + points(low) + " to " + points(high));
    }
    return *value;
}

// The rules of [late], then those an assignment's table changes.
void readRules(const toml::table& table, LatePolicy& p, const std::string& where) {
    p.penaltyPercent = number(table, "penalty_percent", p.penaltyPercent, 0, 100, where);
    p.maxPercent = number(table, "max_percent", p.maxPercent, 0, 100, where);
    p.graceHours = number(table, "grace_days", p.graceHours / 24, 0, 365, where) * 24;
    if (const toml::node* per = table.get("per")) {
        const std::optional<std::string> unit = per->value<std::string>();
        if (!unit || (*unit != "day" && *unit != "hour")) throw UsageError(where + ": per must be \"day\" or \"hour\"");
        p.periodHours = *unit == "day" ? 24 : 1;
    }
}

void readExtensions(const std::string& path, LatePolicy& p, const std::map<std::string, std::string>& aliases) {
    const std::string where = "extensions " + printable(path);
    if (!fs::is_regular_file(path)) throw UsageError("no " + where + " (named by " + printable(p.source) + ")");
    std::vector<std::vector<std::string>> rows;
    try {
        rows = readCsv(readFile(path));
    } catch (const UsageError& e) {
        throw UsageError(where + ": " + e.what());
    }
    if (rows.empty()) return;
    auto column = [&](const std::string& name) {
        const auto at =
            std::find_if(rows[0].begin(), rows[0].end(), [&](const std::string& c) { return trimmed(c) == name; });
        return at == rows[0].end() ? std::string::npos : static_cast<std::size_t>(at - rows[0].begin());
    };
    const std::size_t student = column("student"), due = column("due"), days = column("days");
    if (student == std::string::npos || (due == std::string::npos && days == std::string::npos)) {
        throw UsageError(where + ": its first line must name the columns student and due (or days)");
    }
    for (std::size_t r = 1; r < rows.size(); ++r) {
        const std::vector<std::string>& row = rows[r];
        auto cell = [&](std::size_t c) { return c < row.size() ? trimmed(row[c]) : std::string(); };
        const std::string who = cell(student), line = where + ", row " + std::to_string(r + 1);
        if (who.empty()) continue;
        std::time_t until = p.due;
        if (!cell(due).empty()) {
            const std::optional<std::time_t> t = parseTime(cell(due));
            if (!t)
                throw UsageError(line + ": due '" + printable(cell(due)) +
                                 "' is not a date-time such as 2026-10-05T23:59:00-07:00");
            until = *t;
        } else {
            char* end = nullptr;
            const std::string text = cell(days);
            const double d = std::strtod(text.c_str(), &end);
            if (text.empty() || *end || !std::isfinite(d) || d < 0 || d > 365) {
                throw UsageError(line + ": days '" + printable(text) + "' is not a number of days from 0 to 365");
            }
            until = p.due + static_cast<std::time_t>(std::lround(d * 86400));
        }
        const auto found = aliases.find(who);
        const std::string id = found != aliases.end() ? found->second : who;
        if (found == aliases.end() && !aliases.empty()) p.unknownStudents.push_back(who);
        p.dueFor[id] = until;
    }
}

std::string hoursText(double hours) {
    const long long minutes = std::llround(hours * 60);
    if (minutes < 60) return std::to_string(minutes) + " min";
    if (minutes < 48 * 60)
        return std::to_string(minutes / 60) + " h" + (minutes % 60 ? " " + std::to_string(minutes % 60) + " min" : "");
    return points(std::round(hours / 24 * 10) / 10) + " days";
}

}  // namespace

std::optional<std::time_t> parseTime(const std::string& text) {
    static const std::regex form(
        R"(^\s*(\d{4})-(\d{2})-(\d{2})[T ](\d{2}):(\d{2})(?::(\d{2})(?:\.\d+)?)?\s*(Z|UTC|[+-]\d{2}:?\d{2})?\s*$)");
    std::smatch m;
    if (!std::regex_match(text, m, form)) return std::nullopt;
    const auto n = [&](int i) { return m[i].matched ? std::stoi(m[i].str()) : 0; };
    if (n(2) < 1 || n(2) > 12 || n(3) < 1 || n(3) > 31 || n(4) > 23 || n(5) > 59 || n(6) > 60) return std::nullopt;
    long offset = 0;
    const std::string zone = m[7].matched ? m[7].str() : "Z";
    if (zone != "Z" && zone != "UTC") {
        std::string digits = zone.substr(1);
        digits.erase(std::remove(digits.begin(), digits.end(), ':'), digits.end());
        offset = (zone[0] == '-' ? -1 : 1) * (std::stoi(digits.substr(0, 2)) * 60 + std::stoi(digits.substr(2, 2)));
    }
    return epochOf(n(1), n(2), n(3), n(4), n(5), n(6), offset);
}

std::string utcText(std::time_t t) {
    std::tm tm{};
    gmtime_r(&t, &tm);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return text;
}

LatePolicy loadLatePolicy(const std::string& path, const std::string& assignment,
                          const std::map<std::string, std::string>& aliases) {
    LatePolicy p;
    p.source = path;
    if (path.empty() || !fs::exists(path)) return p;
    toml::table file;
    try {
        file = toml::parse_file(path);
    } catch (const toml::parse_error& e) {
        throw UsageError(printable(path) + ":" + std::to_string(e.source().begin.line) + ": " +
                         std::string(e.description()));
    }
    for (const auto& [key, value] : file) {
        const std::string k(key.str());
        if (k != "late" && !value.is_table()) {
            throw UsageError(printable(path) + ": '" + printable(k) +
                             "' is not a table ([late], or an assignment's [id])");
        }
    }
    if (const toml::table* late = file["late"].as_table()) readRules(*late, p, printable(path) + " [late]");
    const toml::table* own = file[assignment].as_table();
    if (!own) return p;
    const std::string where = printable(path) + " [" + assignment + "]";
    readRules(*own, p, where);
    if (!own->get("due")) return p;  // the rules, but no due date: nothing is late
    p.due = tomlTime(own->get("due"), where + " due");
    if (own->get("cutoff")) p.cutoff = tomlTime(own->get("cutoff"), where + " cutoff");
    p.active = true;
    if (const toml::node* ext = own->get("extensions")) {
        const std::optional<std::string> name = ext->value<std::string>();
        if (!name) throw UsageError(where + ": extensions must name a CSV file");
        readExtensions((fs::path(path).parent_path() / *name).string(), p, aliases);
    }
    return p;
}

std::vector<std::pair<std::string, std::string>> rosterColumn(const std::string& rosterPath,
                                                              const std::string& column) {
    std::vector<std::pair<std::string, std::string>> cells;
    if (!fs::is_regular_file(rosterPath)) return cells;
    const std::vector<std::vector<std::string>> rows = readCsv(readFile(rosterPath));
    if (rows.empty()) return cells;
    const auto id = std::find(rows[0].begin(), rows[0].end(), "simlab id");
    const auto at = std::find(rows[0].begin(), rows[0].end(), column);
    if (id == rows[0].end() || at == rows[0].end()) return cells;
    const auto i = static_cast<std::size_t>(id - rows[0].begin()), c = static_cast<std::size_t>(at - rows[0].begin());
    for (std::size_t r = 1; r < rows.size(); ++r) {
        if (std::max(i, c) >= rows[r].size()) continue;
        const std::string who = csvCellValue(trimmed(rows[r][i]));
        if (!who.empty()) cells.emplace_back(who, csvCellValue(trimmed(rows[r][c])));
    }
    return cells;
}

std::map<std::string, std::string> rosterAliases(const std::string& rosterPath) {
    std::map<std::string, std::string> aliases;
    for (const char* column : {"simlab id", "Student", "ID", "SIS User ID", "SIS Login ID", "Platform ID", "Email"}) {
        for (const auto& [id, value] : rosterColumn(rosterPath, column)) {
            if (!value.empty()) aliases.emplace(value, id);
        }
    }
    return aliases;
}

std::map<std::string, std::string> rosterTimes(const std::string& rosterPath) {
    std::map<std::string, std::string> times;
    for (const auto& [id, when] : rosterColumn(rosterPath, "Submitted")) {
        // Members of a group share a folder: the latest of their times.
        std::string& kept = times[id];
        if (parseTime(when) && (kept.empty() || *parseTime(when) > *parseTime(kept))) kept = when;
    }
    return times;
}

void applyLatePolicy(StudentRecord& r, const LatePolicy& p) {
    r.late = {};
    if (!p.active || r.status == "missing file") return;
    const auto own = p.dueFor.find(r.id);
    const std::time_t due = own != p.dueFor.end() ? own->second : p.due;
    const std::optional<std::time_t> handed = parseTime(r.submitted);
    if (!handed) {
        r.late.line = "no submission time known: no late penalty";
        return;
    }
    const std::string extended = own != p.dueFor.end() ? " (extended to " + utcText(due) + ")" : "";
    const double past = std::difftime(*handed, due) / 3600;
    if (p.cutoff && *handed > *p.cutoff && own == p.dueFor.end()) {
        r.late = {past, 100,
                  "handed in " + hoursText(past) + " late, after the cutoff " + utcText(*p.cutoff) + ": no credit"};
        return;
    }
    if (past <= 0) {
        r.late.line = "handed in on time" + extended;
        return;
    }
    const double charged = past - p.graceHours;
    const std::string days = points(p.graceHours / 24) + " grace day" + (p.graceHours == 24 ? "" : "s");
    const std::string grace = p.graceHours > 0 ? ", " + days : "";
    if (charged <= 0) {
        r.late = {past, 0,
                  "handed in " + hoursText(past) + " late" + extended + ", within the " + days + ": no penalty"};
        return;
    }
    const double periods = std::ceil(charged / p.periodHours - 1e-9);
    const double percent = std::min(p.maxPercent, periods * p.penaltyPercent);
    r.late = {past, percent,
              "handed in " + hoursText(past) + " late" + extended + grace + ": " + points(percent) +
                  " % of the score taken (" + points(p.penaltyPercent) + " % per " +
                  (p.periodHours == 24 ? "day" : "hour") + ")"};
}

}  // namespace simlab::engine
