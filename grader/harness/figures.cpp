// How a grader test writes the numbers of its reasons (grading.h): a figure, a quantity at a time, a measured value
// beside the expected one.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "simlab/harness/grading.h"

namespace simlab::grading {

std::string show(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

std::string at(const std::string& quantity, double time) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", time);  // a sample's time as the run has it: 3.99, not 4
    return quantity + "(" + text + ")";
}

std::string compared(const std::string& what, double value, double expected, const std::string& unit) {
    const bool signs = std::signbit(value) != std::signbit(expected) && value != 0 && expected != 0;
    char shown[2][40];
    for (int digits = 3; digits <= 17; ++digits) {
        std::snprintf(shown[0], sizeof shown[0], signs ? "%+.*g" : "%.*g", digits, value);
        std::snprintf(shown[1], sizeof shown[1], signs ? "%+.*g" : "%.*g", digits, expected);
        if (std::strcmp(shown[0], shown[1]) != 0) break;
    }
    const std::string space = unit.empty() ? "" : " ";
    return what + " = " + shown[0] + space + unit + ", expected " + shown[1] + space + unit;
}

}  // namespace simlab::grading
