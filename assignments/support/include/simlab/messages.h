// One line from a message that runs over several: what a one-line error, a study's row or a grader's reason shows.
#pragma once

#include <cstddef>
#include <string>

namespace simlab {

/// The part of an exception's message that says what went wrong, on one line of at most `maxLength` characters:
/// without Simbody's "SimTK Exception thrown at file:line" preamble and "Error detected by Simbody method", and
/// without the lines a solver adds after the reason (a line that only names the method keeps the next one).
std::string oneLineMessage(const std::string& message, std::size_t maxLength = 240);

}  // namespace simlab
