// A class roster: the CSV an instructor gives simlab export canvas (Canvas's own gradebook export, say), read by
// writers/roster.cpp; and roster.csv beside a gradebook, which the late policy and the export read a column of
// (course/policy.cpp) and which an instructor may extend by hand.
#include "fuzz.h"
#include "simlab/common/errors.h"
#include "simlab/course/policy.h"
#include "simlab/writers/roster.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace simlab::engine;
    const std::string text = simlab::fuzz::text(data, size);
    try {
        readRoster(text, "roster.csv");
    } catch (const UsageError&) {
    }
    const std::string path = simlab::fuzz::scratch().fresh() + "/roster.csv";
    simlab::fuzz::write(path, text);
    try {
        rosterAliases(path);
        for (const auto& [id, when] : rosterTimes(path)) {
            simlab::fuzz::require(when.empty() || parseTime(when), "a roster time kept that is no time: " + when);
        }
    } catch (const UsageError&) {
    }
    return 0;
}
