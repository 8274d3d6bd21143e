#include "simlab/course/policy.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>

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

// The index of the column `name` in a CSV's first row; npos when it has none.
std::size_t columnOf(const std::vector<std::string>& header, const std::string& name) {
    const auto at =
        std::find_if(header.begin(), header.end(), [&](const std::string& c) { return trimmed(c) == name; });
    return at == header.end() ? std::string::npos : static_cast<std::size_t>(at - header.begin());
}

std::vector<std::vector<std::string>> csvRows(const std::string& path, const std::string& where) {
    try {
        return readCsv(readFile(path));
    } catch (const UsageError& e) {
        throw UsageError(where + ": " + e.what());
    }
}

// The student a row of an instructor's file names, through `ids`: one line naming the row when none or two.
std::string studentOfRow(const std::string& who, const StudentIds& ids, const std::string& line) {
    if (ids.empty()) return who;  // no class to match against (a platform's autograder): the id as written
    const std::optional<std::string> id = ids.find(who, line);
    if (!id) {
        throw UsageError(line + ": '" + printable(who) +
                         "' is no student of the class (no simlab id, Canvas ID, SIS User ID, login or e-mail of "
                         "one): correct the row or remove it");
    }
    return *id;
}

// A second row for a student already given one: one line naming both rows.
void onceEach(std::map<std::string, std::size_t>& seen, const std::string& id, std::size_t row,
              const std::string& line) {
    const auto [at, first] = seen.emplace(id, row);
    if (!first) {
        throw UsageError(line + ": " + printable(id) + " has row " + std::to_string(at->second) +
                         " too: one row per student");
    }
}

