// record.json: what simlab keeps of a student's grade to resume a class, and reading it back.
#include "common.h"
#include "simlab/writers/writers.h"

#include <algorithm>
#include <cmath>

namespace simlab::engine {

std::string recordJson(const StudentRecord& r) {
    nlohmann::json tests = nlohmann::json::array();
    for (const TestResult& t : r.tests) {
        nlohmann::json j = {{"name", t.name},         {"visibility", t.visibility}, {"score", t.score},
                            {"max_score", t.maxScore}, {"credit", t.credit}, {"outcome", outcomeName(t.outcome)},
                            {"reason", t.reason},     {"feedback", t.feedback},     {"seconds", t.seconds}};
        if (t.figure) j["figure"] = {{"value", *t.figure}, {"unit", t.unit}};
        for (const BoardEntry& e : t.leaderboard) {
            j["leaderboard"].push_back({{"name", e.name}, {"value", e.value}, {"order", e.order}});
        }
        tests.push_back(j);
    }
    nlohmann::json late = {{"hours", r.late.hours}, {"percent", r.late.percent}, {"line", r.late.line}};
    if (const StudentRecord::Lateness::Slip& s = r.late.slip; s.bank > 0) {
        late["slip"] = {{"bank", s.bank}, {"due", s.due},   {"needed", s.needed},
                        {"had", s.had},   {"used", s.used}, {"ledger", s.ledger}};
    }
    const nlohmann::json record = {
        {"id", r.id},
        {"key", r.key},
        {"basis", r.basis},
        {"status", statusName(r.status)},
        {"note", r.note},
        {"file", r.file},
        {"content", r.content},
        {"score", r.score},
        {"max_score", r.maxScore},
        {"seconds", r.seconds},
        {"compiler", r.compiler},
        {"sandbox", r.sandbox},
        {"assignment", r.assignment},
        {"built", r.built},
        {"build", r.build},
        {"not_run_count", r.notRunCount},
        {"not_run_points", r.notRunPoints},
        {"submitted", r.submitted},
        {"submitted_from", r.submittedFrom},
        {"late", late},
        {"tests", tests}};
    return writers::jsonText(record);
}

std::optional<StudentRecord> readRecordJson(const std::string& text) {
    try {
        const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
        StudentRecord r;
        r.id = j.at("id");
        r.key = j.at("key");
        r.basis = j.value("basis", "");
        const std::optional<SubmissionStatus> status = statusNamed(j.at("status").get<std::string>());
        if (!status) return std::nullopt;  // a status this simlab does not name: the student is regraded
        r.status = *status;
        r.note = j.at("note");
        r.file = j.at("file");
        r.content = j.value("content", "");  // none from an older simlab
        r.score = j.at("score");
        r.maxScore = j.at("max_score");
        r.seconds = j.at("seconds");
        r.compiler = j.at("compiler");
        r.sandbox = j.value("sandbox", "");
        // What results.json shows besides the tests: a record without it is from an older simlab (regraded).
        r.assignment = j.at("assignment");
        r.built = j.at("built");
        r.build = j.at("build");
        r.notRunCount = j.at("not_run_count");
        r.notRunPoints = j.at("not_run_points");
        r.submitted = j.value("submitted", "");
        r.submittedFrom = j.value("submitted_from", "");
        if (j.contains("late")) {
            r.late.hours = j["late"].at("hours");
            r.late.percent = j["late"].at("percent");
            r.late.line = j["late"].at("line");
            if (!(r.late.percent >= 0 && r.late.percent <= 100)) return std::nullopt;
            if (j["late"].contains("slip")) {
                const nlohmann::json& s = j["late"]["slip"];
                StudentRecord::Lateness::Slip& slip = r.late.slip;
                slip.bank = s.at("bank");
                slip.due = s.at("due");
                slip.needed = s.at("needed");
                slip.had = s.at("had");
                slip.used = s.at("used");
                slip.ledger = s.at("ledger");
                // The days a bank could hold and a lab spend of it; anything else is a damaged record.
                if (slip.bank < 1 || slip.bank > 365 || slip.needed < 0 || slip.had < 0 || slip.had > slip.bank ||
                    slip.used < 0 || slip.used > slip.had || slip.used > slip.needed) {
                    return std::nullopt;
                }
            }
        }
        for (const nlohmann::json& t : j.at("tests")) {
            TestResult x;
            x.name = t.at("name");
            x.visibility = t.at("visibility");
            x.score = t.at("score");
            x.maxScore = t.at("max_score");
            x.outcome = outcomeNamed(t.at("outcome"));
            // A record of an older simlab has no credit: its share of the points, or all or nothing.
            x.credit = t.contains("credit") ? t["credit"].get<double>()
                       : x.maxScore > 0     ? x.score / x.maxScore
                                            : x.outcome == Outcome::Passed ? 1.0 : 0.0;
            x.reason = t.at("reason");
            x.feedback = t.at("feedback").get<std::vector<std::string>>();
            x.seconds = t.at("seconds");
            if (t.contains("figure")) {
                x.figure = t["figure"].at("value").get<double>();
                x.unit = t["figure"].at("unit");
            }
            for (const nlohmann::json& e : t.value("leaderboard", nlohmann::json::array())) {
                x.leaderboard.push_back({e.at("name"), e.at("value"), e.at("order")});
            }
            // What a grade is made of, as simlab writes it; anything else is a damaged record.
            const bool named = std::none_of(r.tests.begin(), r.tests.end(),
                                             [&](const TestResult& other) { return other.name == x.name; });
            if (!named || !std::isfinite(x.credit) || x.credit < 0 || x.credit > 1 || !std::isfinite(x.score) ||
                !std::isfinite(x.maxScore) || x.maxScore < 0) {
                return std::nullopt;
            }
            r.tests.push_back(x);
        }
        return r;
    } catch (const std::exception&) {
        return std::nullopt;  // damaged or from another version: regrade
    }
}

}  // namespace simlab::engine
