// Gradescope's submission_metadata.json, beside the submission simlab autograde grades (course/metadata.cpp): the
// student it names, and the times and due dates it gives, with the lateness they make.
#include <cmath>

#include "fuzz.h"
#include "simlab/common/errors.h"
#include "simlab/course/metadata.h"
#include "simlab/grading/grade.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace simlab::engine;
    nlohmann::json metadata;
    try {
        metadata = readSubmissionMetadata(simlab::fuzz::text(data, size), "submission_metadata.json");
    } catch (const UsageError&) {
        return 0;
    }
    try {
        requireStudentId(studentOfMetadata(metadata));
    } catch (const UsageError&) {
    }
    const LatePolicy policy = metadataLatePolicy(LatePolicy{}, metadata);
    StudentRecord r;
    r.status = SubmissionStatus::Graded;
    if (const std::optional<std::time_t> at = metadataTime(metadata, {"created_at"})) r.submitted = utcText(*at);
    applyLatePolicy(r, policy);
    simlab::fuzz::require(r.late.percent >= 0 && r.late.percent <= 100, "a lateness out of 0 to 100 %");
    simlab::fuzz::require(!std::isnan(r.late.hours), "a lateness of NaN hours");
    return 0;
}
