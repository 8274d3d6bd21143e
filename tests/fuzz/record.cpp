// A student's record.json, read back when a class is resumed (course/batch.cpp) and by simlab export: simlab wrote
// it, but a grades folder is anyone's to damage (a disk filled halfway, an editor, another version). A damaged
// record is regraded, never half-read; a record that reads is written again as simlab writes it and reads back the
// same.
#include "fuzz.h"
#include "simlab/writers/writers.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace simlab::engine;
    const std::optional<StudentRecord> record = readRecordJson(simlab::fuzz::text(data, size));
    if (!record) return 0;
    const std::string written = recordJson(*record);
    const std::optional<StudentRecord> again = readRecordJson(written);
    simlab::fuzz::require(again.has_value(), "a record simlab wrote does not read back: " + written.substr(0, 2000));
    simlab::fuzz::require(recordJson(*again) == written, "a record simlab wrote reads back otherwise");
    return 0;
}
