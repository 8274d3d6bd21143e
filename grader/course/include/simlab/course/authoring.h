// Authoring a lab of one's own: a skeleton to start from (simlab assignment new) and the checks a lab must pass
// before students see it (simlab assignment verify). docs/authors.md is the guide.
#pragma once

#include <functional>
#include <string>

#include "simlab/build/manifest.h"

namespace simlab::engine {

/// Write a new lab called `name` (an id: a lowercase letter, then lowercase letters, digits or '_') in the new
/// folder `dir`, from this simlab's template (examples/template: a block on a spring, one test of each kind, a
/// starter and a reference), its id and file names made the name's. Returns the files written. Throws UsageError.
int writeLabSkeleton(const Manifest& manifest, const std::string& name, const std::string& dir);

struct VerifyOptions {
    double starterShare = 0.5;  ///< the most the starter may earn, as a share of the points
    int judges = 1;             ///< judges a grading runs at once
};

/// One verdict of verify: "ok", "FAIL", "warn" or "skip", and its line.
struct VerifyLine {
    std::string status;
    std::string text;
};

/// Check the lab in `dir` as problemtools' verifyproblem checks a problem: it builds against this simlab; the
/// reference earns every point of every test, hidden ones included; the starter earns at most a share; each case
/// of its corpus (corpus/*.toml) gets its score and outcomes; each extreme case (study/extremes.toml) names the
/// outcome the lab promises; a trade the rubric grades has its measured fronts; the student's copy of the lab holds
/// no hidden test, solution or corpus file; the rubric's CPU limit leaves the reference's slowest test a margin of
/// 2 (a limit of 5 times it, at least 1 s, is suggested), and a verdict that changes when the limit is doubled is
/// a warning. Each verdict is told to `print` as it is known; returns the number of FAILs.
int verifyLab(const Manifest& manifest, const std::string& dir, const VerifyOptions& options,
              const std::function<void(const VerifyLine&)>& print);

}  // namespace simlab::engine
