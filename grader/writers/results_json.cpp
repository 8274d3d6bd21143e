// results.json: Gradescope's document for a graded submission (report.h's toGradescope), as a file.
#include "common.h"
#include "simlab/grading/record.h"
#include "simlab/grading/report.h"
#include "simlab/common/text.h"
#include "simlab/writers/writers.h"

namespace simlab::engine {

std::string resultsJson(const StudentRecord& record) { return writers::jsonText(toGradescope(record)); }

std::string resultsJson(const GradeReport& report) { return resultsJson(recordOf(report)); }

namespace {

void addNote(nlohmann::json& document, const SubmissionsNote& note) {
    const nlohmann::json output = document.value("output", nlohmann::json(""));
    document["output"] =
        "Submissions: " + printable(note.line) + "\n" + (output.is_string() ? output.get<std::string>() : "");
    if (!document.contains("extra_data") || !document["extra_data"].is_object())
        document["extra_data"] = nlohmann::json::object();
    nlohmann::json submissions = {{"checked", note.checked}, {"max", note.max}};
    if (note.windowHours > 0) submissions["window_hours"] = note.windowHours;
    if (note.checked) {
        submissions["counted"] = note.counted;
        submissions["number"] = note.number;
        submissions["left"] = note.left;
    }
    document["extra_data"]["submissions"] = submissions;
}

}  // namespace

std::string resultsJson(const StudentRecord& record, const SubmissionsNote& note) {
    nlohmann::json document = toGradescope(record);
    addNote(document, note);
    return writers::jsonText(document);
}

std::string keptResultsJson(const nlohmann::json& earlier, double score, const SubmissionsNote& note) {
    nlohmann::json document = nlohmann::json::object();
    // What Gradescope shows of a submission: the earlier one's tests and standing, as it kept them.
    if (earlier.is_object()) {
        for (const char* key :
             {"tests", "leaderboard", "output", "output_format", "test_output_format", "extra_data"}) {
            if (earlier.contains(key)) document[key] = earlier[key];
        }
    }
    if (!document.contains("tests") || !document["tests"].is_array()) document["tests"] = nlohmann::json::array();
    document["score"] = score;
    document["stdout_visibility"] = "hidden";
    addNote(document, note);
    return writers::jsonText(document);
}

std::string resultsErrorJson(const std::string& why) {
    return writers::jsonText({{"score", 0},
                              {"output", "The autograder could not grade this submission: " + printable(why)},
                              {"tests", nlohmann::json::array()},
                              // Not graded: a cap on graded submissions does not count it.
                              {"extra_data", {{"graded", false}}}});
}

}  // namespace simlab::engine
