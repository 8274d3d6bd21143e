// The judge's verdict records: what the judge writes, the engine reads back whole, and a record with a field
// missing or of the wrong type is refused, naming the field.
#include "simlab/protocol/verdict.h"

#include <catch2/catch.hpp>
#include <string>

namespace verdict_test {

using simlab::wire::ChannelFailure;
using simlab::wire::endRecord;
using simlab::wire::isEndRecord;
using simlab::wire::readVerdict;
using simlab::wire::startRecord;
using simlab::wire::Verdict;
using simlab::wire::WireError;

namespace {

Verdict fullVerdict() {
    Verdict v;
    v.test = "apple lands";
    v.passed = false;
    v.credit = 0.25;
    v.reason = "14.8 digits, need 15";
    v.feedback = {"a line", "another"};
    v.attachments = {{"model.svg", "<svg/>"}};
    v.figure = simlab::wire::Figure{14.8, "digits"};
    v.channel = ChannelFailure::BadReport;
    v.seconds = 1.5;
    v.shared = {{"abc123", 0.5}};
    v.leaderboard = {{"trade: evaluations", 30, "asc"}, {"trade: digits kept", 12, "desc"}};
    return v;
}

// `record` with `key` set to `value` (or removed, when value is discarded).
nlohmann::json with(nlohmann::json record, const std::string& key, const nlohmann::json& value) {
    if (value.is_discarded()) record.erase(key);
    else record[key] = value;
    return record;
}

std::string refusal(const nlohmann::json& record) {
    try {
        readVerdict(record);
    } catch (const WireError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("a verdict reads back as it was written", "[wire]") {
    const Verdict v = fullVerdict();
    // Through text, as the report channel carries it.
    const Verdict back = readVerdict(nlohmann::json::parse(endRecord(v).dump()));
    CHECK(back.test == v.test);
    CHECK(back.passed == v.passed);
    CHECK(back.credit == v.credit);
    CHECK(back.reason == v.reason);
    CHECK(back.feedback == v.feedback);
    REQUIRE(back.attachments.size() == 1);
    CHECK(back.attachments[0].name == "model.svg");
    CHECK(back.attachments[0].text == "<svg/>");
    REQUIRE(back.figure);
    CHECK(back.figure->value == 14.8);
    CHECK(back.figure->unit == "digits");
    CHECK(back.channel == ChannelFailure::BadReport);
    CHECK(back.seconds == 1.5);
    CHECK(back.shared == v.shared);
    REQUIRE(back.leaderboard.size() == 2);
    CHECK(back.leaderboard[0].name == "trade: evaluations");
    CHECK(back.leaderboard[0].value == 30);
    CHECK(back.leaderboard[1].order == "desc");
}

TEST_CASE("a verdict without a figure or a channel failure reads back without them", "[wire]") {
    Verdict v = fullVerdict();
    v.figure.reset();
    v.channel = ChannelFailure::None;
    const nlohmann::json record = endRecord(v);
    CHECK_FALSE(record.contains("figure"));
    CHECK_FALSE(record.contains("channel"));
    const Verdict back = readVerdict(record);
    CHECK_FALSE(back.figure);
    CHECK(back.channel == ChannelFailure::None);
}

TEST_CASE("only a test's own end record is its verdict", "[wire]") {
    const nlohmann::json end = endRecord(fullVerdict());
    CHECK(isEndRecord(end, "apple lands"));
    CHECK_FALSE(isEndRecord(end, "apple falls"));
    CHECK_FALSE(isEndRecord(startRecord("apple lands"), "apple lands"));
    CHECK_FALSE(isEndRecord(nlohmann::json::array(), "apple lands"));
    CHECK_FALSE(isEndRecord(with(end, "test", 5), "apple lands"));
}

TEST_CASE("a malformed verdict is refused, naming its field", "[wire]") {
    const nlohmann::json good = endRecord(fullVerdict());
    const nlohmann::json none(nlohmann::json::value_t::discarded);
    CHECK(refusal(good).empty());
    CHECK(refusal(nlohmann::json::array()) == "verdict is not an object");
    CHECK(refusal(with(good, "passed", none)) == "verdict.passed is missing");
    CHECK(refusal(with(good, "passed", "yes")) == "verdict.passed is not true or false");
    CHECK(refusal(with(good, "credit", "1")) == "verdict.credit is not a number");
    CHECK(refusal(with(good, "credit", 1.5)) == "verdict.credit is not a number from 0 to 1");
    CHECK(refusal(with(good, "credit", nullptr)) == "verdict.credit is not a number from 0 to 1");
    CHECK(refusal(with(good, "reason", none)) == "verdict.reason is missing");
    CHECK(refusal(with(good, "feedback", {"ok", 3})) == "verdict.feedback[1] is not a string");
    CHECK(refusal(with(good, "attachments", {{{"name", "x.svg"}}})) == "verdict.attachments[0].text is missing");
    CHECK(refusal(with(good, "attachments", {{{"name", "../x"}, {"text", ""}}})) ==
          "verdict.attachments: '../x' is not allowed");
    CHECK(refusal(with(good, "figure", {{"value", "high"}, {"unit", "m"}})) == "verdict.figure.value is not a number");
    CHECK(refusal(with(good, "channel", "lost")) == "verdict.channel 'lost' is not known");
    CHECK(refusal(with(good, "seconds", none)) == "verdict.seconds is missing");
    CHECK(refusal(with(good, "seconds", -1)) == "verdict.seconds is not a finite number >= 0");
    CHECK(refusal(with(good, "shared", {{"abc", "fast"}})) == "verdict.shared.abc is not a number");
    CHECK(refusal(with(good, "leaderboard", {{{"name", "x"}, {"value", 1}, {"order", "up"}}})) ==
          "verdict.leaderboard's order is asc or desc");
    CHECK(refusal(with(good, "leaderboard", {{{"name", "x"}, {"value", nullptr}, {"order", "asc"}}})) ==
          "verdict.leaderboard.x is not a finite number");
    // A judge of an older simlab gives no leaderboard: read as none.
    CHECK(readVerdict(with(good, "leaderboard", none)).leaderboard.empty());
}

}  // namespace verdict_test
