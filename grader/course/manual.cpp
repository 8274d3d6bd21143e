#include "simlab/course/manual.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/grading/report.h"
#include "simlab/writers/roster.h"
#include "simlab/common/text.h"

namespace simlab::engine {

namespace {

// A decimal number as a person types it: digits, a point and digits (no sign, exponent, hex, inf or nan).
bool isDecimal(const std::string& text) {
    std::size_t digits = 0, points = 0;
    for (char c : text) {
        if (c >= '0' && c <= '9') ++digits;
        else if (c == '.') ++points;
        else return false;
    }
    return digits > 0 && points <= 1 && text.front() != '.' && text.back() != '.';
}

// A file cell as simlab writes it: hexadecimal digits (a prefix of a SHA-256).
bool isFileHash(const std::string& text) {
    return !text.empty() && text.size() <= 64 && std::all_of(text.begin(), text.end(), [](char c) {
        return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
    });
}

const std::vector<std::string> kColumns = {"student", "item", "points", "comment", "file"};

// Points as the sheet keeps them: the shortest decimal that reads back as the same number (7.5, 0.125), so that
// nobody's points change by being kept.
std::string sheetPoints(double value) {
    char text[400];  // the largest double written out in full
    const std::to_chars_result written = std::to_chars(text, text + sizeof text, value, std::chars_format::fixed);
    return written.ec == std::errc() ? std::string(text, written.ptr) : points(value);
}

}  // namespace

std::string manualKey(const std::string& cell) { return csvCellValue(trimmed(printable(cell))); }

ManualSheet readManualCsv(const std::string& text, const std::string& name, const Rubric& rubric) {
    const std::string where = printable(name);
    std::vector<std::vector<std::string>> rows;
    try {
        rows = readCsv(text);
    } catch (const UsageError& e) {
        throw UsageError(where + ": " + e.what());
    }
    ManualSheet sheet;
    if (rows.empty()) return sheet;
    std::vector<std::string> header;
    for (const std::string& cell : rows[0]) header.push_back(trimmed(cell));
    // An older sheet has no file column, or no comment either.
    if (header.size() < 3 || header.size() > kColumns.size() ||
        !std::equal(header.begin(), header.end(), kColumns.begin())) {
        throw UsageError(where + ": the first line must be student,item,points,comment,file");
    }
    for (std::size_t r = 1; r < rows.size(); ++r) {
        const std::vector<std::string>& row = rows[r];
        const std::string line = where + ", row " + std::to_string(r + 1);
        bool blank = true;
        for (const std::string& cell : row) blank = blank && trimmed(cell).empty();
        if (blank) continue;
        if (row.size() < 3 || row.size() > header.size()) {
            throw UsageError(line + " has " + std::to_string(row.size()) + " cells: student,item,points,comment,file");
        }
        for (const std::string& cell : row) {
            if (!isValidUtf8(cell)) throw UsageError(line + " is not UTF-8 text (save the sheet as CSV UTF-8)");
        }
        const std::string student = manualKey(row[0]), item = manualKey(row[1]);
        if (student.empty() || item.empty()) throw UsageError(line + " has no student or no item");
        ManualEntry entry;
        const std::string points = trimmed(row[2]);
        if (!points.empty()) {
            const double value = isDecimal(points) ? std::strtod(points.c_str(), nullptr) : NAN;
            if (!std::isfinite(value)) {
                throw UsageError(line + ": the points '" + printable(points) + "' are not a decimal number (such as 7 or 7.5)");
            }
            for (const ManualItem& m : rubric.manual) {
                if (manualKey(m.name) == item && (value < 0 || value > m.points + 1e-9)) {
                    throw UsageError(line + ": " + points + " points for '" + printable(item) + "', which is worth 0 to " +
                                     simlab::engine::points(m.points));
                }
            }
            entry.points = value;
        }
        if (row.size() > 3) entry.comment = csvCellValue(row[3]);
        if (row.size() > 4) entry.file = trimmed(row[4]);
        if (!entry.file.empty() && !isFileHash(entry.file)) {
            throw UsageError(line + ": the file '" + printable(entry.file) +
                             "' is not one simlab wrote (clear the cell: simlab fills it in)");
        }
        const auto key = std::make_pair(student, item);
        if (sheet.entries.count(key)) {
            throw UsageError(line + ": " + printable(student) + " and '" + printable(item) + "' are there twice");
        }
        sheet.order.push_back(key);
        sheet.entries[key] = entry;
    }
    return sheet;
}

ManualSheet readManualSheet(const std::string& outDir, const Rubric& rubric) {
    const std::string path = outDir + "/manual.csv";
    if (!std::filesystem::exists(path)) return {};
    return readManualCsv(readFile(path), path, rubric);
}

std::string manualCsv(ManualSheet sheet, const std::vector<std::string>& students, const Rubric& rubric) {
    for (const std::string& student : students) {
        for (const ManualItem& m : rubric.manual) {
            const auto key = std::make_pair(manualKey(student), manualKey(m.name));
            if (sheet.entries.emplace(key, ManualEntry{}).second) sheet.order.push_back(key);
        }
    }
    std::string out = "student,item,points,comment,file\n";
    for (const auto& key : sheet.order) {
        const ManualEntry& e = sheet.entries.at(key);
        out += csvCell(key.first) + "," + csvCell(key.second) + "," + (e.points ? sheetPoints(*e.points) : "") + "," +
               csvCell(e.comment) + "," + e.file + "\n";
    }
    return out;
}

std::vector<std::string> strayManualRows(const ManualSheet& sheet, const std::vector<std::string>& students,
                                         const Rubric& rubric) {
    std::set<std::string> ids, items;
    for (const std::string& s : students) ids.insert(manualKey(s));
    for (const ManualItem& m : rubric.manual) items.insert(manualKey(m.name));
    std::vector<std::string> stray;
    for (const auto& [student, item] : sheet.order) {
        if (!ids.count(student) || !items.count(item)) stray.push_back(student + " / " + item);
    }
    return stray;
}

void stampManual(ManualSheet& sheet, const std::map<std::string, std::string>& graded) {
    std::map<std::string, std::string> byKey;
    for (const auto& [id, file] : graded) {
        if (!file.empty()) byKey[manualKey(id)] = file;
    }
    for (auto& [key, entry] : sheet.entries) {
        const auto file = byKey.find(key.first);
        if (entry.points && entry.file.empty() && file != byKey.end()) entry.file = file->second;
    }
}

// The rubric's manual items with the points the sheet gives this student.
void applyManual(StudentRecord& r, const ManualSheet& sheet, const Rubric& rubric) {
    r.manual.clear();
    for (const ManualItem& m : rubric.manual) {
        ManualGrade g{m.name, m.points, std::nullopt, "", false};
        const auto found = sheet.entries.find({manualKey(r.id), manualKey(m.name)});
        if (found != sheet.entries.end()) {
            const ManualEntry& e = found->second;
            g.points = e.points;
            g.comment = e.comment;
            // A record of an older simlab does not say what it graded: nothing to compare.
            g.earlierFile = e.points && !e.file.empty() && !r.content.empty() && e.file != r.content;
        }
        r.manual.push_back(g);
    }
}

}  // namespace simlab::engine
