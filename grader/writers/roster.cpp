#include "simlab/writers/roster.h"

#include <algorithm>
#include <map>

#include "simlab/common/errors.h"
#include "simlab/common/text.h"

namespace simlab::engine {

std::vector<std::vector<std::string>> readCsv(const std::string& text) {
    std::vector<std::vector<std::string>> rows;
    std::vector<std::string> row;
    std::string cell;
    bool quoted = false, any = false, cellStart = true;
    std::size_t i = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
    int line = 1, quoteLine = 0;
    auto endRow = [&] {
        row.push_back(cell);
        rows.push_back(row);
        row.clear();
        cell.clear();
        any = false;
    };
    for (; i < text.size(); ++i) {
        const char c = text[i];
        if (quoted) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
                cell += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                line += c == '\n';
                cell += c;
            }
            continue;
        }
        if (c == '"' && cellStart) {  // a quote elsewhere in a cell is just a character, as spreadsheets read it
            quoted = true;
            quoteLine = line;
            any = true;
            cellStart = false;
        } else if (c == ',') {
            row.push_back(cell);
            cell.clear();
            any = true;
            cellStart = true;
        } else if (c == '\n' || c == '\r') {
            if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
            ++line;
            endRow();
            cellStart = true;
        } else {
            cell += c;
            any = true;
            cellStart = false;
        }
    }
    if (quoted) throw UsageError("the quote opened on line " + std::to_string(quoteLine) + " is never closed");
    if (any || !cell.empty() || !row.empty()) endRow();
    return rows;
}

std::vector<RosterEntry> readRoster(const std::string& text, const std::string& name) {
    const std::string where = "roster " + printable(name);
    std::vector<std::vector<std::string>> rows;
    try {
        rows = readCsv(text);
    } catch (const UsageError& e) {
        throw UsageError(where + ": " + e.what());
    }
    // Blank lines are no one.
    rows.erase(std::remove_if(rows.begin(), rows.end(),
                              [](const std::vector<std::string>& r) {
                                  return std::all_of(r.begin(), r.end(),
                                                     [](const std::string& c) { return trimmed(c).empty(); });
                              }),
               rows.end());
    if (rows.empty()) throw UsageError(where + " is empty; its first line names the columns (Student, ID, ...)");
    std::map<std::string, std::size_t> column;
    for (std::size_t i = 0; i < rows[0].size(); ++i) column.emplace(trimmed(rows[0][i]), i);
    const bool ownIds = column.count("simlab id") > 0;
    if (!column.count("Student")) throw UsageError(where + " has no Student column (its first line names the columns)");
    if (!column.count("ID") && !column.count("SIS User ID") && !column.count("SIS Login ID")) {
        throw UsageError(where + " has none of the columns ID, SIS User ID and SIS Login ID: Canvas needs one to "
                                 "know the student");
    }
    if (!ownIds && !column.count("SIS Login ID")) {
        throw UsageError(where + " has no 'simlab id' column (the students' folder names), nor an SIS Login ID to "
                                 "use instead");
    }
    auto cellOf = [&](const std::vector<std::string>& row, const std::string& key) {
        const auto found = column.find(key);
        return found == column.end() || found->second >= row.size() ? std::string()
                                                                     : csvCellValue(trimmed(row[found->second]));
    };
    std::vector<RosterEntry> entries;
    // An id of Canvas's names one student: on two rows it is a mistake, and either could get the other's grade.
    std::map<std::pair<std::string, std::string>, std::size_t> seen;
    for (std::size_t r = 1; r < rows.size(); ++r) {
        const std::string line = where + ", row " + std::to_string(r + 1);
        if (rows[r].size() > rows[0].size()) {
            throw UsageError(line + " has " + std::to_string(rows[r].size()) + " cells, the header " +
                             std::to_string(rows[0].size()));
        }
        RosterEntry e;
        e.student = cellOf(rows[r], "Student");
        if (e.student == "Points Possible") continue;
        e.canvasId = cellOf(rows[r], "ID");
        e.sisUserId = cellOf(rows[r], "SIS User ID");
        e.sisLoginId = cellOf(rows[r], "SIS Login ID");
        e.section = cellOf(rows[r], "Section");
        // An empty simlab id is a student simlab has no grade for (a blank cell); the same id on several rows is
        // a group's folder, whose grade each member gets.
        e.folder = cellOf(rows[r], ownIds ? "simlab id" : "SIS Login ID");
        if (e.student.empty() && e.canvasId.empty() && e.sisUserId.empty() && e.sisLoginId.empty()) {
            throw UsageError(line + " names no student (Student, ID, SIS User ID and SIS Login ID are all empty)");
        }
        for (const auto& [key, value] : {std::pair<const char*, const std::string&>{"ID", e.canvasId},
                                         {"SIS User ID", e.sisUserId},
                                         {"SIS Login ID", e.sisLoginId}}) {
            if (value.empty()) continue;
            const auto [at, first] = seen.emplace(std::make_pair(std::string(key), value), r + 1);
            if (!first) {
                throw UsageError(line + ": " + key + " " + printable(value) + " is row " + std::to_string(at->second) +
                                 "'s too: one student per id");
            }
        }
        entries.push_back(e);
    }
    return entries;
}

}  // namespace simlab::engine
