// Text as people read it: one line from a message that runs over several (what a one-line error, a study's row or
// a grader's reason shows), and text made safe to put in a page.
#pragma once

#include <cstddef>
#include <string>

namespace simlab {

/// The part of an exception's message that says what went wrong, on one line of at most `maxLength` characters:
/// without Simbody's "SimTK Exception thrown at file:line" preamble and "Error detected by Simbody method", and
/// without the lines a solver adds after the reason (a line that only names the method keeps the next one). An
/// integrator's failed step is said with its cause ("the integrator could not advance past t = 0.744 s: ...").
std::string oneLineMessage(const std::string& message, std::size_t maxLength = 240);

/// `value` in at most 6 significant digits ("%g"), for a message.
std::string shortNumber(double value);

/// A span of wall time for a progress line: "8.2 s", "41 s", "12 min", "3.4 h".
std::string durationText(double seconds);

/// `text` as HTML or XML character data or an attribute's value: &, <, >, " and ' as character references.
std::string markupEscaped(const std::string& text);

}  // namespace simlab
