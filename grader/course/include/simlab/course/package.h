// What simlab hands out: the student bundle, and an assignment's package for each platform that grades it -
// Gradescope's autograder archive, a PrairieLearn question, a GitHub Classroom template repository. Every
// platform's grader runs `simlab autograde` or `simlab check` on the same engine; only the format of the results
// differs (writers.h).
#pragma once

#include <string>
#include <vector>

#include "simlab/build/manifest.h"

namespace simlab::engine {

/// The project's files, relative to its top folder: what git tracks (a file added but not committed too; nothing
/// untracked); outside a git checkout, every file but build folders and .git.
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
/// With `lab` (a lab of one's own), the bundle carries it too, as labs/<its folder's name>, without its corpus,
/// solution and hidden tests: students build simlab and self-check with `simlab check labs/<name> FILE`.
PackageSummary writeStudentBundle(const Manifest& manifest, const std::string& outDir, const Assignment* lab = nullptr);

/// A lab of one's own as students receive it, in `dir`/labs/<its folder's name>: all but its corpus, its solution and
/// its hidden tests.
PackageSummary writeStudentLab(const Assignment& lab, const std::string& dir);

/// Whether `assignment` is a lab of one's own, built from its folder (simlab/build/lab.h), not one of the course's.
bool isOwnLab(const Manifest& manifest, const Assignment& assignment);
/// Where packages carry a lab of one's own: labs/<its folder's name>.
std::string labPlace(const Assignment& assignment);

/// Write Gradescope's autograder archive for `assignment`: the project without solutions, tests, CI and
/// benchmarks, plus setup.sh (install packages, build) and run_autograder (grade /autograder/submission into
/// /autograder/results/results.json; AUTOGRADER_ROOT changes /autograder). It carries this system's Catch2 2.13
/// header too, in third_party/catch2, for Gradescope's Ubuntu 24.04 image, whose Catch2 is version 3.
PackageSummary writeGradescopeZip(const Manifest& manifest, const Assignment& assignment, const std::string& zip);

struct PrairieLearnOptions {
    std::string image = "simlab-grader";  ///< the grading image's name on Docker Hub, as info.json gives it
    int timeout = 300;                    ///< seconds a grading job may take (PrairieLearn allows 600 at most)
    bool upload = false;                  ///< the student uploads the file (pl-file-upload), not edits it in the page
};

/// Write a PrairieLearn question for `assignment` to `outDir` (new or empty): info.json (external grading with
/// the image and tests/run_autograder as its entry point), question.html (the file in pl-file-editor, or
/// pl-file-upload; pl-external-grader-results in the submission panel), the starter file the editor opens with,
/// tests/run_autograder (grade /grade/student into /grade/results/results.json; GRADE_ROOT changes /grade and
/// SIMLAB names the simlab command), and image/: the grading image's Dockerfile beside the project without
/// solutions, tests, CI and benchmarks, which it builds with scripts/setup.
PackageSummary writePrairieLearnQuestion(const Manifest& manifest, const Assignment& assignment,
                                         const std::string& outDir, const PrairieLearnOptions& options);

/// Write the template repository of a GitHub Classroom assignment to `outDir` (new or empty): the student bundle
/// (writeStudentBundle: starter, contract, build, handouts) and .github/workflows/classroom.yml, which on every
/// push builds simlab, runs `simlab check --format classroom` on the assignment's visible tests and hands the
/// result to GitHub Classroom's grading reporter. Those points are a self-check, which the student's repository
/// can change; the README says so.
PackageSummary writeClassroomTemplate(const Manifest& manifest, const Assignment& assignment, const std::string& outDir);

/// Write an installed simlab's files under `root` (DESTDIR and the prefix, as `cmake --install` gives them): what
/// the build manifest names, the build's part in <root>/lib/simlab/build and the sources' in
/// <root>/share/simlab/source, and the manifest itself as <root>/lib/simlab/simlab-build.json with every path
/// written from the prefix (loadManifest places them where the prefix is found, so that it may move). Precompiled
/// headers are left out: they name their headers by path, and are made where the prefix is on first use.
PackageSummary writeInstalledTree(const Manifest& manifest, const std::string& root);

}  // namespace simlab::engine
