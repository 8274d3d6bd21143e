// Command-line checks shared by the lab programs and simlab, with one-line messages.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
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

}  // namespace simlab
