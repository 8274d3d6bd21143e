#include "simlab/course/policy.h"

#include <cstdio>
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
#include "simlab/writers/writers.h"

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

// A whole number `key` of `table` from `low` to `high`; `fallback` when it is not there.
int wholeNumber(const toml::table& table, const std::string& key, int fallback, int low, int high,
                const std::string& where, const std::string& hint) {
    const toml::node* node = table.get(key);
    if (!node) return fallback;
    const std::optional<std::int64_t> value = node->is_integer() ? node->value<std::int64_t>() : std::nullopt;
    if (!value || *value < low || *value > high) {
        throw UsageError(where + ": " + key + " must be a whole number from " + std::to_string(low) + " to " +
                         std::to_string(high) + hint);
    }
    return static_cast<int>(*value);
}

// The course's bank of slip days ([late] slip_days), kept against due dates: a course whose labs have none has
// nothing to spend it on. A key of the course's in an assignment's table, or of an assignment's in [late], is
// refused rather than left unread.
void readCourseRules(const toml::table& file, LatePolicy& p, const std::string& path) {
    const toml::table* late = file["late"].as_table();
    const std::string where = printable(path) + " [late]";
    if (late) {
        p.slipDays = wholeNumber(*late, "slip_days", 0, 0, 365, where, "");
        for (const char* own : {"max_submissions", "submission_window_hours", "due", "cutoff", "extensions"}) {
            if (late->get(own)) throw UsageError(where + ": " + own + " is an assignment's: set it in its [id]");
        }
    }
    bool dated = false;
    for (const auto& [key, value] : file) {
        if (key.str() == "late" || !value.is_table()) continue;
        const toml::table& lab = *value.as_table();
        dated = dated || lab.get("due");
        if (lab.get("slip_days")) {
            throw UsageError(printable(path) + " [" + printable(std::string(key.str())) +
                             "]: slip_days is the course's bank, for every lab: set it in [late]");
        }
    }
    if (p.slipDays > 0 && !dated) {
        throw UsageError(where + ": slip_days = " + std::to_string(p.slipDays) +
                         ", but no assignment has a due date: the days are spent past each lab's due (give each lab "
                         "its due = 2026-10-02T23:59:00-07:00)");
    }
}

// An assignment's cap on graded submissions (max_submissions, submission_window_hours).
SubmissionCap readCap(const toml::table& own, const std::string& where) {
    SubmissionCap cap;
    cap.max = wholeNumber(own, "max_submissions", 0, 1, 1000, where,
                          " (graded submissions that count; leave it out for no cap)");
    cap.windowHours = number(own, "submission_window_hours", 0, 1, 24 * 366, where);
    if (cap.windowHours > 0 && cap.max == 0) {
        throw UsageError(where + ": submission_window_hours needs max_submissions, the submissions each window counts");
    }
    return cap;
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
    // The year in four digits, as parseTime reads it back (strftime's %Y writes the year 226 as "226").
    char text[48];
    std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02dZ", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday,
                  tm.tm_hour, tm.tm_min, tm.tm_sec);
    return text;
}

