// results.json: Gradescope's document for a graded submission (report.h's toGradescope), as a file.
#include "common.h"
#include "simlab/grading/record.h"
#include "simlab/grading/report.h"
#include "simlab/writers/writers.h"

namespace simlab::engine {

std::string resultsJson(const GradeReport& report) { return writers::jsonText(toGradescope(report)); }

// results.json (Gradescope's document, written when the student was graded) with the scores of `r` now and the
// manual points given: for a record re-scored or graded by hand since.
std::string updatedResultsJson(const std::string& text, const StudentRecord& r) {
    nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
    if (doc.is_discarded() || !doc.is_object() || !doc.contains("tests") || !doc["tests"].is_array()) return text;
    for (nlohmann::json& t : doc["tests"]) {
        for (const TestResult& x : r.tests) {
            if (t.is_object() && t.value("name", "") == x.name) {
                t["score"] = x.score;
                t["max_score"] = x.maxScore;
            }
        }
    }
    doc["score"] = r.score;
    if (!doc.contains("extra_data") || !doc["extra_data"].is_object()) doc["extra_data"] = nlohmann::json::object();
    nlohmann::json& extra = doc["extra_data"];
    extra["max_score"] = r.maxScore;
    if (!r.manual.empty()) {
        nlohmann::json pending = nlohmann::json::array(), given = nlohmann::json::array();
        for (const ManualGrade& m : r.manual) {
            if (m.points) {
                given.push_back({{"name", m.name}, {"score", *m.points}, {"max_score", m.maxPoints}, {"comment", m.comment}});
            } else {
                pending.push_back({{"name", m.name}, {"max_score", m.maxPoints}, {"status", "pending"}});
            }
        }
        extra["manual_pending"] = pending;
        extra["manual_points_pending"] = r.pendingPoints();
        extra["manual_graded"] = given;
        extra["total_with_manual"] = r.total();
        extra["max_with_manual"] = r.maxTotal();
    }
    return writers::jsonText(doc);
}

}  // namespace simlab::engine
