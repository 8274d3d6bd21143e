// JUnit XML for CI dashboards: one test suite per student, one test case per test.
#include <sstream>

#include "simlab/grading/report.h"
#include "simlab/common/text.h"
#include "simlab/writers/writers.h"

namespace simlab::engine {

std::string junitXml(const Assignment& assignment, const std::vector<StudentRecord>& records) {
    int tests = 0, failures = 0, errors = 0;
    std::ostringstream suites;
    for (const StudentRecord& r : records) {
        int f = 0, e = 0;
        std::ostringstream cases;
        for (const TestResult& t : r.tests) {
            cases << "    <testcase classname=\"" << xmlText(assignment.id + "." + r.id) << "\" name=\""
                  << xmlText(t.name) << "\" time=\"" << t.seconds << "\"";
            if (t.outcome == Outcome::Passed) {
                cases << "/>\n";
                continue;
            }
            const bool failed = t.outcome == Outcome::Failed;
            (failed ? f : e)++;
            const std::string tag = failed ? "failure" : "error";
            const std::string message = outcomeName(t.outcome) + (t.reason.empty() ? "" : ": " + t.reason);
            cases << ">\n      <" << tag << " type=\"" << xmlText(outcomeName(t.outcome)) << "\" message=\""
                  << xmlText(message) << "\">" << xmlText(message) << "</" << tag << ">\n    </testcase>\n";
        }
        tests += static_cast<int>(r.tests.size());
        failures += f;
        errors += e;
        suites << "  <testsuite name=\"" << xmlText(r.id) << "\" tests=\"" << r.tests.size() << "\" failures=\""
               << f << "\" errors=\"" << e << "\" time=\"" << r.seconds << "\">\n"
               << "    <properties><property name=\"score\" value=\"" << points(r.score) << "/"
               << points(r.maxScore) << "\"/><property name=\"status\" value=\"" << xmlText(statusName(r.status))
               << "\"/></properties>\n"
               << cases.str() << "  </testsuite>\n";
    }
    std::ostringstream out;
    out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"simlab " << xmlText(assignment.id)
        << "\" tests=\"" << tests << "\" failures=\"" << failures << "\" errors=\"" << errors << "\">\n"
        << suites.str() << "</testsuites>\n";
    return out.str();
}

}  // namespace simlab::engine
