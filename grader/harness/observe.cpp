// The judge's side of observations: each question to the student's process, and the checks its answer has to
// pass before a test may look at it (see observe.h).
#include "simlab/harness/observe.h"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "transport.h"

namespace simlab::observe {

namespace {

/// A student's text as reports show it: its first 400 bytes, and how many more there were.
std::string shortened(const std::string& text) {
    constexpr std::size_t kShown = 400;
    if (text.size() <= kShown) return text;
    return text.substr(0, kShown) + "... (" + std::to_string(text.size() - kShown) + " more bytes)";
}

int gLastId = 0;
ChannelFailure gFailure = ChannelFailure::None;

// The largest answer the judge reads: SIMLAB_ANSWER_LIMIT bytes (set by the engine from the rubric), else 64 MiB.
std::size_t answerLimit() {
    const char* limit = std::getenv("SIMLAB_ANSWER_LIMIT");
    const unsigned long long bytes = limit ? std::strtoull(limit, nullptr, 10) : 0;
    return bytes > 0 ? static_cast<std::size_t>(bytes) : std::size_t{64} << 20;
}

[[noreturn]] void badReport(const std::string& why) {
    gFailure = ChannelFailure::BadReport;
    throw BadReport(why);
}

// " at t = 0.37 s" when `where` names a sample ("samples[37].yLocation") whose time is a number.
std::string sampleTime(const nlohmann::json& answer, const std::string& where) {
    if (where.rfind("samples[", 0) != 0 || !answer.contains("samples")) return "";
    const std::size_t index = std::strtoul(where.c_str() + 8, nullptr, 10);
    const nlohmann::json& samples = answer["samples"];
    if (!samples.is_array() || index >= samples.size() || !samples[index].is_object()) return "";
    const auto time = samples[index].find("time");
    if (time == samples[index].end() || !time->is_number()) return "";
    char text[48];
    std::snprintf(text, sizeof text, " at t = %g s", time->get<double>());
    return text;
}

// 64-bit FNV-1a of the question, in hex: the same question has the same digest in every run of the judge.
std::string digestOf(const std::string& key) {
    std::uint64_t h = 14695981039346656037ull;
    for (const unsigned char c : key) {
        h ^= c;
        h *= 1099511628211ull;
    }
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
    return text;
}

}  // namespace

nlohmann::json ask(const std::string& kind, const nlohmann::json& arguments) {
    const int id = ++gLastId;
    const nlohmann::json request = {{"id", id}, {"kind", kind}, {"arguments", arguments}};
    std::string line;
    try {
        line = detail::exchange(request.dump() + "\n", answerLimit());
    } catch (const ProcessEnded&) {
        gFailure = ChannelFailure::ProcessEnded;
        throw;
    } catch (const BadReport&) {
        gFailure = ChannelFailure::BadReport;
        throw;
    }
    const std::string what = "the answer to request " + std::to_string(id) + " ('" + kind + "')";
    if (wire::nestingDepth(line) > wire::kMaxNesting) {
        badReport(what + " nests deeper than " + std::to_string(wire::kMaxNesting) + " levels");
    }
    const nlohmann::json reply = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
    if (reply.is_discarded() || !reply.is_object()) badReport(what + " is not a JSON object");
    const auto number = reply.find("id");
    if (number == reply.end() || !number->is_number_integer()) badReport(what + " carries no request number");
    if (number->get<long long>() != id) {
        badReport(what + " carries the number " + number->dump() + ": an answer out of turn, twice or unasked");
    }
    const bool answered = reply.contains("answer"), threw = reply.contains("threw");
    if (reply.size() != 2 || answered == threw) badReport(what + " must hold its number and one answer or exception");
    if (threw) {
        const nlohmann::json& e = reply["threw"];
        if (!e.is_object() || !e.contains("type") || !e["type"].is_string() || !e.contains("message") ||
            !e["message"].is_string()) {
            badReport(what + " reports an exception in the wrong shape");
        }
        // Cut to what a report shows: Catch2 echoes an exception's message whole onto the judge's output, whose
        // size is capped, and a student's megabytes there must not stop the judge.
        const std::string type = shortened(e["type"]), message = shortened(e["message"]);
        // A SIMLAB_TODO speaks for itself: "not done yet (NewtonsApple.cpp:39): build the model: ...".
        throw StudentError(type == "simlab::NotDoneYet" ? message : "threw " + type + ": " + message);
    }
    const nlohmann::json& value = reply["answer"];
    const std::string where = wire::firstNull(value);
    if (!where.empty()) {
        throw NonFinite("the student's " + kind + " produced a value that is not a finite number (NaN or infinity): " +
                        where + sampleTime(value, where));
    }
    return value;
}

// Shared answers (askShared): those of tests whose channel ended clean, and those of the test under way, which
// join them only if its channel ends clean too (an answer followed by bytes nobody asked for is not kept).
static std::map<std::string, nlohmann::json> gShared, gPending;
// The shared questions the test under way used, by digest: the seconds the answer took where it asked the
// student's process, 0 where an earlier test's answer served.
static std::map<std::string, double> gUsed;

nlohmann::json askShared(const std::string& kind, const nlohmann::json& arguments) {
    const std::string key = kind + "\n" + arguments.dump();
    const std::string digest = digestOf(key);
    if (gUsed.size() < kMaxSharedReported) gUsed.emplace(digest, 0.0);
    if (const auto found = gShared.find(key); found != gShared.end()) return found->second;
    if (const auto found = gPending.find(key); found != gPending.end()) return found->second;
    const auto start = std::chrono::steady_clock::now();
    nlohmann::json value = ask(kind, arguments);  // whatever it throws is not kept: the next test asks again
    if (const auto used = gUsed.find(digest); used != gUsed.end()) {
        used->second = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    gPending.emplace(key, value);
    return value;
}

std::map<std::string, double> sharedUsed() { return gUsed; }

void startTest(const std::string& test) {
    gFailure = ChannelFailure::None;
    gUsed.clear();
    detail::beginTest(test);
}

std::string finishTest() {
    const std::string extra = detail::drain();
    if (extra.empty() && gFailure == ChannelFailure::None) gShared.insert(gPending.begin(), gPending.end());
    gPending.clear();
    if (extra.empty()) return "";
    gFailure = ChannelFailure::BadReport;
    return "the student's process sent " + std::to_string(extra.size()) +
           " bytes after its last answer, which nobody asked for";
}

ChannelFailure lastFailure() { return gFailure; }

void clearFailure() { gFailure = ChannelFailure::None; }

}  // namespace simlab::observe
