// What simlab hands out: the student bundle, and the Gradescope autograder archive.
#pragma once

#include <string>
#include <vector>

#include "simlab/engine/manifest.h"

namespace simlab::engine {

/// The project's files, relative to its top folder: what git tracks plus what it would (untracked, not ignored);
/// outside a git checkout, every file but build folders and .git.
std::vector<std::string> projectFiles(const std::string& sourceDir);

struct PackageSummary {
    int files = 0;
    std::vector<std::string> left;  ///< what was left out, one line per kind
    std::vector<std::string> made;  ///< what was made for the package rather than copied, one line per kind
};

/// Write what students receive to `outDir` (which must not exist or be empty): everything but the solutions, the
/// hidden tests, the test corpus (made from the solutions, with expected scores), CI and benchmarks; with
/// handouts/README-student.md as its README.md, and this system's Catch2 2.13 header (third_party/catch2) for
/// systems that ship Catch2 3. It builds and self-checks on its own. Where pandoc is installed, each handout is
/// also a page (handouts/<id>.html: one file that opens offline), with the reference solution's run drawn in it
/// and its replay page beside it (for each assignment whose program draws and replays).
PackageSummary writeStudentBundle(const Manifest& manifest, const std::string& outDir);

/// Write Gradescope's autograder archive for `assignment`: the project without solutions, tests, CI and
/// benchmarks, plus setup.sh (install packages, build) and run_autograder (grade /autograder/submission into
/// /autograder/results/results.json; AUTOGRADER_ROOT changes /autograder). It carries this system's Catch2 2.13
/// header too, in third_party/catch2, for Gradescope's Ubuntu 24.04 image, whose Catch2 is version 3.
PackageSummary writeGradescopeZip(const Manifest& manifest, const Assignment& assignment, const std::string& zip);

}  // namespace simlab::engine
