// What a person grades: OUT/manual.csv, one row per student and manual item of the rubric ("the schematic is
// clear"), written by simlab grade with the points empty, filled in by the instructor, and kept by every regrade.
//
//     student,item,points,comment,file
//     ada,the schematic shows the points and bodies clearly,8,the knee's axis is missing,3f9a0c21b7d4
//     bob,the schematic shows the points and bodies clearly,,,
//
// An empty points cell is pending. Rows of students or items that are no longer there are kept as they are (a
// person typed them), and count for nothing.
//
// The file cell says which of the student's files the points were given to: a short hash of what was graded (the
// record's `content`). simlab fills it in the first time it reads a row with points and no file: the file of the
// grade the instructor saw, the one graded before this run. When the student's file changes, the points are kept
// and still count, but are flagged as given to an earlier file (report.html, the run's summary, the feedback) until
// the instructor confirms them by clearing the file cell (simlab then fills in the file graded now). A sheet of an
// older simlab, without the file column, reads as one with every file cell empty.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "simlab/grading/record.h"
#include "simlab/rubric/rubric.h"

namespace simlab::engine {

struct ManualEntry {
    std::optional<double> points;  ///< empty: pending
    std::string comment;
    std::string file;  ///< the hash of the file the points were given to; empty: not known yet
};

/// The sheet, by student id and item name, in the order of its rows.
struct ManualSheet {
    std::vector<std::pair<std::string, std::string>> order;  ///< (student, item), each row once
    std::map<std::pair<std::string, std::string>, ManualEntry> entries;
};

/// A student id or item name as the sheet keys it: printable, without spaces at its ends or the apostrophe that
/// neutralizes a formula (so that what simlab writes reads back the same).
std::string manualKey(const std::string& cell);

/// The rows of `sheet` that count for nothing: their student is not in `students`, or their item is not the
/// rubric's ("ada / writeup"), to warn of a typo.
std::vector<std::string> strayManualRows(const ManualSheet& sheet, const std::vector<std::string>& students,
                                         const Rubric& rubric);

/// Reads manual.csv. Throws UsageError, in one line naming `name` and the row, for a header other than
/// student,item,points[,comment[,file]], a row twice, text that is not UTF-8, points that are not a decimal number
/// from 0 to the item's points, or a file cell that is not a hash simlab wrote.
ManualSheet readManualCsv(const std::string& text, const std::string& name, const Rubric& rubric);

/// OUT/manual.csv of the grades in `outDir`, read and checked by readManualCsv; an empty sheet where there is none.
ManualSheet readManualSheet(const std::string& outDir, const Rubric& rubric);

/// The sheet with a row for each of `students` and each manual item of `rubric` (new rows pending), the rows
/// already there kept with their points and comments; as CSV (cells neutralized against formulas).
std::string manualCsv(ManualSheet sheet, const std::vector<std::string>& students, const Rubric& rubric);

/// Fills in the file cell of each row with points and none: the hash `graded` holds for its student, if any.
void stampManual(ManualSheet& sheet, const std::map<std::string, std::string>& graded);

/// Gives `r` the rubric's manual items with the points and comments the sheet holds for it (pending where none),
/// each flagged earlierFile when the sheet's file is not `r.content`.
void applyManual(StudentRecord& r, const ManualSheet& sheet, const Rubric& rubric);

}  // namespace simlab::engine
