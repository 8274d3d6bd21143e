#include "common.h"

#include <algorithm>
#include <cstdio>

namespace simlab::engine::writers {

Spread spreadOf(std::vector<double> values) {
    Spread s;
    s.count = static_cast<int>(values.size());
    if (values.empty()) return s;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    s.median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
    s.min = values.front();
    s.max = values.back();
    return s;
}

std::vector<TestSummary> summarize(const Rubric& rubric, const std::vector<StudentRecord>& records) {
    std::vector<TestSummary> out;
    for (const RubricTest& test : rubric.tests) {
        TestSummary s;
        s.test = &test;
        for (const StudentRecord& r : records) {
            for (const TestResult& t : r.tests) {
                // Built and run: not a missing file, nor one that did not compile or was refused before it ran.
                if (t.name != test.name || t.outcome == Outcome::MissingFile || t.outcome == Outcome::DidNotCompile ||
                    t.outcome == Outcome::Refused) {
                    continue;
                }
                ++s.graded;
                s.passed += t.outcome == Outcome::Passed;
                if (t.figure) {
                    s.values.push_back(*t.figure);
                    s.unit = t.unit;
                }
            }
        }
        std::sort(s.values.begin(), s.values.end());
        s.figures = spreadOf(s.values);
        out.push_back(s);
    }
    return out;
}

std::string number(double v) {
    if (std::isnan(v)) return "";
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", v);
    return text;
}

std::string jsonText(const nlohmann::json& j) {
    return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::string base64(const std::string& bytes) {
    static const char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
        unsigned v = 0;
        for (std::size_t k = 0; k < 3; ++k) v = v << 8 | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
        for (std::size_t k = 0; k < 4; ++k) out += k <= n ? alphabet[v >> (18 - 6 * k) & 63] : '=';
    }
    return out;
}

std::string dataUri(const std::string& mime, const std::string& bytes) {
    return "data:" + mime + ";base64," + base64(bytes);
}

std::string pictureType(const std::string& name) {
    auto endsWith = [&](const std::string& tail) {
        return name.size() >= tail.size() && name.compare(name.size() - tail.size(), tail.size(), tail) == 0;
    };
    if (endsWith(".svg")) return "image/svg+xml";
    if (endsWith(".png")) return "image/png";
    return "";
}

}  // namespace simlab::engine::writers
