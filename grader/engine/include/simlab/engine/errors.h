// Errors the engine reports to its user as one line.
#pragma once

#include <stdexcept>

namespace simlab::engine {

/// Bad input from the user: a missing file, an unknown assignment, a bad option. The CLI prints what() on one
/// line and exits with status 2.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Grading was interrupted (Ctrl-C, SIGTERM) before it finished; nothing of the unfinished submission is kept.
class Interrupted : public std::runtime_error {
public:
    Interrupted() : std::runtime_error("interrupted") {}
};

}  // namespace simlab::engine
