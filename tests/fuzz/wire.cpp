// A line on a channel of the student's process or the judge, read as the engine reads it (protocol/bounded_json.h:
// nesting counted before anything recursive touches it), and the judge's verdict record on its report channel
// (protocol/verdict.h). A verdict that reads is also written again as the judge writes it and read back: the same.
#include "fuzz.h"
#include "simlab/protocol/bounded_json.h"
#include "simlab/protocol/verdict.h"

namespace {

using namespace simlab;

bool same(const wire::Verdict& a, const wire::Verdict& b) {
    const auto sameFigure = [](const std::optional<wire::Figure>& x, const std::optional<wire::Figure>& y) {
        return x.has_value() == y.has_value() && (!x || (x->value == y->value && x->unit == y->unit));
    };
    bool board = a.leaderboard.size() == b.leaderboard.size();
    for (std::size_t i = 0; board && i < a.leaderboard.size(); ++i) {
        board = a.leaderboard[i].name == b.leaderboard[i].name && a.leaderboard[i].value == b.leaderboard[i].value &&
                a.leaderboard[i].order == b.leaderboard[i].order;
    }
    bool files = a.attachments.size() == b.attachments.size();
    for (std::size_t i = 0; files && i < a.attachments.size(); ++i) {
        files = a.attachments[i].name == b.attachments[i].name && a.attachments[i].text == b.attachments[i].text;
    }
    return a.test == b.test && a.passed == b.passed && a.credit == b.credit && a.reason == b.reason &&
           a.feedback == b.feedback && files && sameFigure(a.figure, b.figure) && board && a.channel == b.channel &&
           a.seconds == b.seconds && a.shared == b.shared;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string line = fuzz::text(data, size);
    const nlohmann::json record = wire::parseBounded(line);
    if (record.is_discarded()) return 0;
    fuzz::require(wire::nestingDepth(line) <= wire::kMaxNesting, "a line nested past the bound was parsed");
    wire::firstNull(record);
    if (!record.is_object()) return 0;
    const auto named = record.find("test");
    wire::isEndRecord(record, named != record.end() && named->is_string() ? named->get<std::string>() : "");
    wire::Verdict verdict;
    try {
        verdict = wire::readVerdict(record);
    } catch (const wire::WireError&) {
        return 0;
    }
    const std::string written = wire::endRecord(verdict).dump();
    fuzz::require(wire::isEndRecord(wire::parseBounded(written), verdict.test), "a written verdict is not its test's");
    fuzz::require(same(verdict, wire::readVerdict(wire::parseBounded(written))), "a written verdict reads back otherwise");
    return 0;
}
