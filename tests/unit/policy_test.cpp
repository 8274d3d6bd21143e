// The late policy's record from authority (course/policy.h): who a student is, by the platform's ids; late or not,
// by the platform's flag; how late, by the time; what the run says of the times.
#include <catch2/catch.hpp>

#include <string>

#include "simlab/common/errors.h"
#include "simlab/course/policy.h"

using namespace simlab::engine;

namespace {

// Due 2026-10-03 06:59 UTC, 10 % a day, no grace.
LatePolicy policy() {
    LatePolicy p;
    p.active = true;
    p.due = *parseTime("2026-10-03T06:59:00Z");
    p.penaltyPercent = 10;
    return p;
}

StudentRecord handedIn(const std::string& id, const std::string& when, const std::string& from) {
    StudentRecord r;
    r.id = id;
    r.status = "graded";
    r.submitted = when;
    r.submittedFrom = from;
    return r;
}

}  // namespace

TEST_CASE("Ids: one that names one student resolves; one that names two is refused naming both", "[policy]") {
    StudentIds ids;
    ids.add("101", "lovelaceada_101");
    ids.add("ada@example.edu", "lovelaceada_101");
    ids.add("101", "lovelaceada_101");  // the same student again: still one
    ids.add("s7", "hopper_103");
    ids.add("s7", "eve_104");
    ids.add("", "nobody");  // an empty cell is no id
    CHECK(ids.find("ada@example.edu", "x") == std::optional<std::string>("lovelaceada_101"));
    CHECK(ids.find("101", "x") == std::optional<std::string>("lovelaceada_101"));
    CHECK_FALSE(ids.find("102", "x"));
    CHECK_FALSE(ids.find("", "x"));
    CHECK_THROWS_WITH(ids.find("s7", "ext.csv, row 2"),
                      Catch::StartsWith("ext.csv, row 2: 's7' is an id of two students, eve_104 and hopper_103"));
    CHECK(ids.students() == std::set<std::string>{"eve_104", "hopper_103", "lovelaceada_101"});
}

TEST_CASE("Late or not by Canvas's flag; how late by the time", "[policy]") {
    const LatePolicy p = policy();
    // Two days past, flagged late: charged two days.
    StudentRecord r = handedIn("a", "2026-10-05T06:00:00Z", "--submitted times.json");
    applyLatePolicy(r, p, handInOf(r.submitted, r.submittedFrom, true));
    CHECK(r.late.percent == 20);
    // The same time, the flag says on time: on time, the time it did not use said.
    r = handedIn("b", "2026-10-05T06:00:00Z", "Canvas's file time");
    applyLatePolicy(r, p, handInOf(r.submitted, r.submittedFrom, false));
    CHECK(r.late.percent == 0);
    CHECK(r.late.line ==
          "handed in on time by Canvas's flag (Canvas's file time, 2026-10-05T06:00:00Z, is later: not used)");
    // Flagged late, but the time is on time: no penalty on the time alone, and what to do said.
    r = handedIn("c", "2026-10-03T06:00:00Z", "Canvas's file time");
    applyLatePolicy(r, p, handInOf(r.submitted, r.submittedFrom, true));
    CHECK(r.late.percent == 0);
    CHECK(r.late.line.find("late by Canvas's flag, but Canvas's file time (2026-10-03T06:00:00Z) is on time") == 0);
    // Flagged late, no time at all.
    r = handedIn("d", "", "");
    applyLatePolicy(r, p, handInOf("", "", true));
    CHECK(r.late.percent == 0);
    CHECK(r.late.line.find("no time known to say how late") != std::string::npos);
    // No flag (Gradescope): the time decides, as before.
    r = handedIn("e", "2026-10-04T06:00:00Z", "Gradescope's created_at");
    applyLatePolicy(r, p, handInOf(r.submitted, r.submittedFrom, std::nullopt));
    CHECK(r.late.percent == 10);
}

TEST_CASE("The run says whose times no platform vouches for, where flags and times disagree, and drops one shared time",
          "[policy]") {
    const LatePolicy p = policy();
    HandIns h = {{"a", handInOf("2026-10-05T06:00:00Z", "Canvas's file time", true)},
                 {"b", handInOf("2026-10-05T06:00:00Z", "Canvas's file time", false)},
                 {"c", handInOf("2026-10-05T06:00:00Z", "Canvas's file time", false)}};
    std::vector<std::string> lines = checkHandIns(h, p);
    REQUIRE(lines.size() == 1);
    CHECK(lines[0].find("every student's time is the same, 2026-10-05T06:00:00Z") == 0);
    CHECK(lines[0].find("Canvas flags 1 student late, not charged until --submitted gives their times: a") !=
          std::string::npos);
    CHECK((h["a"].time.empty() && h["b"].time.empty()));

    h = {{"a", handInOf("2026-10-05T06:00:00Z", "Canvas's file time", true)},
         {"b", handInOf("2026-10-05T07:00:00Z", "Canvas's file time", false)},
         {"c", handInOf("2026-10-02T07:00:00Z", "Canvas's file time", false)}};
    lines = checkHandIns(h, p);
    REQUIRE(lines.size() == 2);
    CHECK(lines[0].find("Canvas's late flag and the time disagree for 1 student") == 0);
    CHECK(lines[0].find("): b; --submitted FILE") != std::string::npos);
    CHECK(lines[1].find("3 students timed by Canvas's file time, which no platform vouches for") == 0);

    h = {{"a", handInOf("2026-10-05T06:00:00Z", "Gradescope's created_at", std::nullopt)},
         {"b", handInOf("2026-10-05T06:00:00Z", "Gradescope's created_at", std::nullopt)}};
    CHECK(checkHandIns(h, p).empty());  // the platform's word, one time or not
    CHECK(h["a"].time == "2026-10-05T06:00:00Z");
}
