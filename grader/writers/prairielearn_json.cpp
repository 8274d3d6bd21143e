// results.json for PrairieLearn's external grader: its documented fields (score in [0, 1], gradable,
// format_errors, message, output, tests[] with name, points, max_points, message, output and images), under its
// 1 MB limit. The texts are the record's account of itself and its tests (report.h's recordAccount, testAccount),
// as Gradescope's document gives them, so both say the same.
#include <algorithm>

#include "common.h"
#include "simlab/grading/report.h"
#include "simlab/common/text.h"
#include "simlab/writers/writers.h"

namespace simlab::engine {

namespace {

using nlohmann::json;

// A submission whose file could not be graded at all: PrairieLearn marks it invalid and charges no attempt.
bool gradable(const StudentRecord& r) {
    return r.status != SubmissionStatus::MissingFile && r.status != SubmissionStatus::UnsafeFile &&
           r.status != SubmissionStatus::FileTooLarge;
}

// `text` cut to at most `bytes` bytes, on a character boundary, saying it was cut.
std::string cut(const std::string& text, std::size_t bytes) {
    static const std::string said = "\n[cut short: PrairieLearn takes at most 1 MB of results]";
    if (text.size() <= bytes) return text;
    std::size_t end = bytes > said.size() ? bytes - said.size() : 0;
    while (end > 0 && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80) --end;
    return text.substr(0, end) + said;
}

}  // namespace

std::string prairieLearnJson(const GradeReport& report, std::size_t limitBytes) {
    return prairieLearnJson(recordOf(report), limitBytes);
}

std::string prairieLearnJson(const StudentRecord& record, std::size_t limitBytes) {
    json tests = json::array();
    for (const TestResult& t : record.tests) {
        json test = {{"name", t.name}, {"points", t.score}, {"max_points", t.maxScore}};
        if (t.visibility == "visible") {
            const TestAccount account = testAccount(record, t);
            std::string more;
            for (std::size_t k = 0; k < account.more.size(); ++k) more += (k == 0 ? "" : "\n") + account.more[k];
            test["message"] = account.line;
            test["output"] = more;
            json images = json::array();
            for (const auto& [name, contents] : t.attachments) {
                const std::string mime = writers::pictureType(name);
                if (!mime.empty()) images.push_back({{"label", printable(name)}, {"url", writers::dataUri(mime, contents)}});
            }
            if (!images.empty()) test["images"] = images;
        } else {
            // PrairieLearn shows every test to the student: a hidden test shows its points and outcome only, as
            // the feedback does.
            test["message"] = outcomeName(t.outcome) + " (a hidden test: the details are your instructor's)";
            test["output"] = "";
        }
        tests.push_back(test);
    }
    const double max = record.maxScore;
    std::string message = "Score: " + points(record.score) + "/" + points(max);
    if (!record.note.empty()) message += ". " + printable(record.note);
    json doc = {{"gradable", gradable(record)},
                {"score", max > 0 ? std::clamp(record.score / max, 0.0, 1.0) : 0.0},
                {"message", message},
                {"output", recordAccount(record)},
                {"tests", tests}};
    if (!gradable(record)) {
        doc["format_errors"] = json::array({printable(record.note.empty() ? statusName(record.status) : record.note)});
    }

    // Over the limit: leave out pictures, the largest first; then cut the texts ever shorter.
    auto size = [&] { return writers::jsonText(doc).size(); };
    if (size() <= limitBytes) return writers::jsonText(doc);
    struct Picture {
        std::size_t test;
        json image;
        bool kept = true;
    };
    std::vector<Picture> pictures;
    for (std::size_t i = 0; i < doc["tests"].size(); ++i) {
        if (!doc["tests"][i].contains("images")) continue;
        for (const json& image : doc["tests"][i]["images"]) pictures.push_back({i, image});
    }
    std::vector<std::size_t> largestFirst(pictures.size());
    for (std::size_t k = 0; k < pictures.size(); ++k) largestFirst[k] = k;
    std::stable_sort(largestFirst.begin(), largestFirst.end(), [&](std::size_t a, std::size_t b) {
        return pictures[a].image["url"].get<std::string>().size() > pictures[b].image["url"].get<std::string>().size();
    });
    for (std::size_t k : largestFirst) {
        pictures[k].kept = false;
        for (json& test : doc["tests"]) test.erase("images");
        for (const Picture& p : pictures) {
            if (p.kept) doc["tests"][p.test]["images"].push_back(p.image);
        }
        doc["message"] = message + ". Pictures were left out to keep the results under PrairieLearn's 1 MB.";
        if (size() <= limitBytes) return writers::jsonText(doc);
    }
    for (std::size_t longest = limitBytes / 2; longest >= 64; longest /= 2) {
        doc["output"] = cut(doc["output"], longest);
        for (json& test : doc["tests"]) {
            test["message"] = cut(test["message"], longest);
            test["output"] = cut(test["output"], longest);
        }
        if (size() <= limitBytes) return writers::jsonText(doc);
    }
    // Still too long (a rubric of thousands of tests): the score alone.
    doc.erase("tests");
    doc["output"] = "";
    doc["message"] = message + ". The tests' results were left out: they would not fit in PrairieLearn's 1 MB.";
    return writers::jsonText(doc);
}

std::string prairieLearnErrorJson(const std::string& why) {
    const std::string said = "The autograder could not grade this submission: " + printable(why);
    return writers::jsonText({{"gradable", false}, {"score", 0}, {"message", said}, {"format_errors", {said}}});
}

}  // namespace simlab::engine
