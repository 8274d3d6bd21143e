// How the judge's questions reach the student's code: over pipes to the probe process (observe_remote.cpp,
// what grading uses) or by a direct call into a probe linked into the same program (observe_local.cpp, for the
// benchmark's floor and for debugging). observe.cpp validates what either returns.
#pragma once

#include <cstddef>
#include <string>

namespace simlab::observe::detail {

/// A test case begins; its first exchange gets a new student's process.
void beginTest(const std::string& test);

/// Send one request line and return the answer line (without its newline). Throws ProcessEnded if the probe is
/// gone, BadReport if the answer is longer than `limit` bytes.
std::string exchange(const std::string& request, std::size_t limit);

/// After a test: close the channel and return what arrived after the last answer (at most a few KiB).
std::string drain();

}  // namespace simlab::observe::detail
