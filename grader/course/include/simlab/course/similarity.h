// Which submissions of a class are far more alike than the class: each pair of files compared, once the starter's
// code is removed by its tokens, by Debian's similarity-tester (sim_c++, Dick Grune's token-run comparison, the
// measure MOSS's users know): the share of each file's tokens that lies in runs shared with the other. Both steps
// compare tokens with identifiers, numbers and strings by kind alone, so that renaming hides neither a copy nor
// the starter. The tokens are read by cppTokens, a small C++ tokenizer (Debian's C++ lexers come with a compiler
// or a preprocessor library: libclang, Boost.Wave's compiled lexer, which the grader does not otherwise need).
#pragma once

#include <cstddef>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace simlab::engine {

/// A token of C++ source: its text, its kind (the keyword or punctuator itself, or ID, NUM, STR, CHR) and its line.
struct CppToken {
    std::string text;
    std::string kind;
    int line = 0;
};

/// The tokens of C++ source, comments and #include lines left out, read as the compiler reads them: lines joined
/// at a backslash that ends one, digraphs (<% %> <: :> %:) and alternative tokens (and, or, not_eq, ...) as the
/// punctuators they are, in their usual spelling. Each token has the line of the file where it starts. Any bytes
/// read: an unterminated literal or comment ends at the end of its line or the file.
std::vector<CppToken> cppTokens(const std::string& source);

/// The default floor: a pair at or above it is flagged whatever the class. In a scaffolded lab every honest
/// solution looks alike, so the class-relative threshold can reach 100 % and miss copies. Honest apple solutions
/// that differ by a few edits each share up to 78 % a pair; their copies, renamed or not, 91 % or more.
inline constexpr double kSimilarityFloor = 90;

/// A run of tokens both files hold, by the lines of each file as handed in (1-based, both ends included).
struct SharedRun {
    int aFirst = 0, aLast = 0;
    int bFirst = 0, bLast = 0;
    int tokens = 0;
};

struct SimilarPair {
    std::string a, b;     ///< student ids, a < b
    double percent = 0;   ///< the larger of the two shares: how much of one file the other holds
    bool overFloor = false;       ///< at or above the report's floor
    bool overClass = false;       ///< at or above the class-relative threshold
    std::vector<SharedRun> runs;  ///< a flagged pair's shared runs, most tokens first
};

struct SimilarityReport {
    std::vector<std::string> ids;     ///< the students compared (those with a file)
    std::vector<SimilarPair> pairs;   ///< every pair sim_c++ found anything in, most alike first
    double median = 0;                ///< of every pair of the class (pairs with nothing shared count as 0)
    double spread = 0;                ///< of every pair: 1.4826 x the median absolute deviation from the median
    double threshold = 0;             ///< the class-relative threshold (similarityThreshold)
    double floor = kSimilarityFloor;  ///< the absolute floor
    std::vector<SimilarPair> flagged;  ///< at or above the floor or the threshold, with their shared runs
    std::map<std::string, std::set<int>> starterLines;  ///< each file's lines the starter's code took whole
};

/// Which rule flagged a pair: "floor", "class", "floor, class", or "" when neither did.
std::string flaggedBy(const SimilarPair& pair);

/// The percent at or above which a pair is flagged: the class's median pair and three times its spread, at least
/// 50 % and at most 100 % (a class made from one file still shows its identical copies).
double similarityThreshold(double median, double spread);

/// `text` as it is compared: its tokens on their own lines, without the starter's code (the places where the file
/// holds a run of the starter's tokens, identifiers, numbers and strings compared by kind), literals emptied.
std::string withoutStarter(const std::string& text, const std::string& starter);

/// The runs of `sim_c++ -n` output ("3.cpp: line 4-9 |5.cpp: line 2-7 [40]") by file number, the lower first.
std::map<std::pair<std::size_t, std::size_t>, std::vector<SharedRun>> parseSimRuns(const std::string& output);

/// Compares every pair of `files` (id -> the file's text), the starter's code removed by its tokens, with sim_c++ run
/// in the sandbox (it reads students' bytes), and flags a pair at or above `floor` or the class-relative threshold.
/// Throws UsageError in one line if sim_c++ is missing or fails.
SimilarityReport compareSubmissions(const std::map<std::string, std::string>& files, const std::string& starter,
                                    double floor = kSimilarityFloor);

/// The page: the flagged pairs and the rule that flagged each, each pair with both files side by side (its shared
/// runs highlighted, the lines of the starter's code dimmed), and the class's
/// spread of pairs; self-contained, as every page of simlab's.
std::string similarityHtml(const std::string& title, const SimilarityReport& report,
                           const std::map<std::string, std::string>& files);

}  // namespace simlab::engine
