// The results of a lab run: a table printed as it grows and written to a tab-separated file.
#pragma once

#include <cstdio>
#include <iosfwd>
#include <string>
#include <vector>

namespace simlab {

class ResultsTable {
public:
    /// Opens `path` for writing (throws std::runtime_error with the reason if it cannot) and writes the header
    /// there. The table goes to `screen` too (nullptr: print nothing), its header with the first row.
    ResultsTable(std::vector<std::string> columns, const std::string& path, std::ostream* screen);
    ~ResultsTable();
    ResultsTable(const ResultsTable&) = delete;
    ResultsTable& operator=(const ResultsTable&) = delete;

    /// One row, one value per column: to the file at full double precision (17 significant digits), to the
    /// screen rounded to fit the column. A row with an infinite or NaN value, or in which the watched column (see
    /// watchGrowth) has moved past its bound, is not written: the file ends with a comment line ("# ...") saying
    /// where the run broke, and add throws std::runtime_error with the same one-line message.
    void add(const std::vector<double>& values);

    /// Treat `column` (a quantity the run should conserve, such as the energy) moving from its first row's value by
    /// more than `factor` times its scale as a failure of the run. The scale is the larger of that first value's
    /// magnitude and `scale`, the scene's own size for the quantity (for an energy, the size of the terms it sums:
    /// m g L for a pendulum), so that a quantity that starts at or near zero is judged against the scene, never
    /// against its own rounding. Where both are zero nothing in the scene has a size to judge by, and the column is
    /// not watched.
    void watchGrowth(const std::string& column, double factor, double scale = 0);

    /// Ends the file with the comment line "# `text`" (once; later notes are dropped).
    void note(const std::string& text);

    std::size_t rows() const { return rows_; }

    const std::string& path() const { return path_; }

private:
    std::vector<std::string> columns_;
    std::string path_;
    std::FILE* file_ = nullptr;
    std::ostream* screen_;
    std::size_t rows_ = 0;
    int watched_ = -1;         // the column watchGrowth watches, or -1
    double watchedFactor_ = 0;
    double watchedScale_ = 0;  // the scene's size for it
    double watchedFirst_ = 0;  // its value in the first row
    bool noted_ = false;
};

/// The rows of a results file a lab program wrote with `columns` (its header must be exactly those), comment lines
/// ("# ...") skipped. Throws std::runtime_error, in one line naming the file (and the line), if it cannot be read,
/// is another program's, has a row that is not `columns.size()` numbers, or has no rows.
std::vector<std::vector<double>> readResults(const std::string& path, const std::vector<std::string>& columns);

}  // namespace simlab
