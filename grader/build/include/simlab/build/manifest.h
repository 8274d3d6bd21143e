// The build manifest: what CMake built for the engine and how to compile and link student code
// (written by cmake/Simlab.cmake to <build>/simlab-build.json).
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace simlab::engine {

struct Assignment {
    std::string id;
    std::string title;
    std::string source;            ///< file name a student hands in, e.g. NewtonsApple.cpp
    std::string program;           ///< name of the lab program
    std::string programPath;       ///< the lab program built from the in-tree student file
    std::string referenceProgramPath;  ///< built from the solution; empty without solutions/
    std::string studyProgramPath;      ///< the work-precision study of the solution; empty without one
    std::string dir;               ///< assignments/<id>
    std::string rubric;
    std::string contractInclude;   ///< the one include folder a student file sees: the contract and support headers
    std::vector<std::string> compile;  ///< compiler, flags and the assignment's precompiled header; append
                                       ///< -I<contractInclude> -c SOURCE -o OBJECT
    std::string starter;
    std::string solution;          ///< empty in the student bundle
    bool solutionShipped = false;  ///< the solution is handed out as a worked example (simlab_add_assignment's
                                   ///< WORKED_EXAMPLE): in the student bundle, and no secret
    bool hiddenTestsBuilt = false;
    std::vector<std::string> hiddenTests;  ///< the hidden tests' source files (absent from the student bundle)
    std::string judge;                     ///< the tests' program, which decides every verdict
    std::vector<std::string> probeObjects;  ///< the course's side of the probe, linked before the student's object
    std::vector<std::string> floorObjects;  ///< tests and probe in one program (the benchmark's floor)
    std::vector<std::string> programObjects;
    std::vector<std::string> studyObjects;  ///< the work-precision study's side, for a study of any student file
    std::string buildDir;              ///< where CMake built the assignment's folder (its judge, its tests' objects)
    std::string precompiledHeader;     ///< the header `compile` reads precompiled (<pch>/<id>.h), "" without one
    std::vector<std::string> precompileFlags;  ///< what building it adds to Manifest::compile
};

/// What a lab built out of the tree builds against (cmake/Simlab.cmake's simlab_kit): the headers its code
/// includes, simlab's CMake scripts, and each library simlab_add_assignment() names, with what it links after it.
struct Kit {
    struct Target {
        std::string name;
        std::string kind;  ///< STATIC, OBJECT or INTERFACE
        std::vector<std::string> files;
        std::vector<std::string> links;
    };
    std::vector<std::string> include;
    std::string cmakeDir;
    std::vector<Target> targets;
};

struct Manifest {
    std::string path;
    std::string version;
    std::string sourceDir;
    std::string buildDir;
    /// Installed (`cmake --install`): the manifest under <prefix>/lib/simlab, its paths written from the prefix
    /// it is found in, so that a moved prefix still works. The precompiled headers are then made where this
    /// prefix is, on first use (ensurePrecompiledHeaders).
    bool installed = false;
    std::string prefix;                ///< the installed prefix, "" for a build tree
    std::string cacheDir;              ///< what simlab keeps between runs (compiled files, labs' builds, an
                                       ///< installation's precompiled headers): $SIMLAB_CACHE, else <build>/cache
                                       ///< or, installed, the user's cache
    std::string cmake;                 ///< the cmake that configured the build
    std::string studiesTarget;         ///< the target that builds every study (left out of `all` in the bundle)
    std::string sampleClass;           ///< <build>/sample-class: one folder per assignment, made from tests/corpus
    std::string catch2Include;         ///< the folder holding catch2/catch.hpp (Catch2 2.13)
    std::vector<std::string> compile;  ///< compiler and flags of every student file (an assignment's adds its
                                       ///< precompiled header: Assignment::compile)
    std::vector<std::string> link;     ///< linker driver and flags
    std::vector<std::string> probeLibraries;  ///< shared libraries a probe links after the student's object
    std::vector<std::string> probeLink;       ///< flags a probe's link adds: a shared object exporting its entry
                                              ///< point alone (see cmake/Simlab.cmake)
    std::string probeHost;                    ///< simlab-probe-host, the program every probe runs in
    std::vector<std::string> floorLibraries;
    std::vector<std::string> programLibraries;
    std::vector<std::string> studyLibraries;
    std::vector<Assignment> assignments;
    Kit kit;

    /// The assignment with this id; throws UsageError listing the known ones. A folder (a path, or a name with a
    /// slash) is a lab of one's own: built on first use against this simlab (simlab/build/lab.h) and kept in
    /// `labs`, whose secrets are then every sandbox's to miss as the course's are.
    const Assignment& find(const std::string& id) const;
    mutable std::vector<std::unique_ptr<Assignment>> labs;
    std::vector<std::string> ids() const;
};

/// The assignments a lab built out of the tree declares (its build's simlab-lab.json).
std::vector<Assignment> loadLabManifest(const std::string& path);

/// What no student may have, for one assignment: its hidden tests' sources, its solution's folder, its judge
/// (which holds the hidden tests) and its tests' objects, the hidden trade question's text as the build embeds
/// it, what the build made of the solution (its object, its reference lab program and study) - the solution's
/// part not for a worked example handed out with the bundle - and the course's sample class.
std::vector<std::string> secretPaths(const Manifest& manifest, const Assignment& assignment);

/// Everything of the course no student may have: every assignment's secretPaths, the corpus (the solutions'
/// edits), the object cache (every student's source), the source tree's history (.git: every file it ever held)
/// and the test logs (build/Testing); `simlab list --secrets`, and what the student bundle leaves out. (What no
/// test's code may read is wider: everything of simlab's places but what a test is lent, isolation/reach.h.)
std::vector<std::string> courseSecrets(const Manifest& manifest);

/// The manifest at SIMLAB_MANIFEST if set, else the one of the build this engine was built in. simlab's places it
/// names - its sources, its build or installation, its cache ($SIMLAB_CACHE, which holds every cache), the sample
/// class - are out of every sandbox's reach from then on (isolation::addPlaces). Throws UsageError if it is
/// missing or unreadable.
Manifest loadManifest();
Manifest loadManifest(const std::string& path);

/// The manifest of an installed simlab whose executable is `exe` (<prefix>/bin/simlab): <prefix>/lib/simlab/
/// simlab-build.json, or "" if there is none.
std::string installedManifestPath(const std::string& exe);

}  // namespace simlab::engine
