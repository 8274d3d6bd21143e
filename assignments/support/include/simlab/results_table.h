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
    /// watchGrowth) has grown past its bound, is not written: the file ends with a comment line ("# ...") saying
    /// where the run broke, and add throws std::runtime_error with the same one-line message.
    /// `scale` is the size of the terms the watched column sums in this row (0: none given): growth is then judged
    /// against the larger of the first value and the terms' rounding (1e-12 of them), so that a quantity that
    /// starts tiny and sums terms that cancel is not taken for one that blew up.
    void add(const std::vector<double>& values, double scale = 0);

    /// Treat `column` (a quantity the run should conserve, such as the energy) growing to more than `factor`
    /// times its first row's magnitude (or its terms' rounding, see add) as a failure of the run.
    void watchGrowth(const std::string& column, double factor);

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
    double watchedFirst_ = 0;  // its value in the first row
    bool noted_ = false;
};

/// The rows of a results file a lab program wrote with `columns` (its header must be exactly those), comment lines
/// ("# ...") skipped. Throws std::runtime_error, in one line naming the file (and the line), if it cannot be read,
/// is another program's, has a row that is not `columns.size()` numbers, or has no rows.
std::vector<std::vector<double>> readResults(const std::string& path, const std::vector<std::string>& columns);

}  // namespace simlab
