// Building student code: compile the one file against its assignment's contract (with the precompiled Simbody
// header, cached by content), check that the object adds to the course's code without replacing any of it, and
// link it after the course's objects into the probe - or into the lab program.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "simlab/build/manifest.h"
#include "simlab/isolation/object_check.h"
#include "simlab/isolation/process.h"

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
    std::string object;        ///< the student's object, in the object cache, once compiled
};

/// What a grading's sandboxed processes are lent of simlab's places (isolation/reach.h) beside their own folders:
/// the contract's headers and the precompiled header (the compiler), the course's objects of the probe and of the
/// lab program and the probe's export list (the linker), the probe's host. The rest of the places is none of theirs; the audit of limits only and
/// `simlab lock` keep these open to throwaway users and nothing else.
std::vector<std::string> lentToTools(const Manifest& manifest, const Assignment& assignment);

/// Where the sandbox's users could not reach what a build lends them (the contract's headers, the precompiled
/// header, the course's objects and libraries) - as root without bubblewrap each tool runs as a throwaway user,
/// which must be able to pass through every folder above them: one line naming the closed folder and the fix
/// ("... chmod o+x /root"). Tried as a tool is run (readableInSandbox), and only where such users are used; empty
/// where everything is reachable.
std::string sandboxCannotReach(const Manifest& manifest, const Assignment& assignment);

/// Why this user cannot grade `assignment` at all, in one line, where its judge is closed to them (an installation
/// whose owner closed its judges, scripts/lock-course, used by another member of the course's staff); empty where
/// they may read it.
std::string judgeNotYours(const Assignment& assignment);

/// An installed simlab's precompiled header for `assignment`, made where the manifest places it (manifest.h) the
/// first time the prefix grades that assignment, and again after the prefix moves (clang's name their headers by
/// path), saying so on stderr. Nothing for a build tree, whose build makes them. Throws SetupError if the compiler
/// fails.
void ensurePrecompiledHeader(const Manifest& manifest, const Assignment& assignment);

class Builder {
public:
    /// Objects are cached in <cache>/objects (Manifest::cacheDir: $SIMLAB_CACHE, or the build's or user's cache).
    explicit Builder(const Manifest& manifest);

    /// Compile the student's file (`name`, its bytes `text`) in `workDir` in the sandbox, check the object (unless
    /// `checkObject` is false: GradeOptions::checkObject), and link it after the course's probe objects into the
    /// probe `binary`, a shared object the probe's host loads.
    BuildResult buildProbe(const Assignment& assignment, const std::string& name, const std::string& text,
                           const std::string& workDir, const std::string& binary, bool checkObject = true) const;
    /// Compile the student's file and link it with the course's main into the lab program at `output`.
    BuildResult buildProgram(const Assignment& assignment, const std::string& name, const std::string& text,
                             const std::string& output) const;
    /// The assignment's work-precision study program (simlab/study.h) built from a student file, as buildProgram
    /// builds the lab program, and with the object check grading makes (simlab runs it, in its sandbox).
    BuildResult buildStudy(const Assignment& assignment, const std::string& name, const std::string& text,
                           const std::string& output) const;
    /// Key of a source file's object in the cache: its name and content, the compile command, the contract's
    /// headers and the precompiled header.
    std::string objectKey(const Assignment& assignment, const std::string& fileName, const std::string& sourceText) const;
    /// Changes whenever what a submission is graded with might: the object key's parts, the link command, the
    /// course's probe objects, the libraries and the judge (by path, size and time stamp).
    std::string graderKey(const Assignment& assignment) const;
    /// What a grade depends on besides the submission and the rubric, by content: the compile and link commands
    /// (with this build's own folders written as <build> and <source>), the precompiled header, the contract's
    /// headers, the course's probe objects, the libraries and the judge. Another machine's copy of the same build
    /// has the same key, wherever it is and whatever its files' times, so a class's records are reused there.
    std::string gradingKey(const Assignment& assignment) const;
    /// The course's symbols for `assignment`'s probe, found once (and kept in the cache).
    const isolation::CourseSymbols& courseSymbols(const Assignment& assignment) const;
    /// The folder of the object cache (<cache>/objects).
    const std::string& cacheDir() const { return cacheDir_; }
    /// simlab-probe-host, the program every probe of this build runs in.
    const std::string& probeHost() const { return manifest_.probeHost; }

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
    isolation::ProcessResult runCompiler(const Assignment& assignment, const std::string& name, const std::string& text,
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

/// The object cache's size cap: $SIMLAB_CACHE_MIB MiB (default 2048); a UsageError for a value that is no size.
std::uintmax_t objectCacheCap();
/// Keep the object cache `dir` under its cap: past it, the entries least recently used go, oldest first, down to
/// 80 % of the cap, never one used in the last hour. Run once per Builder, before anything is compiled.
void trimObjectCache(const std::string& dir);

}  // namespace simlab::engine
