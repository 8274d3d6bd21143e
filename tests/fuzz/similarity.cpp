// simlab similarity's readers (course/similarity.cpp): a student's file with the starter's lines removed, and the
// runs sim_c++ prints of the files it compared (by numbers and lines: a tool's output about the students' bytes,
// whose numbers sim_c++ keeps to the files' lengths; a number past an int is the one-line error simlab's command
// prints). An input is sim_c++'s output, a line "%%", a student's file, a line "%%", the starter.
#include <stdexcept>

#include "fuzz.h"
#include "simlab/course/similarity.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace simlab::engine;
    const std::vector<std::string> input = simlab::fuzz::parts(simlab::fuzz::text(data, size), "\n%%\n", 3);
    try {
        for (const auto& [pair, runs] : parseSimRuns(input[0])) {
            simlab::fuzz::require(pair.first < pair.second, "a pair of files not in order");
        }
    } catch (const std::out_of_range&) {
    }
    if (input.size() > 1) withoutStarter(input[1], input.size() > 2 ? input[2] : "");
    return 0;
}
