// A course's rules for late work, course.toml, and the extensions file it names (course/policy.cpp), both an
// instructor's to edit; then the lateness of records handed in at several times. An input is course.toml, then a
// line "%%", then the extensions file (which course.toml names as extensions = "extensions.csv"); each time with and
// without a platform's late flag.
#include <cmath>
#include <optional>
#include <utility>

#include "fuzz.h"
#include "simlab/common/errors.h"
#include "simlab/course/policy.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace simlab::engine;
    const std::vector<std::string> input = simlab::fuzz::parts(simlab::fuzz::text(data, size), "\n%%\n", 2);
    const std::string& folder = simlab::fuzz::scratch().fresh();
    simlab::fuzz::write(folder + "/course.toml", input[0]);
    if (input.size() > 1) simlab::fuzz::write(folder + "/extensions.csv", input[1]);
    StudentIds ids;
    for (const auto& [alias, id] : {std::pair<const char*, const char*>{"ada", "ada"},
                                    {"ada@example.edu", "ada"},
                                    {"9001", "ada"},
                                    {"bob", "bob"}}) {
        ids.add(alias, id);
    }
    LatePolicy policy;
    try {
        policy = loadLatePolicy(folder + "/course.toml", "apple", ids);
    } catch (const UsageError&) {
        return 0;
    }
    for (const char* id : {"ada", "bob", "cy"}) {
        for (const char* when : {"", "2026-10-02T23:59:00Z", "2026-10-05T12:00:00-07:00", "1970-01-01T00:00:00Z",
                                 "9999-12-31T23:59:59Z"}) {
            for (const std::optional<bool> flaggedLate :
                 {std::optional<bool>(), std::optional<bool>(true), std::optional<bool>(false)}) {
                StudentRecord r;
                r.id = id;
                r.status = SubmissionStatus::Graded;
                r.submitted = when;
                applyLatePolicy(r, policy, handInOf(when, "Canvas's file time", flaggedLate));
                simlab::fuzz::require(r.late.percent >= 0 && r.late.percent <= 100,
                                      "a lateness taking " + std::to_string(r.late.percent) + " % of the score");
                simlab::fuzz::require(!std::isnan(r.late.hours), "a lateness of NaN hours");
            }
        }
    }
    return 0;
}
