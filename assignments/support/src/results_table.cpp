#include "simlab/results_table.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <ostream>
#include <stdexcept>

namespace simlab {

namespace {
constexpr int kScreenWidth = 16;  // characters per column on the screen
}

ResultsTable::ResultsTable(std::vector<std::string> columns, const std::string& path, std::ostream* screen)
    : columns_(std::move(columns)), path_(path), screen_(screen) {
    file_ = std::fopen(path.c_str(), "w");
    if (!file_) throw std::runtime_error("cannot write results file '" + path + "': " + std::strerror(errno));
    for (std::size_t i = 0; i < columns_.size(); ++i) {
        std::fprintf(file_, "%s%s", i ? "\t" : "", columns_[i].c_str());
    }
    std::fputc('\n', file_);
}

ResultsTable::~ResultsTable() {
    if (file_) std::fclose(file_);
}

void ResultsTable::add(const std::vector<double>& values) {
    if (values.size() != columns_.size()) {
        throw std::logic_error("results row has " + std::to_string(values.size()) + " values for " +
                               std::to_string(columns_.size()) + " columns");
    }
    // The first column is the time.
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (std::isfinite(values[i])) continue;
        char what[200];
        std::snprintf(what, sizeof what, "the run broke at t = %g s: %s is %s", values[0], columns_[i].c_str(),
                      std::isnan(values[i]) ? "NaN" : values[i] > 0 ? "+infinity" : "-infinity");
        note(what);
        throw std::runtime_error(std::string(what) + " (the results file keeps the rows before it)");
    }
    if (watched_ >= 0) {
        const double v = values[static_cast<std::size_t>(watched_)];
        if (rows_ == 0) watchedFirst_ = v;
        // Against the scene's own size for the quantity, or its first value where that is larger: never a size
        // that can be zero while the scene has one.
        const double scale = std::max(std::abs(watchedFirst_), watchedScale_);
        if (scale > 0 && std::abs(v - watchedFirst_) > watchedFactor_ * scale) {
            char what[280];
            std::snprintf(what, sizeof what,
                          "the run broke at t = %g s: %s moved from %.6g to %.6g, more than %g times its scale in "
                          "this scene (%.3g)",
                          values[0], columns_[static_cast<std::size_t>(watched_)].c_str(), watchedFirst_, v,
                          watchedFactor_, scale);
            note(what);
            throw std::runtime_error(std::string(what) + " (the results file keeps the rows before it)");
        }
    }
    for (std::size_t i = 0; i < values.size(); ++i) std::fprintf(file_, "%s%.17g", i ? "\t" : "", values[i]);
    std::fputc('\n', file_);
    if (std::ferror(file_)) throw std::runtime_error("cannot write results file '" + path_ + "'");
    if (screen_ && rows_ == 0) {
        for (const std::string& c : columns_) {
            const long pad = kScreenWidth + 1 - static_cast<long>(c.size());
            *screen_ << std::string(static_cast<std::size_t>(std::max(1L, pad)), ' ') << c;
        }
        *screen_ << '\n';
    }
    if (screen_) {
        char cell[64];
        for (double v : values) {
            std::snprintf(cell, sizeof cell, " %*.*g", kScreenWidth, kScreenWidth - 7, v);
            *screen_ << cell;
        }
        *screen_ << '\n';
    }
    ++rows_;
}

void ResultsTable::watchGrowth(const std::string& column, double factor, double scale) {
    const auto found = std::find(columns_.begin(), columns_.end(), column);
    if (found == columns_.end()) throw std::logic_error("results table has no column '" + column + "'");
    watched_ = static_cast<int>(found - columns_.begin());
    watchedFactor_ = factor;
    watchedScale_ = std::isfinite(scale) ? std::abs(scale) : 0.0;
}

void ResultsTable::note(const std::string& text) {
    if (noted_ || !file_) return;
    noted_ = true;
    std::fprintf(file_, "# %s\n", text.c_str());
    std::fflush(file_);
}

std::vector<std::vector<double>> readResults(const std::string& path, const std::vector<std::string>& columns) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read results file '" + path + "': " + std::strerror(errno));
    std::string expected;
    for (std::size_t i = 0; i < columns.size(); ++i) expected += (i ? "\t" : "") + columns[i];
    std::string line;
    if (!std::getline(in, line) || line != expected) {
        std::string start;
        for (std::size_t i = 0; i < columns.size() && i < 3; ++i) start += (i ? ", " : "") + columns[i];
        throw std::runtime_error("'" + path + "' is not a results file of this program (its header starts " + start +
                                 ")");
    }
    std::vector<std::vector<double>> rows;
    for (int number = 2; std::getline(in, line); ++number) {
        if (line.empty() || line[0] == '#') continue;
        std::vector<double> row;
        const char* at = line.c_str();
        while (*at) {
            char* end = nullptr;
            const double value = std::strtod(at, &end);
            if (end == at || (*end && *end != '\t')) {
                throw std::runtime_error("'" + path + "', line " + std::to_string(number) + ": not a table of numbers");
            }
            row.push_back(value);
            at = *end ? end + 1 : end;
        }
        if (row.size() != columns.size()) {
            throw std::runtime_error("'" + path + "', line " + std::to_string(number) + ": " +
                                     std::to_string(row.size()) + " values for " + std::to_string(columns.size()) +
                                     " columns");
        }
        rows.push_back(std::move(row));
    }
    if (rows.empty()) throw std::runtime_error("'" + path + "' has no rows: the run it comes from recorded nothing");
    return rows;
}

}  // namespace simlab
