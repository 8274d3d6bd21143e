// What the writers of writers/ share: the class's figures per test and how numbers are printed.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "simlab/grading/record.h"

namespace simlab::engine::writers {

/// The median, min and max of some values (NaN when there are none).
struct Spread {
    int count = 0;
    double median = NAN, min = NAN, max = NAN;
};
Spread spreadOf(std::vector<double> values);

/// One rubric test across the class.
struct TestSummary {
    const RubricTest* test = nullptr;
    int graded = 0;  ///< students whose file was built and run
    int passed = 0;
    std::vector<double> values;  ///< what it measured, one per student that has a figure, in ascending order
    Spread figures;              ///< of values
    std::string unit;
};
/// Each test of the rubric, in its order, over the records whose file was built and run (a missing file, one that
/// did not compile and one refused before it ran are not counted as graded).
std::vector<TestSummary> summarize(const Rubric& rubric, const std::vector<StudentRecord>& records);

/// "0.833", "14.8", "1.97e-14" (three significant digits); empty for NaN.
std::string number(double v);

/// `bytes` in base64 (RFC 4648, the standard alphabet, padded with '='): for a data URI.
std::string base64(const std::string& bytes);
/// A data URI holding `bytes` of media type `mime` ("image/svg+xml"), base64-encoded: a picture inside a page or
/// a JSON document, with nothing beside it to fetch.
std::string dataUri(const std::string& mime, const std::string& bytes);
/// The media type a picture's file name says, by its extension: "image/svg+xml" for .svg, "image/png" for .png;
/// empty for anything else.
std::string pictureType(const std::string& name);

/// A JSON document as simlab writes its files: indented by 2, invalid UTF-8 replaced, a newline at the end.
std::string jsonText(const nlohmann::json& j);

}  // namespace simlab::engine::writers