LatePolicy loadLatePolicy(const std::string& path, const std::string& assignment, const StudentIds& ids) {
    LatePolicy p;
    p.source = path;
    p.assignment = assignment;
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
    readCourseRules(file, p, path);
    const toml::table* own = file[assignment].as_table();
    if (!own) return p;
    const std::string where = printable(path) + " [" + assignment + "]";
    readRules(*own, p, where);
    p.cap = readCap(*own, where);
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

namespace {

std::string daysText(int days) { return std::to_string(days) + (days == 1 ? " slip day" : " slip days"); }

// The ledger of the bank after this lab: what each lab spent, this one included, and what is left.
std::string ledgerLine(const LatePolicy& p, const SlipAccount& account, int used) {
    std::string spent;
    for (const auto& [lab, days] : account.spent)
        spent += (spent.empty() ? "" : ", ") + std::to_string(days) + " on " + lab;
    if (used > 0) spent += (spent.empty() ? "" : ", ") + std::to_string(used) + " on " + p.assignment + " (this lab)";
    return (spent.empty() ? std::string("none spent") : spent) + "; " + std::to_string(account.had - used) + " of " +
           std::to_string(p.slipDays) + " left";
}

// The lateness of `r` under `p`, the bank of slip days spent first where the course keeps one (r.late.slip.needed
// and .used say how many days).
void chargeLateness(StudentRecord& r, const LatePolicy& p, const HandIn& handIn, const SlipAccount& account) {
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
    // A cutoff is the course's last word: no slip day reaches past it.
    if (p.cutoff && *handed > *p.cutoff && own == p.dueFor.end()) {
        const std::string line = "handed in " + hoursText(past) + " late, after the cutoff " + utcText(*p.cutoff);
        r.late = {past, 100, line + ": no credit", {}};
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
    double charged = past - p.graceHours;
    const std::string days = points(p.graceHours / 24) + " grace day" + (p.graceHours == 24 ? "" : "s");
    std::string grace = p.graceHours > 0 ? ", " + days : "";
    if (charged <= 0) {
        const std::string line = "handed in " + hoursText(past) + " late" + extended + ", within the " + days;
        r.late = {past, 0, line + ": no penalty", {}};
        return;
    }
    if (p.slipDays > 0) {
        // Whole days, rounded up, from the bank before any penalty.
        r.late.slip.needed = static_cast<int>(std::ceil(charged / 24 - 1e-9));
        if (!p.slipKnown) {
            r.late = {past, 0,
                      "handed in " + hoursText(past) + " late" + extended + grace +
                          ": the course's slip days decide it where its labs are graded together (simlab grade), so "
                          "no penalty is taken here",
                      r.late.slip};
            return;
        }
        r.late.slip.used = std::min(r.late.slip.needed, account.had);
        charged -= r.late.slip.used * 24.0;
        if (r.late.slip.used > 0) grace += ", " + daysText(r.late.slip.used) + " spent";
        if (charged <= 0) {
            r.late = {past, 0, "handed in " + hoursText(past) + " late" + extended + grace + ": no penalty",
                      r.late.slip};
            return;
        }
        grace += r.late.slip.used < account.had ? "" : account.had == 0 ? " (no slip day left)" : " (none left)";
    }
    const double periods = std::ceil(charged / p.periodHours - 1e-9);
    const double percent = std::min(p.maxPercent, periods * p.penaltyPercent);
    r.late = {past, percent,
              "handed in " + hoursText(past) + " late" + extended + grace + ": " + points(percent) +
                  " % of the score taken (" + points(p.penaltyPercent) + " % per " +
                  (p.periodHours == 24 ? "day" : "hour") + ")",
              r.late.slip};
}

}  // namespace

void applyLatePolicy(StudentRecord& r, const LatePolicy& p, const HandIn& handIn) {
    r.late = {};
    if (!p.active || r.status == SubmissionStatus::MissingFile) return;
    SlipAccount account;
    account.had = p.slipDays;
    if (const auto found = p.slip.find(r.id); found != p.slip.end()) account = found->second;
    chargeLateness(r, p, handIn, account);
    if (p.slipDays == 0) return;
    // What the record keeps of the bank: enough for the labs due after this one to know what it left them.
    StudentRecord::Lateness::Slip& slip = r.late.slip;
    slip.bank = p.slipDays;
    slip.due = utcText(p.due);
    if (!p.slipKnown) return;
    slip.had = account.had;
    slip.ledger = ledgerLine(p, account, slip.used);
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

// --- The bank of slip days across the labs graded side by side ---------------------------------------------------

SlipLedger readSlipLedger(const std::string& gradesRoot) {
    SlipLedger ledger;
    if (!fs::is_directory(gradesRoot)) return ledger;
    for (const FolderEntry& folder : listFolder(gradesRoot, /*followFolder=*/true)) {
        if (folder.type != EntryType::Directory || folder.name[0] == '.') continue;
        const std::string students = gradesRoot + "/" + folder.name + "/students";
        if (!fs::is_directory(students)) continue;
        SlipLedger::Lab lab;
        lab.id = folder.name;
        bool dated = false;
        std::map<std::string, int> dues;  // the due date each record gives: the most given is the lab's
        for (const FolderEntry& e : listFolder(students, /*followFolder=*/true)) {
            if (e.type != EntryType::Directory) continue;
            const std::string path = students + "/" + e.name + "/record.json";
            if (!fs::is_regular_file(path)) continue;
            std::optional<StudentRecord> r;
            try {
                r = readRecordJson(readFile(path));
            } catch (const std::exception&) {
                continue;  // unreadable: graded again by its lab's next run, said there
            }
            // A folder of another lab's grades, or of a record that is none of a lab's: not this lab's days.
            if (!r || r->assignment != folder.name) continue;
            dated = dated || !r->late.line.empty();
            if (r->late.slip.bank == 0) continue;
            if (const std::optional<std::time_t> due = parseTime(r->late.slip.due)) ++dues[utcText(*due)];
            lab.students[e.name] = r->late.slip;
        }
        if (lab.students.empty()) {
            if (dated) ledger.withoutBank.push_back(lab.id);
            continue;
        }
        const auto most = std::max_element(dues.begin(), dues.end(),
                                           [](const auto& a, const auto& b) { return a.second < b.second; });
        lab.due = most == dues.end() ? 0 : *parseTime(most->first);
        ledger.labs.push_back(std::move(lab));
    }
    std::sort(ledger.labs.begin(), ledger.labs.end(), [](const SlipLedger::Lab& a, const SlipLedger::Lab& b) {
        return std::tie(a.due, a.id) < std::tie(b.due, b.id);
    });
    return ledger;
}

SlipAccount slipAccount(const SlipLedger& ledger, int bank, const std::string& lab, std::time_t due,
                        const std::string& student) {
    SlipAccount account;
    account.had = bank;
    for (const SlipLedger::Lab& before : ledger.labs) {
        if (std::tie(before.due, before.id) >= std::tie(due, lab)) break;
        const auto found = before.students.find(student);
        if (found == before.students.end()) continue;
        const int used = std::min(found->second.needed, account.had);
        if (used > 0) account.spent.emplace_back(before.id, used);
        account.had -= used;
    }
    return account;
}

std::vector<std::pair<std::string, std::vector<std::string>>> staleSlipLabs(const SlipLedger& ledger, int bank) {
    std::vector<std::pair<std::string, std::vector<std::string>>> stale;
    for (const SlipLedger::Lab& lab : ledger.labs) {
        std::vector<std::string> differ;
        for (const auto& [id, slip] : lab.students) {
            const SlipAccount account = slipAccount(ledger, bank, lab.id, lab.due, id);
            const int used = std::min(slip.needed, account.had);
            if (slip.bank != bank || slip.had != account.had || slip.used != used) differ.push_back(id);
        }
        if (!differ.empty()) stale.emplace_back(lab.id, differ);
    }
    for (const std::string& lab : ledger.withoutBank) stale.emplace_back(lab, std::vector<std::string>{});
    return stale;
}

std::string staleSlipLine(const std::vector<std::pair<std::string, std::vector<std::string>>>& stale,
                          const std::string& gradesRoot) {
    if (stale.empty()) return "";
    std::string labs, commands;
    for (std::size_t i = 0; i < stale.size(); ++i) {
        const auto& [lab, students] = stale[i];
        const char* separator = i == 0 ? "" : i + 1 == stale.size() ? " and " : ", ";
        labs += separator + printable(lab) + " (" +
                (students.empty() ? std::string("graded before the course kept the bank")
                                  : studentsText(students.size()) + ": " + named(students, 4)) +
                ")";
        commands += (i == 0 ? "" : "; ") + std::string("simlab grade ") + printable(lab) + " ... -o " +
                    printable((fs::path(gradesRoot) / lab).string());
    }
    return "the slip days spent on " + labs + " are not what the bank now gives them (a lab due before was graded " +
           "again, or the bank changed): grade " + (stale.size() == 1 ? "it" : "each") +
           " again, which runs no code (" + commands + "), then export " + (stale.size() == 1 ? "it" : "each") +
           " again";
}

// --- A cap on graded submissions ------------------------------------------------------------------------------------

CapStanding capStanding(const SubmissionCap& cap, std::time_t at, const std::vector<PriorSubmission>& prior) {
    CapStanding s;
    if (cap.max <= 0) return s;
    // The earlier submissions in the order they were made; each counted when the window (or the assignment) held
    // fewer counted ones than the cap, as this one is.
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < prior.size(); ++i) {
        if (prior[i].at < at) order.push_back(i);  // a regrade's metadata may list later ones: not before this one
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return prior[a].at < prior[b].at; });
    const double window = cap.windowHours * 3600;
    std::vector<std::pair<std::time_t, std::size_t>> counted;  // (time, index) of the counted ones
    auto within = [&](std::time_t t) {
        std::vector<std::pair<std::time_t, std::size_t>> in;
        for (const auto& c : counted) {
            if (window <= 0 || std::difftime(t, c.first) < window) in.push_back(c);
        }
        return in;
    };
    for (const std::size_t i : order) {
        if (prior[i].graded && static_cast<int>(within(prior[i].at).size()) < cap.max)
            counted.emplace_back(prior[i].at, i);
    }
    const std::vector<std::pair<std::time_t, std::size_t>> in = within(at);
    const std::string each = window > 0 ? " each " + points(cap.windowHours) + " h" : "";
    const std::string counts =
        std::to_string(cap.max) + " graded submission" + (cap.max == 1 ? "" : "s") + " the course counts" + each;
    // With a window, the next counts once the oldest counted one in it leaves it.
    auto nextText = [&](const std::vector<std::pair<std::time_t, std::size_t>>& held) {
        if (window <= 0 || held.empty()) return std::string();
        s.next = held.front().first + static_cast<std::time_t>(window);
        return "; the next counts from " + utcText(*s.next);
    };
    if (static_cast<int>(in.size()) < cap.max) {
        s.number = static_cast<int>(in.size()) + 1;
        s.left = cap.max - s.number;
        std::vector<std::pair<std::time_t, std::size_t>> held = in;
        held.emplace_back(at, prior.size());
        s.line = "graded submission " + std::to_string(s.number) + " of the " + counts + ": " +
                 (s.left == 0 ? "none" : std::to_string(s.left)) + " left" + (s.left == 0 ? nextText(held) : "");
        return s;
    }
    s.counted = false;
    s.number = static_cast<int>(in.size());
    s.kept = counted.back().second;
    const PriorSubmission& kept = prior[*s.kept];
    s.line = "not graded: past the " + counts + "; your score stays " +
             (kept.score ? points(*kept.score) : std::string("that")) + ", from your submission of " +
             utcText(kept.at) + nextText(in);
    return s;
}

std::optional<int> gradeRateMinutes(const SubmissionCap& cap) {
    if (cap.max <= 0 || cap.windowHours <= 0) return std::nullopt;
    // Spaced R minutes apart, a window of W minutes holds at most ceil(W / R) of them: no more than the cap when
    // R >= W / max.
    return static_cast<int>(std::ceil(cap.windowHours * 60 / cap.max - 1e-9));
}

}  // namespace simlab::engine
