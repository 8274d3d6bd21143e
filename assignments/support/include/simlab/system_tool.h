// A tool of the system that a lab program draws with (Graphviz's dot, gnuplot): started by name from the PATH, with
// no shell, text on its standard input, its output and complaints read back. simlab's own children (the sandboxed
// tests, the compilers, pandoc) go through the grading engine's launcher instead (simlab/isolation/process.h); the
// lab programs do not link the engine.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace simlab {

/// What a tool did: its exit status (or the signal that ended it) and what it wrote.
struct SystemToolRun {
    bool exited = false;   ///< it exited (else a signal ended it)
    int status = 0;        ///< its exit status, or the signal's number
    std::string output;    ///< its standard output
    std::string errors;    ///< its standard error (at most 64 KiB)

    bool succeeded() const { return exited && status == 0; }
    /// Its first line of complaint, or how it ended: "exit status 1", "killed by signal 9".
    std::string reason() const;
};

/// The tool is not installed (not found on the PATH).
class SystemToolMissing : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Run argv[0] (found on the PATH) with `input` on its standard input, reading its standard output (at most
/// `maxOutput` bytes) and error at once, so that neither side waits on a full pipe. SIGPIPE stays blocked in this
/// thread meanwhile (a tool that stops reading is EPIPE, not the end of the program). Throws SystemToolMissing
/// when it is not installed, std::runtime_error ("<tool> failed: ...") when it cannot start, writes more than
/// `maxOutput` or runs past `seconds` (it is killed then).
SystemToolRun runSystemTool(const std::vector<std::string>& argv, const std::string& input, int seconds,
                            std::size_t maxOutput);

}  // namespace simlab
