// Building student code: compile the one file (with the precompiled Simbody header, cached by content) and
// link it with the grader's or the lab program's prebuilt objects.
#pragma once

#include <string>

#include "simlab/engine/manifest.h"

namespace simlab::engine {

struct BuildResult {
    bool ok = false;
    std::string stage;        ///< where it failed: "compile" or "link"
    std::string log;          ///< the first lines of the compiler's or linker's message
    std::string warnings;     ///< compiler warnings when it succeeded
    bool cached = false;      ///< the object came from the cache
    double compileSeconds = 0;
    double linkSeconds = 0;
    std::string binary;
};

class Builder {
public:
    /// Objects are cached in <build>/cache/objects, or in $SIMLAB_CACHE.
    explicit Builder(const Manifest& manifest);

    /// Compile `source` in `workDir` and link it with `assignment`'s grader into the program `binary`.
    BuildResult buildGrader(const Assignment& assignment, const std::string& source, const std::string& workDir,
                            const std::string& binary) const;
    /// Compile `source` and link it with the course's main into the lab program at `output`.
    BuildResult buildProgram(const Assignment& assignment, const std::string& source, const std::string& output) const;
    /// Key of a source file's object in the cache: its content, the compile command and the precompiled header.
    std::string objectKey(const std::string& sourceText) const;
    /// Changes whenever the grader a submission is linked with might: the compile and link commands, the
    /// precompiled header, the assignment's test objects and the libraries (by path, size and time stamp).
    std::string graderKey(const Assignment& assignment) const;

private:
    BuildResult compile(const std::string& source, const std::string& workDir, std::string* object) const;
    void link(const std::vector<std::string>& inputs, const std::string& output, BuildResult& result) const;

    const Manifest& manifest_;
    std::string cacheDir_;
};

/// At most `maxLines` lines of a tool's output, the rest summarized as "... (N more lines)".
std::string firstLines(const std::string& text, int maxLines);

}  // namespace simlab::engine
