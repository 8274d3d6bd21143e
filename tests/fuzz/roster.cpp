// A class roster: the CSV an instructor gives simlab export canvas (Canvas's own gradebook export, say), read by
// writers/roster.cpp; and roster.csv beside a gradebook, which the late policy and the export read a column of
// (course/policy.cpp: its ids and hand-in times) and which an instructor may extend by hand; and the hand-in times an
// instructor names (--submitted).
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
        const StudentIds ids = rosterIds(path);
        for (const std::string& id : ids.students()) {
            simlab::fuzz::require(ids.find(id, "roster.csv") == id, "a simlab id that names another student: " + id);
        }
        for (const auto& [id, handIn] : rosterHandIns(path)) {
            simlab::fuzz::require(handIn.time.empty() || parseTime(handIn.time),
                                  "a roster time kept that is no time: " + handIn.time);
        }
        // The same bytes as the times an instructor names (--submitted: a CSV, or Canvas's submissions as JSON).
        for (const auto& [id, handIn] : readSubmittedTimes(path, ids)) {
            simlab::fuzz::require(handIn.time.empty() || parseTime(handIn.time),
                                  "a hand-in time kept that is no time: " + handIn.time);
        }
    } catch (const UsageError&) {
    }
    return 0;
}
