// The corpus of sample submissions, each with the score the grader must give it: the course's (tests/corpus) and
// a lab's own (its corpus/ folder, which simlab assignment verify grades).
//
// A case is a TOML file (tests/corpus/<assignment>/<case>.toml, a lab's corpus/<case>.toml): a base file (the reference solution or the
// starter) plus exact edits, so the bug a case carries is the few lines it changes:
//
//     description = "Gravity points up."
//     base = "solution"                        # or "starter"
//     score = 35                               # total the grader must give, hidden tests included
//     status = "graded"                        # optional: the gradebook's status for it
//     report_contains = ["...", ["a", "b"]]   # optional: text the report must show; a list inside is a choice
//                                              # (the compiler's own words: clang's, or GCC's where it compiles)
//     report_lacks = ["..."]                   # optional: text it must not show (an answer key, say)
//     [[edit]]                                 # `find` must occur exactly once in the base
//     find = "Vec3(0, -scene.gravity, 0)"
//     replace = "Vec3(0, scene.gravity, 0)"
//     file = "BookAnswers.toml"                # optional: edit one of the rubric's extra files instead
//     percent = true                           # optional: %XX in `replace` is the byte XX (TOML holds only UTF-8)
//     [outcomes]                               # every test not listed must pass
//     "y at the final time has the target accuracy digits" = "failed"
//     tests = ["..."]                          # optional: the tests the edit concerns, which `check` runs (its
//                                              # [outcomes] among them; default: the tests [outcomes] names, or
//                                              # the rubric's first); a class grades every test of every case
//     sandbox = true                           # optional: what it does depends on the sandbox's mode (a class
//                                              # graded in each mode takes these)
//
// Attacks on the files themselves are [[file]] entries, applied after the edits, and a folder name:
//
//     folder = "%1B]0;pwned%07"                # the student's folder in a class (percent escapes decoded)
//     skipped = true                           # in a class, the folder is listed as skipped, with no row
//     [[file]]
//     name = "NewtonsApple.cpp"
//     symlink = "/etc/shadow"                  # or: fifo = true; sparse_bytes = 3221225472; remove = true;
//                                              # rename = "other name" (percent escapes decoded);
//                                              # text = "..." (with percent = true for raw bytes)
//
// In a symlink target, {class} is the class folder (to point at another student's file). In a symlink target and
// in an edit's `replace`, {source_dir} and {build_dir} are this tree's folders (an attacker may guess them). In a
// `replace`, {witness} is tests/corpus/witness.inc, code that records where it runs, as whom, with what, and which
// of simlab's secrets it can read ({secrets}: their paths for the build graded with, one per line).
//
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "simlab/build/manifest.h"
#include "simlab/grading/grade.h"
#include "simlab/rubric/rubric.h"

namespace simlab::engine {

// A file of the student's folder as a case lays it out.
struct CorpusFile {
    std::string text;
    std::string symlink;          // a symbolic link to this target instead
    bool fifo = false;            // a named pipe instead
    unsigned long long sparse = 0;  // a sparse file of this many bytes instead
};

struct CorpusCase {
    std::string name;
    std::string invariantEntry;  // [invariant] entry: the witness's record that must be there
    bool invariantRuns = true;   // [invariant] runs
    std::string folder;  // the student's folder name in a class (raw bytes)
    std::string description;
    std::map<std::string, CorpusFile> files;  // what the student hands in
    double score = 0;
    std::optional<SubmissionStatus> status;  // the gradebook's status for it, where the case says
    bool skipped = false;
    std::vector<std::vector<std::string>> reportContains;  // each: any one of these
    std::vector<std::string> reportLacks;
    std::map<std::string, std::string> outcomes;
    std::vector<std::string> tests;  // what `check` runs: the `tests` key, else the tests [outcomes] names
    bool sandbox = false;            // `sandbox = true`: what it does depends on the sandbox's mode
};

/// "%1B" is the byte 0x1B; "%%" is "%".
std::string percentDecoded(const std::string& text);

/// The case in the TOML file `path`, its files made from the assignment's solution or starter. Each key of
/// `placeholders` ("{source_dir}", say) is replaced by its value in an edit's `replace` and a symlink's target.
/// Throws std::runtime_error naming the file and what is wrong with it.
CorpusCase loadCorpusCase(const Assignment& assignment, const simlab::Rubric& rubric, const std::string& path,
                          const std::map<std::string, std::string>& placeholders = {});

/// Write a case's files into `dir`; a regular file is rewritten only when it changed, so it keeps its time stamp.
/// `{class}` in a symlink's target is `classDir`.
void writeCorpusCase(const CorpusCase& c, const std::string& dir, const std::string& classDir);

/// What differs between a case's expectations and a grade: outcomes, the score, texts the report must show (with
/// `everyTest`: a grade of only some tests shows only some texts).
std::vector<std::string> compareWithCase(const CorpusCase& c, const std::vector<TestResult>& tests,
                                         std::optional<double> score, SubmissionStatus status,
                                         const std::string& text, bool everyTest = true);

}  // namespace simlab::engine
