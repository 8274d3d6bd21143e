// Recorder: where a simulation puts its samples, one row per sampling time.
#pragma once

#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace simlab {

template <class Row>
class Recorder {
public:
    /// Called with each row as it is recorded (the lab programs print it); may be empty.
    using Listener = std::function<void(const Row&)>;

    /// A simulation that records more than `maxRows` rows is stopped: its stepping loop is not ending.
    explicit Recorder(Listener listener = {}, std::size_t maxRows = 10'000'000)
        : listener_(std::move(listener)), maxRows_(maxRows) {}

    /// Keep one row. Throws std::length_error past the row limit.
    void record(const Row& row) {
        if (rows_.size() >= maxRows_) {
            throw std::length_error("more than " + std::to_string(maxRows_) +
                                    " samples recorded: does the stepping loop stop at the final time?");
        }
        rows_.push_back(row);
        if (listener_) listener_(row);
    }

    const std::vector<Row>& rows() const { return rows_; }

private:
    Listener listener_;
    std::size_t maxRows_;
    std::vector<Row> rows_;
};

}  // namespace simlab