void readExtensions(const std::string& path, LatePolicy& p, const StudentIds& ids) {
    const std::string where = "extensions " + printable(path);
    if (!fs::is_regular_file(path)) throw UsageError("no " + where + " (named by " + printable(p.source) + ")");
    const std::vector<std::vector<std::string>> rows = csvRows(path, where);
    if (rows.empty()) return;
    const std::size_t student = columnOf(rows[0], "student"), due = columnOf(rows[0], "due"),
                      days = columnOf(rows[0], "days");
    if (student == std::string::npos || (due == std::string::npos && days == std::string::npos)) {
        throw UsageError(where + ": its first line must name the columns student and due (or days)");
    }
    std::map<std::string, std::size_t> seen;
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
        const std::string id = studentOfRow(who, ids, line);
        onceEach(seen, id, r + 1, line);
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

LatePolicy loadLatePolicy(const std::string& path, const std::string& assignment, const StudentIds& ids) {
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
        readExtensions((fs::path(path).parent_path() / *name).string(), p, ids);
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

void StudentIds::add(const std::string& alias, const std::string& id) {
    if (!alias.empty() && !id.empty()) ids_[alias].insert(id);
}

std::optional<std::string> StudentIds::find(const std::string& alias, const std::string& where) const {
    const auto found = ids_.find(alias);
    if (found == ids_.end()) return std::nullopt;
    const std::set<std::string>& who = found->second;
    if (who.size() > 1) {
        throw UsageError(where + ": '" + printable(alias) + "' is an id of two students, " + printable(*who.begin()) +
                         " and " + printable(*std::next(who.begin())) +
                         " (their platform ids clash): name the student by their simlab id");
    }
    return *who.begin();
}

std::set<std::string> StudentIds::students() const {
    std::set<std::string> all;
    for (const auto& [alias, who] : ids_) all.insert(who.begin(), who.end());
    return all;
}

StudentIds rosterIds(const std::string& rosterPath) {
    StudentIds ids;
    // The platform's ids alone: Student is the name a student gives themselves.
    for (const char* column : {"simlab id", "ID", "SIS User ID", "SIS Login ID", "Platform ID", "Email"}) {
        for (const auto& [id, value] : rosterColumn(rosterPath, column)) ids.add(value, id);
    }
    return ids;
}

HandIn handInOf(const std::string& time, const std::string& from, std::optional<bool> flaggedLate) {
    HandIn h;
    h.time = time;
    h.from = time.empty() ? "" : from;
    // A platform's record of the hand-in; a file's time (a download's, a commit's) is whatever the copy made it.
    h.vouched = !time.empty() && (from == "Gradescope's created_at" || from.compare(0, 11, "--submitted") == 0);
    h.flaggedLate = flaggedLate;
    return h;
}

HandIns rosterHandIns(const std::string& rosterPath) {
    HandIns handIns;
    if (!fs::is_regular_file(rosterPath)) return handIns;
    const std::string where = "roster " + printable(rosterPath);
    const std::vector<std::vector<std::string>> rows = csvRows(rosterPath, where);
    if (rows.empty()) return handIns;
    const std::size_t id = columnOf(rows[0], "simlab id"), at = columnOf(rows[0], "Submitted"),
                      from = columnOf(rows[0], "Submitted from"), late = columnOf(rows[0], "Late"),
                      canvasFile = columnOf(rows[0], "Canvas file");
    if (id == std::string::npos) return handIns;
    for (std::size_t r = 1; r < rows.size(); ++r) {
        auto cell = [&](std::size_t c) {
            return c < rows[r].size() ? csvCellValue(trimmed(rows[r][c])) : std::string();
        };
        const std::string who = cell(id), when = cell(at);
        if (who.empty()) continue;
        std::string time;
        if (!when.empty()) {
            const std::optional<std::time_t> t = parseTime(when);
            if (!t) {
                throw UsageError(where + ", row " + std::to_string(r + 1) + ": Submitted '" + printable(when) +
                                 "' is not a date-time such as 2026-10-02T23:59:00Z");
            }
            time = utcText(*t);
        }
        // Canvas's download names a late submission so, and roster.csv keeps its flag.
        const std::optional<bool> flag =
            cell(canvasFile).empty() ? std::nullopt : std::optional<bool>(!cell(late).empty());
        const HandIn h = handInOf(time, cell(from).empty() ? "roster.csv" : cell(from), flag);
        // Members of a group share a folder: the latest of their times (and late if any is).
        const auto [kept, first] = handIns.emplace(who, h);
        if (!first) {
            if (!h.time.empty() && (kept->second.time.empty() || *parseTime(h.time) > *parseTime(kept->second.time))) {
                kept->second.time = h.time;
                kept->second.from = h.from;
            }
            if (h.flaggedLate) kept->second.flaggedLate = *h.flaggedLate || kept->second.flaggedLate.value_or(false);
        }
    }
    return handIns;
}

HandIns readSubmittedTimes(const std::string& path, const StudentIds& ids) {
    const std::string where = "submission times " + printable(path);
    if (!fs::is_regular_file(path)) throw UsageError("no " + where);
    const std::string text = readFile(path);
    const std::string from = "--submitted " + fs::path(path).filename().string();
    HandIns times;
    std::map<std::string, std::size_t> seen;
    auto take = [&](const std::string& who, const std::string& when, std::size_t row, const std::string& line,
                    std::optional<bool> late) {
        const std::string id = studentOfRow(who, ids, line);
        onceEach(seen, id, row, line);
        std::string time;
        if (!when.empty()) {
            const std::optional<std::time_t> t = parseTime(when);
            if (!t)
                throw UsageError(line + ": '" + printable(when) + "' is not a date-time such as 2026-10-02T23:59:00Z");
            time = utcText(*t);
        }
        times[id] = handInOf(time, from, late);
    };
    const std::size_t first = text.find_first_not_of(" \t\r\n\xEF\xBB\xBF");
    if (first != std::string::npos && text[first] == '[') {
        // Canvas's API: GET .../assignments/:id/submissions, a list of submissions.
        const nlohmann::json list = nlohmann::json::parse(text, nullptr, false);
        if (list.is_discarded() || !list.is_array())
            throw UsageError(where + " is not a JSON list of Canvas's submissions");
        for (std::size_t i = 0; i < list.size(); ++i) {
            const nlohmann::json& s = list[i];
            const std::string line = where + ", submission " + std::to_string(i + 1);
            if (!s.is_object() || !s.contains("user_id") ||
                !(s["user_id"].is_number_integer() || s["user_id"].is_string())) {
                throw UsageError(line + " has no user_id");
            }
            const std::string user = s["user_id"].is_string() ? s["user_id"].get<std::string>() : s["user_id"].dump();
            const nlohmann::json at = s.value("submitted_at", nlohmann::json());
            if (!at.is_null() && !at.is_string()) throw UsageError(line + ": submitted_at is not a date-time");
            const nlohmann::json late = s.value("late", nlohmann::json());
            take(user, at.is_string() ? at.get<std::string>() : "", i + 1, line,
                 late.is_boolean() ? std::optional<bool>(late.get<bool>()) : std::nullopt);
        }
        return times;
    }
    const std::vector<std::vector<std::string>> rows = csvRows(path, where);
    if (rows.empty()) return times;
    const std::size_t student = columnOf(rows[0], "student"), submitted = columnOf(rows[0], "submitted");
    if (student == std::string::npos || submitted == std::string::npos) {
        throw UsageError(where + ": its first line must name the columns student and submitted");
    }
    for (std::size_t r = 1; r < rows.size(); ++r) {
        auto cell = [&](std::size_t c) { return c < rows[r].size() ? trimmed(rows[r][c]) : std::string(); };
        if (cell(student).empty()) continue;
        const std::string line = where + ", row " + std::to_string(r + 1);
        if (cell(submitted).empty()) throw UsageError(line + ": no time");
        take(cell(student), cell(submitted), r + 1, line, std::nullopt);
    }
    return times;
}

void applyLatePolicy(StudentRecord& r, const LatePolicy& p, const HandIn& handIn) {
    r.late = {};
    if (!p.active || r.status == "missing file") return;
    const auto own = p.dueFor.find(r.id);
    const std::time_t due = own != p.dueFor.end() ? own->second : p.due;
    const std::optional<std::time_t> handed = parseTime(r.submitted);
    const std::string extended = own != p.dueFor.end() ? " (extended to " + utcText(due) + ")" : "";
    // The platform's flag decides late or not; the time, how late.
    if (handIn.flaggedLate == false) {
        r.late.line = "handed in on time by Canvas's flag" + extended;
        if (handed && *handed > due) {
            r.late.line += " (" + printable(r.submittedFrom) + ", " + utcText(*handed) + ", is later: not used)";
        }
        return;
    }
    if (!handed) {
        r.late.line = handIn.flaggedLate ? "late by Canvas's flag, but no time known to say how late: no late penalty "
                                           "(give the time with --submitted)"
                                         : "no submission time known: no late penalty";
        return;
    }
    const double past = std::difftime(*handed, due) / 3600;
    if (p.cutoff && *handed > *p.cutoff && own == p.dueFor.end()) {
        r.late = {past, 100,
                  "handed in " + hoursText(past) + " late, after the cutoff " + utcText(*p.cutoff) + ": no credit"};
        return;
    }
    if (past <= 0) {
        r.late.line = "handed in on time" + extended;
        if (handIn.flaggedLate && own == p.dueFor.end()) {
            r.late.line = "late by Canvas's flag, but " + printable(r.submittedFrom) + " (" + utcText(*handed) +
                          ") is on time: no late penalty (give the time with --submitted)";
        }
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

namespace {

// "a, b and 3 more": at most `shown` names.
std::string named(const std::vector<std::string>& ids, std::size_t shown = 8) {
    std::string out;
    for (std::size_t i = 0; i < ids.size() && i < shown; ++i) out += (i ? ", " : "") + printable(ids[i]);
    if (ids.size() > shown) out += " and " + std::to_string(ids.size() - shown) + " more";
    return out;
}

std::string studentsText(std::size_t n) { return std::to_string(n) + (n == 1 ? " student" : " students"); }

}  // namespace

std::vector<std::string> checkHandIns(HandIns& handIns, const LatePolicy& p) {
    std::vector<std::string> lines;
    if (!p.active) return lines;
    std::vector<std::string> unvouched, flagged;
    std::set<std::string> times, sources;
    for (const auto& [id, h] : handIns) {
        if (h.time.empty() || h.vouched) continue;
        unvouched.push_back(id);
        times.insert(h.time);
        sources.insert(h.from);
        if (h.flaggedLate.value_or(false)) flagged.push_back(id);
    }
    // Every file of one time: the download's (Canvas's zip at times gives none) or a copy's. They say nothing of
    // anyone's hand-in, and are dropped.
    if (unvouched.size() >= 2 && times.size() == 1) {
        lines.push_back("every student's time is the same, " + *times.begin() +
                        ": they are a download's or a copy's, not when each student handed in, and are not used" +
                        (flagged.empty()
                             ? std::string()
                             : "; Canvas flags " + studentsText(flagged.size()) +
                                   " late, not charged until --submitted gives their times: " + named(flagged)));
        for (const std::string& id : unvouched) {
            handIns[id].time.clear();
            handIns[id].from.clear();
        }
        return lines;
    }
    std::vector<std::string> disagree;
    for (const auto& [id, h] : handIns) {
        if (!h.flaggedLate) continue;
        const std::optional<std::time_t> at = parseTime(h.time);
        const auto own = p.dueFor.find(id);
        const std::time_t due = own != p.dueFor.end() ? own->second : p.due;
        // Late by the flag, yet on time even by the course's due date; or on time by it, yet past the student's own.
        if (!at || (*h.flaggedLate ? *at <= p.due : *at > due)) disagree.push_back(id);
    }
    if (!disagree.empty()) {
        lines.push_back("Canvas's late flag and the time disagree for " + studentsText(disagree.size()) +
                        " (the flag decides late or not; none is charged on the time alone): " + named(disagree) +
                        "; --submitted FILE gives Canvas's times");
    }
    if (!unvouched.empty()) {
        std::string from;
        for (const std::string& s : sources) from += (from.empty() ? "" : ", ") + s;
        const bool files = from.find("file") != std::string::npos;
        lines.push_back(studentsText(unvouched.size()) + " timed by " + printable(from) +
                        ", which no platform vouches for" + (files ? " (a copied folder has the copy's)" : "") + ": " +
                        named(unvouched) + "; --submitted FILE gives the platform's times");
    }
    return lines;
}

}  // namespace simlab::engine
