// The late policy's record from authority (course/policy.h): who a student is, by the platform's ids; late or not,
// by the platform's flag; how late, by the time; what the run says of the times.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "simlab/common/errors.h"
#include "simlab/course/policy.h"

namespace policy_test {

using namespace simlab::engine;
namespace fs = std::filesystem;

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
    r.status = SubmissionStatus::Graded;
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

// --- A cap on graded submissions -------------------------------------------------------------------------------------

namespace {

PriorSubmission prior(const std::string& at, double score, bool graded = true) {
    PriorSubmission s;
    s.at = *parseTime(at);
    s.score = score;
    s.graded = graded;
    return s;
}

}  // namespace

TEST_CASE("Past a cap of three, a fourth submission keeps the last counted one's score", "[policy][cap]") {
    const SubmissionCap cap{3, 0};
    const std::vector<PriorSubmission> three = {prior("2026-10-01T10:00:00Z", 40), prior("2026-10-01T11:00:00Z", 85),
                                                prior("2026-10-01T12:00:00Z", 70)};
    // The third: counted, none left.
    CapStanding s = capStanding(cap, *parseTime("2026-10-01T12:00:00Z"), {three[0], three[1]});
    CHECK((s.counted && s.number == 3 && s.left == 0));
    CHECK(s.line == "graded submission 3 of the 3 graded submissions the course counts: none left");
    // The fourth: not graded, the score of the third (the last counted, not the best) stays.
    s = capStanding(cap, *parseTime("2026-10-02T09:00:00Z"), three);
    CHECK_FALSE(s.counted);
    REQUIRE(s.kept);
    CHECK(*s.kept == 2);
    CHECK(s.line ==
          "not graded: past the 3 graded submissions the course counts; your score stays 70, from your "
          "submission of 2026-10-01T12:00:00Z");
    // One the autograder could not grade is not counted: the fourth is the third graded.
    std::vector<PriorSubmission> failed = three;
    failed[1].graded = false;
    s = capStanding(cap, *parseTime("2026-10-02T09:00:00Z"), failed);
    CHECK((s.counted && s.number == 3 && s.left == 0));
    // Listed in any order, and a later one (a regrade's metadata) is not before this one.
    s = capStanding(cap, *parseTime("2026-10-01T10:30:00Z"), {three[2], three[0], three[1]});
    CHECK((s.counted && s.number == 2 && s.left == 1));
}

TEST_CASE("A cap per window counts the submissions within any window of its hours", "[policy][cap]") {
    const SubmissionCap cap{2, 24};
    const std::vector<PriorSubmission> two = {prior("2026-10-01T10:00:00Z", 40), prior("2026-10-01T20:00:00Z", 60)};
    CapStanding s = capStanding(cap, *parseTime("2026-10-02T09:00:00Z"), two);
    CHECK_FALSE(s.counted);
    CHECK(*s.kept == 1);
    REQUIRE(s.next);
    CHECK(utcText(*s.next) == "2026-10-02T10:00:00Z");
    CHECK(s.line.find("not graded: past the 2 graded submissions the course counts each 24 h; your score stays "
                      "60") == 0);
    // A day after the first, the window holds one: counted, none left, and when the next counts said.
    s = capStanding(cap, *parseTime("2026-10-02T10:30:00Z"), two);
    CHECK((s.counted && s.number == 2 && s.left == 0));
    CHECK(s.line ==
          "graded submission 2 of the 2 graded submissions the course counts each 24 h: none left; the next "
          "counts from 2026-10-02T20:00:00Z");
}

TEST_CASE("PrairieLearn's rate of grading lets no more than the cap through in any window", "[policy][cap]") {
    CHECK(gradeRateMinutes({3, 24}) == std::optional<int>(480));
    CHECK(gradeRateMinutes({7, 1}) == std::optional<int>(9));  // 8.57 min rounded up: 7 an hour at most, not 8
    CHECK_FALSE(gradeRateMinutes({3, 0}));                      // a count over the whole assignment: no rate says it
    CHECK_FALSE(gradeRateMinutes({0, 0}));
}

// --- A bank of slip days ---------------------------------------------------------------------------------------------

TEST_CASE("3 slip days cover 2 days late on the apple and 1 of 2 on the projectile", "[policy][slip]") {
    // 10 % a day, no grace; the apple due 2026-10-03 06:59 UTC, the projectile a week later.
    LatePolicy apple = policy();
    apple.assignment = "apple";
    apple.slipDays = 3;
    apple.slipKnown = true;
    StudentRecord a = handedIn("s", "2026-10-05T05:59:00Z", "Gradescope's created_at");  // 47 h late: 2 days
    applyLatePolicy(a, apple);
    CHECK(a.late.percent == 0);
    CHECK((a.late.slip.needed == 2 && a.late.slip.had == 3 && a.late.slip.used == 2));
    CHECK(a.late.line == "handed in 47 h late, 2 slip days spent: no penalty");
    CHECK(a.late.slip.ledger == "2 on apple (this lab); 1 of 3 left");

    // The projectile's account from the apple's record, as readSlipLedger gives it.
    SlipLedger ledger;
    ledger.labs.push_back({"apple", apple.due, {{"s", a.late.slip}}});
    LatePolicy projectile = apple;
    projectile.assignment = "projectile";
    projectile.due = *parseTime("2026-10-10T06:59:00Z");
    const SlipAccount account = slipAccount(ledger, 3, "projectile", projectile.due, "s");
    CHECK(account.had == 1);
    CHECK(account.spent == std::vector<std::pair<std::string, int>>{{"apple", 2}});
    projectile.slip["s"] = account;
    StudentRecord b = handedIn("s", "2026-10-11T18:59:00Z", "Gradescope's created_at");  // 36 h late: 2 days
    applyLatePolicy(b, projectile);
    CHECK(b.late.percent == 10);
    CHECK((b.late.slip.needed == 2 && b.late.slip.had == 1 && b.late.slip.used == 1));
    CHECK(b.late.line == "handed in 36 h late, 1 slip day spent (none left): 10 % of the score taken (10 % per day)");
    CHECK(b.late.slip.ledger == "2 on apple, 1 on projectile (this lab); 0 of 3 left");
    // A student the apple's records do not name has the whole bank.
    StudentRecord c = handedIn("t", "2026-10-11T18:59:00Z", "Gradescope's created_at");
    applyLatePolicy(c, projectile);
    CHECK((c.late.percent == 0 && c.late.slip.used == 2));

    // The apple graded again, on time: the projectile's records no longer say what the bank gives them.
    ledger.labs.push_back({"projectile", projectile.due, {{"s", b.late.slip}}});
    CHECK(staleSlipLabs(ledger, 3).empty());
    ledger.labs[0].students["s"].needed = 0;
    ledger.labs[0].students["s"].used = 0;
    const auto stale = staleSlipLabs(ledger, 3);
    REQUIRE(stale.size() == 1);
    CHECK(stale[0] == std::pair<std::string, std::vector<std::string>>{"projectile", {"s"}});
    const std::string line = staleSlipLine(stale, "grades");
    CHECK(line.find("the slip days spent on projectile (1 student: s) are not what the bank now gives them") == 0);
}

TEST_CASE("Without the other labs' records (a platform's autograder) slip days are said, not charged",
          "[policy][slip]") {
    LatePolicy p = policy();
    p.assignment = "apple";
    p.slipDays = 3;
    StudentRecord r = handedIn("s", "2026-10-05T05:59:00Z", "Gradescope's created_at");
    applyLatePolicy(r, p);
    CHECK(r.late.percent == 0);
    CHECK(r.late.line.find("the course's slip days decide it where its labs are graded together") != std::string::npos);
    CHECK((r.late.slip.bank == 3 && r.late.slip.needed == 2 && r.late.slip.ledger.empty()));
}

TEST_CASE("A negative cap, and slip days on a course with no due dates, are refused in one line", "[policy][cap]") {
    const fs::path dir = fs::temp_directory_path() / ("simlab-policy-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string path = (dir / "course.toml").string();
    auto refused = [&](const std::string& toml) {
        std::ofstream(path) << toml;
        try {
            loadLatePolicy(path, "apple", {});
        } catch (const UsageError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    CHECK(refused("[apple]\ndue = 2026-10-02T23:59:00Z\nmax_submissions = -1\n") ==
          path +
              " [apple]: max_submissions must be a whole number from 1 to 1000 (graded submissions that count; "
              "leave it out for no cap)");
    CHECK(refused("[apple]\nmax_submissions = 2.5\n").find("max_submissions must be a whole number") !=
          std::string::npos);
    CHECK(refused("[late]\nslip_days = 3\npenalty_percent = 10\n[apple]\nmax_submissions = 3\n") ==
          path +
              " [late]: slip_days = 3, but no assignment has a due date: the days are spent past each lab's due "
              "(give each lab its due = 2026-10-02T23:59:00-07:00)");
    CHECK(refused("[late]\nslip_days = -2\n[apple]\ndue = 2026-10-02T23:59:00Z\n")
              .find("slip_days must be a whole number from 0 to 365") != std::string::npos);
    CHECK(refused("[apple]\ndue = 2026-10-02T23:59:00Z\nslip_days = 2\n")
              .find("slip_days is the course's bank, for every lab: set it in [late]") != std::string::npos);
    // Well formed: read as written.
    std::ofstream(path) << "[late]\nslip_days = 3\n[apple]\ndue = 2026-10-02T23:59:00Z\nmax_submissions = 3\n"
                           "submission_window_hours = 24\n";
    const LatePolicy p = loadLatePolicy(path, "apple", {});
    CHECK((p.slipDays == 3 && p.cap.max == 3 && p.cap.windowHours == 24 && p.active));
    fs::remove_all(dir);
}

TEST_CASE("A time is written as it is read back, its year in four digits", "[policy]") {
    // Gradescope's created_at of the year 226 was kept as "226-11-20T10:00:00Z", which no reader took back.
    const std::optional<std::time_t> early = parseTime("0226-11-20T10:00:00Z");
    REQUIRE(early);
    CHECK(utcText(*early) == "0226-11-20T10:00:00Z");
    CHECK(parseTime(utcText(*early)) == early);
    CHECK(utcText(*parseTime("2026-11-20T10:00:00Z")) == "2026-11-20T10:00:00Z");
}

}  // namespace policy_test
