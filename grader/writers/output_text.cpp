// output.txt: what each test's process printed, for instructors.
#include "simlab/common/text.h"
#include "simlab/writers/writers.h"

namespace simlab::engine {

std::string testOutputText(const GradeReport& report) {
    std::string output;
    for (const TestResult& t : report.tests) {
        output += "=== " + t.name + " (" + outcomeName(t.outcome) + ")\n" + printable(t.output, true) + "\n";
    }
    if (!report.graderOutput.empty()) {
        output += "=== the grader's account of the tests\n" + printable(report.graderOutput, true) + "\n";
    }
    return output;
}

}  // namespace simlab::engine
