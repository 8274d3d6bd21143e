// How a grader test writes the numbers of its reasons (grading.h): a figure, a quantity at a time, a measured value
// beside the expected one.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

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
    return compared(what, std::vector<double>{value}, std::vector<double>{expected}, unit);
}

std::string compared(const std::string& what, const std::vector<double>& value, const std::vector<double>& expected,
                     const std::string& unit) {
    bool signs = false;
    for (std::size_t i = 0; i < value.size() && i < expected.size(); ++i) {
        signs = signs || (std::signbit(value[i]) != std::signbit(expected[i]) && value[i] != 0 && expected[i] != 0);
    }
    // Written with the fewest digits (3 at least) at which the two differ.
    auto write = [signs](const std::vector<double>& v, int digits) {
        std::string text = v.size() == 1 ? "" : "(";
        for (std::size_t i = 0; i < v.size(); ++i) {
            char number[40];
            std::snprintf(number, sizeof number, signs ? "%+.*g" : "%.*g", digits, v[i]);
            text += (i > 0 ? ", " : "") + std::string(number);
        }
        return text + (v.size() == 1 ? "" : ")");
    };
    std::string shown, shownExpected;
    for (int digits = 3; digits <= 17; ++digits) {
        shown = write(value, digits);
        shownExpected = write(expected, digits);
        if (shown != shownExpected) break;
    }
    const std::string space = unit.empty() ? "" : " ";
    return what + " = " + shown + space + unit + ", expected " + shownExpected + space + unit;
}

}  // namespace simlab::grading
