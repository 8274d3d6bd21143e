// A line a study program prints (study/run.cpp): with `simlab study ... --file`, a program built from a student's
// file, so every byte is the student's. A line is taken only well formed; what is taken is itself well formed.
#include "fuzz.h"
#include "internal.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using simlab::study::json;
    const json line = json::parse(simlab::fuzz::text(data, size), nullptr, false);
    if (line.is_discarded() || !line.is_object()) return 0;
    std::string why;
    const std::optional<json> taken = simlab::study::wellFormedLine(line, why);
    if (!taken) {
        simlab::fuzz::require(!why.empty(), "a line refused without a reason");
        return 0;
    }
    const std::optional<json> again = simlab::study::wellFormedLine(*taken, why);
    simlab::fuzz::require(again && *again == *taken, "a line taken as well formed is not: " + why);
    return 0;
}
