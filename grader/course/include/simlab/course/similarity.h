// Which submissions of a class are far more alike than the class: each pair of files compared, once the starter's
// lines are removed, by Debian's similarity-tester (sim_c++, Dick Grune's token-run comparison, the measure MOSS's
// users know): the share of each file's tokens that lies in runs shared with the other.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace simlab::engine {

struct SimilarPair {
    std::string a, b;     ///< student ids, a < b
    double percent = 0;   ///< the larger of the two shares: how much of one file the other holds
};

struct SimilarityReport {
    std::vector<std::string> ids;     ///< the students compared (those with a file)
    std::vector<SimilarPair> pairs;   ///< every pair sim_c++ found anything in, most alike first
    double median = 0;                ///< of every pair of the class (pairs with nothing shared count as 0)
    double spread = 0;                ///< of every pair: 1.4826 x the median absolute deviation from the median
    double threshold = 0;             ///< a pair at or above it is flagged (similarityThreshold)
    std::vector<SimilarPair> flagged; ///< far more alike than the class
};

/// The percent at or above which a pair is flagged: the class's median pair and three times its spread, at least
/// 50 % and at most 100 % (a class made from one file still shows its identical copies).
double similarityThreshold(double median, double spread);

/// `text` without the lines the starter has (compared without the spaces at their ends; blank lines dropped).
std::string withoutStarter(const std::string& text, const std::string& starter);

/// Compares every pair of `files` (id -> the file's text), the starter's lines removed, with sim_c++ run in the
/// sandbox (it reads students' bytes). Throws UsageError in one line if sim_c++ is missing or fails.
SimilarityReport compareSubmissions(const std::map<std::string, std::string>& files, const std::string& starter);

/// The page: the flagged pairs, each with both files side by side (the starter's lines dimmed), and the class's
/// spread of pairs; self-contained, as every page of simlab's.
std::string similarityHtml(const std::string& title, const SimilarityReport& report,
                           const std::map<std::string, std::string>& files, const std::string& starter);

}  // namespace simlab::engine
