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

/// simlab's build cannot grade on this machine as it is (a precompiled header older than a system header it was
/// made from, say): no submission's fault, so nothing is recorded for it; the CLI prints what() on one line and
/// exits with status 2, and a class stops where it is, keeping what was graded.
class SetupError : public UsageError {
public:
    using UsageError::UsageError;
};

/// Grading was interrupted (Ctrl-C, SIGTERM) before it finished; nothing of the unfinished submission is kept.
class Interrupted : public std::runtime_error {
public:
    Interrupted() : std::runtime_error("interrupted") {}
};

}  // namespace simlab::engine
