// Building student code: compile the one file against its assignment's contract (with the precompiled Simbody
// header, cached by content), check that the object adds to the course's code without replacing any of it, and
// link it after the course's objects into the probe - or into the lab program.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "simlab/engine/process.h"
#include <vector>

#include "simlab/engine/manifest.h"

namespace simlab::engine {

struct BuildResult {
    bool ok = false;
    bool interrupted = false;  ///< simlab's own interrupt stopped the compiler or linker: no outcome at all
    std::string stage;         ///< where it failed: "compile", "check" (forbidden code) or "link"
    std::string log;           ///< the first lines of the compiler's or linker's message, or the check's reasons
    std::string warnings;      ///< compiler warnings when it succeeded
    bool cached = false;       ///< the object came from the cache
    bool stoppedByLimit = false;  ///< a course limit stopped the compiler or linker (log's first line says which)
    double compileSeconds = 0;
    double linkSeconds = 0;
    std::string binary;
};

/// A symbol the course's side of a probe defines or refers to - in its objects, the libraries it links or the C
/// and C++ runtime.
struct CourseSymbol {
    bool defined = false;     ///< somewhere in the course
    bool strong = false;      ///< some definition of it is strong (not weak or inline)
    bool inObjects = false;   ///< the course's objects define it (their copy is the one linked)
    bool inLibraries = false; ///< a shared library or the runtime defines it
    bool required = false;    ///< the course's objects need it and nothing of the course's defines it: a contract
                              ///< function the student writes
    bool referenced = false;  ///< something of the course's refers to it
    std::string from;         ///< where it is defined: "course", or a library's file name such as "libc.so.6"
};
using CourseSymbols = std::map<std::string, CourseSymbol>;

/// What a student's object may not do, one line each ("NewtonsApple.cpp defines simlab::describeModel(...), which
/// the course's code defines: a submission may define only the contract's functions and its own helpers"): hold
/// a section a compiler does not make from C++ (LTO code, .preinit_array, .init, a constructor or destructor with a
/// priority, ...), define an ifunc, define a symbol the course defines (or redefine inline one it defines out of
/// line, or export its own copy of one a library exports, which would take the library's place for every caller),
/// or define a hook the course's runtime calls when it exists (__gmon_start__, say). Empty when it is clean.
std::vector<std::string> forbiddenCode(const std::string& objectPath, const std::string& sourceName,
                                       const CourseSymbols& course);

/// Where the sandbox's users could not reach what a build lends them (the contract's headers, the precompiled
/// header, the course's objects and libraries) - as root without bubblewrap each tool runs as a throwaway user,
/// which must be able to pass through every folder above them: one line naming the closed folder and the fix
/// ("... chmod o+x /root"). Tried as a tool is run (readableInSandbox), and only where such users are used; empty
/// where everything is reachable.
std::string sandboxCannotReach(const Manifest& manifest, const Assignment& assignment);

/// An installed simlab's precompiled header for `assignment`, made where the manifest places it (manifest.h) the
/// first time the prefix grades that assignment, and again after the prefix moves (clang's name their headers by
/// path), saying so on stderr. Nothing for a build tree, whose build makes them. Throws SetupError if the compiler
/// fails.
void ensurePrecompiledHeader(const Manifest& manifest, const Assignment& assignment);

class Builder {
public:
    /// Objects are cached in <cache>/objects (Manifest::cacheDir), or in $SIMLAB_CACHE.
    explicit Builder(const Manifest& manifest);

    /// Compile the student's file (`name`, its bytes `text`) in `workDir` in the sandbox, check the object, and link
    /// it after the course's probe objects into the program `binary`.
    BuildResult buildProbe(const Assignment& assignment, const std::string& name, const std::string& text,
                           const std::string& workDir, const std::string& binary) const;
    /// Compile the student's file and link it with the course's main into the lab program at `output`.
    BuildResult buildProgram(const Assignment& assignment, const std::string& name, const std::string& text,
                             const std::string& output) const;
    /// The assignment's work-precision study program (simlab/study.h) built from a student file, as buildProgram
    /// builds the lab program, and with the object check grading makes (simlab runs it, in its sandbox).
    BuildResult buildStudy(const Assignment& assignment, const std::string& name, const std::string& text,
                           const std::string& output) const;
    /// Key of a source file's object in the cache: its content, the compile command, the contract's headers and
    /// the precompiled header.
    std::string objectKey(const Assignment& assignment, const std::string& sourceText) const;
    /// Changes whenever what a submission is graded with might: the object key's parts, the link command, the
    /// course's probe objects, the libraries and the judge (by path, size and time stamp).
    std::string graderKey(const Assignment& assignment) const;
    /// What a grade depends on besides the submission and the rubric, by content: the compile and link commands
    /// (with this build's own folders written as <build> and <source>), the precompiled header, the contract's
    /// headers, the course's probe objects, the libraries and the judge. Another machine's copy of the same build
    /// has the same key, wherever it is and whatever its files' times, so a class's records are reused there.
    std::string gradingKey(const Assignment& assignment) const;
    /// The course's symbols for `assignment`'s probe, found once (and kept in the cache).
    const CourseSymbols& courseSymbols(const Assignment& assignment) const;
    /// The folder of the object cache (SIMLAB_CACHE, or the build's cache/).
    const std::string& cacheDir() const { return cacheDir_; }

private:
    /// The student's file compiled and linked first, before `objects` and `libraries`, into `output`.
    BuildResult buildLinked(const Assignment& assignment, const std::string& name, const std::string& text,
                            const std::string& output, const std::vector<std::string>& objects,
                            const std::vector<std::string>& libraries, bool checkObject) const;
    BuildResult compile(const Assignment& assignment, const std::string& name, const std::string& text,
                        const std::string& workDir, std::string* object) const;
    void link(const std::vector<std::string>& inputs, const std::vector<std::string>& flags, const std::string& output,
              BuildResult& result) const;
    /// Runs the compiler on `name` (holding `text`) in `workDir`, in the sandbox, into `output`.
    ProcessResult runCompiler(const Assignment& assignment, const std::string& name, const std::string& text,
                              const std::string& workDir, const std::string& output) const;
    /// Throws SetupError if the precompiled header is older than a file it was made from (as its dependency file
    /// lists them): a header of the system changed since simlab was built (a package upgrade), and the compiler
    /// would refuse the header for every file that includes that one again - no fault of the file at hand. The
    /// constructor calls it, so that simlab stops before it builds anything.
    void checkPrecompiledHeader() const;
    /// The object check (forbiddenCode) of a compiled student file: true, with `result` saying why, if it is refused.
    bool refusedObject(const Assignment& assignment, const std::string& object, const std::string& name,
                       BuildResult& result) const;

    const Manifest& manifest_;
    std::string cacheDir_;
};

/// At most `maxLines` lines of a tool's output, the rest summarized as "... (N more lines)".
std::string firstLines(const std::string& text, int maxLines);

/// The object cache's size cap: $SIMLAB_CACHE_MIB MiB (default 2048); a UsageError for a value that is no size.
std::uintmax_t objectCacheCap();
/// Keep the object cache `dir` under its cap: past it, the entries least recently used go, oldest first, down to
/// 80 % of the cap, never one used in the last hour. Run once per Builder, before anything is compiled.
void trimObjectCache(const std::string& dir);

}  // namespace simlab::engine
