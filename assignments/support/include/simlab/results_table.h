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
    /// screen rounded to fit the column.
    void add(const std::vector<double>& values);

    const std::string& path() const { return path_; }

private:
    std::vector<std::string> columns_;
    std::string path_;
    std::FILE* file_ = nullptr;
    std::ostream* screen_;
    std::size_t rows_ = 0;
};

}  // namespace simlab
