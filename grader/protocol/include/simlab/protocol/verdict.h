// The judge's records on its report channel (descriptor 3): one "start" record when a test case begins, and one
// "end" record, the test's verdict, when it is finished. The judge writes them and the engine reads them here, and
// nowhere else.
//
// Reading is strict, like the probe channel's: a missing or mistyped field throws WireError naming it, and the
// engine then counts the judge as having failed the test.
#pragma once

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "simlab/protocol/attachments.h"
#include "simlab/protocol/wire.h"

namespace simlab::wire {

/// A file a test attaches to the student's feedback (attachments.h says which names and sizes are allowed).
struct Attachment {
    std::string name;
    std::string text;
};
SIMLAB_WIRE(Attachment, name, text)

/// What a test measured, e.g. 14.8 "digits".
struct Figure {
    double value = 0;
    std::string unit;
};
SIMLAB_WIRE(Figure, value, unit)

/// An entry for Gradescope's leaderboard (results.json's `leaderboard`): a figure the judge measured, and whether
/// the lower ("asc") or the higher ("desc") value ranks first.
struct BoardEntry {
    std::string name;
    double value = 0;
    std::string order;
};
SIMLAB_WIRE(BoardEntry, name, value, order)

/// The most leaderboard entries one test may give.
constexpr std::size_t kMaxBoardEntries = 8;

/// How the observation channel failed a test, whatever the test itself concluded.
enum class ChannelFailure { None, BadReport, ProcessEnded };

/// The judge's verdict on one test case.
struct Verdict {
    std::string test;
    bool passed = false;
    double credit = 0;  ///< from 0 to 1: 1 when passed, else the test's partial credit
    std::string reason;
    std::vector<std::string> feedback;
    std::vector<Attachment> attachments;
    std::optional<Figure> figure;
    std::vector<BoardEntry> leaderboard;
    ChannelFailure channel = ChannelFailure::None;
    /// How long the test took in the judge, the student's process included, and the shared questions it used
    /// (by digest: the seconds each answer took): hints for sharing tests out, nothing scored.
    double seconds = 0;
    std::map<std::string, double> shared;
};

namespace verdict_detail {

inline const char* channelName(ChannelFailure channel) {
    switch (channel) {
        case ChannelFailure::BadReport:
            return "bad report";
        case ChannelFailure::ProcessEnded:
            return "process ended";
        case ChannelFailure::None:
            break;
    }
    return "";
}

inline void requireNonNegative(double value, const std::string& where) {
    if (!std::isfinite(value) || value < 0) throw WireError(where + " is not a finite number >= 0");
}

}  // namespace verdict_detail

/// The record that the test case `test` has begun.
inline nlohmann::json startRecord(const std::string& test) { return {{"event", "start"}, {"test", test}}; }

/// The record of a test case's verdict.
inline nlohmann::json endRecord(const Verdict& v) {
    nlohmann::json j = {{"event", "end"},
                        {"test", v.test},
                        {"passed", v.passed},
                        {"credit", toJson(v.credit)},
                        {"reason", v.reason},
                        {"feedback", toJson(v.feedback)},
                        {"attachments", toJson(v.attachments)},
                        {"seconds", toJson(v.seconds)},
                        {"shared", toJson(v.shared)}};
    if (v.figure) j["figure"] = toJson(*v.figure);
    if (!v.leaderboard.empty()) j["leaderboard"] = toJson(v.leaderboard);
    if (v.channel != ChannelFailure::None) j["channel"] = verdict_detail::channelName(v.channel);
    return j;
}

/// Whether `record` is the verdict record of the test case `test` (well formed or not).
inline bool isEndRecord(const nlohmann::json& record, const std::string& test) {
    if (!record.is_object()) return false;
    const auto event = record.find("event"), named = record.find("test");
    return event != record.end() && *event == "end" && named != record.end() && *named == test;
}

/// The verdict in an end record; throws WireError naming the first field that is missing or wrong.
inline Verdict readVerdict(const nlohmann::json& record) {
    const std::string where = "verdict";
    if (!record.is_object()) throw WireError(where + " is not an object");
    Verdict v;
    readField(record, "test", v.test, where);
    readField(record, "passed", v.passed, where);
    readField(record, "credit", v.credit, where);
    if (!(v.credit >= 0 && v.credit <= 1)) throw WireError(where + ".credit is not a number from 0 to 1");
    readField(record, "reason", v.reason, where);
    readField(record, "feedback", v.feedback, where);
    readField(record, "attachments", v.attachments, where);
    if (v.attachments.size() > kMaxAttachments) throw WireError(where + ".attachments has too many files");
    for (const Attachment& file : v.attachments) {
        if (!isAttachmentName(file.name)) throw WireError(where + ".attachments: '" + file.name + "' is not allowed");
        if (file.text.size() > kMaxAttachmentBytes)
            throw WireError(where + ".attachments: " + file.name + " is too large");
    }
    if (record.contains("figure")) {
        v.figure.emplace();
        readField(record, "figure", *v.figure, where);
        if (!std::isfinite(v.figure->value)) throw WireError(where + ".figure.value is not a finite number");
    }
    if (record.contains("leaderboard")) {
        readField(record, "leaderboard", v.leaderboard, where);
        if (v.leaderboard.size() > kMaxBoardEntries) throw WireError(where + ".leaderboard has too many entries");
        for (const BoardEntry& e : v.leaderboard) {
            if (e.name.empty() || e.name.size() > 100) throw WireError(where + ".leaderboard: a name is empty or long");
            if (!std::isfinite(e.value)) throw WireError(where + ".leaderboard." + e.name + " is not a finite number");
            if (e.order != "asc" && e.order != "desc") throw WireError(where + ".leaderboard's order is asc or desc");
        }
    }
    if (record.contains("channel")) {
        std::string channel;
        readField(record, "channel", channel, where);
        for (const ChannelFailure known : {ChannelFailure::BadReport, ChannelFailure::ProcessEnded}) {
            if (channel == verdict_detail::channelName(known)) v.channel = known;
        }
        if (v.channel == ChannelFailure::None) throw WireError(where + ".channel '" + channel + "' is not known");
    }
    readField(record, "seconds", v.seconds, where);
    verdict_detail::requireNonNegative(v.seconds, where + ".seconds");
    readField(record, "shared", v.shared, where);
    for (const auto& [digest, seconds] : v.shared)
        verdict_detail::requireNonNegative(seconds, where + ".shared." + digest);
    return v;
}

}  // namespace simlab::wire
