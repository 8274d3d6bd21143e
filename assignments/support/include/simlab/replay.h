// A replay of a run that needs no display: one HTML page, opened from disk, that shows the bodies move in 3-D
// (three.js, inlined from Debian's libjs-three) beside the run's time series.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace SimTK {
class MultibodySystem;
}

namespace simlab {

/// Records the motion of every mobilized body of a MultibodySystem for a replay page.
class ReplayRecorder {
public:
    /// Adds a periodic event reporter to `system` (call before its topology is realized) that records each
    /// body's pose (X_GB: position + rotation) every `frameInterval` s of simulated time, and, at its first
    /// frame, what every body looks like: the decorations of its Body and its mobilizer, and those a
    /// DecorationSubsystem fixes to it. The system adopts the reporter; the recording is shared between the two,
    /// so either may go first. A frame earlier than the last one recorded starts the recording over (a new run
    /// of the same system). Throws std::invalid_argument unless `frameInterval` is positive and finite.
    ReplayRecorder(SimTK::MultibodySystem& system, double frameInterval);

    /// Writes the page: `title` on top, the 3-D replay, and the run's time series beside it (`columns` names,
    /// `rows` one vector per sample, the first column is time; more than 5000 rows are thinned to every k-th
    /// row for the chart). The page plays from the start; PAGE.html#t=1.5 opens it paused at t = 1.5 s.
    /// Throws std::runtime_error (one line) if the three.js file is missing, nothing was recorded, or the file
    /// cannot be written; std::invalid_argument if a row's length is not the number of columns.
    void write(const std::string& path, const std::string& title, const std::vector<std::string>& columns,
               const std::vector<std::vector<double>>& rows) const;

    /// Frames recorded so far.
    std::size_t frames() const;

private:
    struct Recording;
    class Reporter;
    std::shared_ptr<Recording> recording_;
};

}  // namespace simlab
