// Command-line checks shared by the lab programs and simlab, with one-line messages.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <string>

namespace simlab {

/// For options that must be positive numbers: "--dt: must be a positive number, got -1".
inline CLI::Validator positive() {
    return CLI::Validator(
        [](std::string& text) {
            double value = 0;
            if (!CLI::detail::lexical_cast(text, value) || !(value > 0) || !std::isfinite(value)) {
                return "must be a positive number, got " + text;
            }
            return std::string();
        },
        "POSITIVE");
}

/// For options that may take any sign but must be numbers: "--omega: must be a finite number, got nan".
inline CLI::Validator finite() {
    return CLI::Validator(
        [](std::string& text) {
            double value = 0;
            if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value)) {
                return "must be a finite number, got " + text;
            }
            return std::string();
        },
        "FINITE");
}

/// For options with a range: "--accuracy: must be between 1e-15 and 0.5, got 1e-20", the limits as written
/// (CLI::Range prints them with six decimals, so 1e-15 shows as 0.000000).
inline CLI::Validator between(double low, double high) {
    auto shown = [](double value) {
        char text[32];
        std::snprintf(text, sizeof text, "%g", value);
        return std::string(text);
    };
    const std::string range = "between " + shown(low) + " and " + shown(high);
    return CLI::Validator(
        [low, high, range](std::string& text) {
            double value = 0;
            if (!CLI::detail::lexical_cast(text, value) || !(value >= low && value <= high)) {
                return "must be " + range + ", got " + text;
            }
            return std::string();
        },
        range);
}

}  // namespace simlab
