// The build manifest: what CMake built for the engine and how to compile and link student code
// (written by cmake/Simlab.cmake to <build>/simlab-build.json).
#pragma once

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
    std::string dir;               ///< assignments/<id>
    std::string rubric;
    std::string starter;
    std::string solution;          ///< empty in the student bundle
    bool hiddenTestsBuilt = false;
    std::vector<std::string> hiddenTests;  ///< the hidden tests' source files (absent from the student bundle)
    std::vector<std::string> graderObjects;
    std::vector<std::string> programObjects;
};

struct Manifest {
    std::string path;
    std::string version;
    std::string sourceDir;
    std::string buildDir;
    std::string sampleClass;           ///< <build>/sample-class: one folder per assignment, made from tests/corpus
    std::string catch2Include;         ///< the folder holding catch2/catch.hpp (Catch2 2.13)
    std::vector<std::string> compile;  ///< compiler and flags; append -c SOURCE -o OBJECT
    std::vector<std::string> link;     ///< linker driver and flags
    std::vector<std::string> graderLibraries;
    std::vector<std::string> programLibraries;
    std::vector<Assignment> assignments;

    /// The assignment with this id; throws UsageError listing the known ones.
    const Assignment& find(const std::string& id) const;
    std::vector<std::string> ids() const;
};

/// The manifest at SIMLAB_MANIFEST if set, else the one of the build this engine was built in.
/// Throws UsageError if it is missing or unreadable.
Manifest loadManifest();
Manifest loadManifest(const std::string& path);

}  // namespace simlab::engine
