// Accuracy digits: -log10 of the relative error, clamped to what a double can hold.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "simlab/digits.h"

namespace digits_test {

using simlab::accuracyDigits;
using simlab::kMaxDigits;

TEST_CASE("digits count the leading figures that agree", "[digits]") {
    // y(4) = -68.4: an error of 6.84e-9 is a relative error of 1e-10, ten digits.
    CHECK(accuracyDigits(-68.4 + 6.84e-9, -68.4) == Approx(10.0).margin(1e-6));
    CHECK(accuracyDigits(1.001, 1.0) == Approx(3.0).margin(1e-6));
    // The sign of the error does not matter.
    CHECK(accuracyDigits(0.999, 1.0) == Approx(accuracyDigits(1.001, 1.0)).margin(1e-9));
}

TEST_CASE("digits are capped at double precision", "[digits]") {
    CHECK(kMaxDigits == Approx(15.65).margin(0.01));
    CHECK(accuracyDigits(-68.4, -68.4) == kMaxDigits);
    // One unit in the last place of 1.0 is already at the cap.
    CHECK(accuracyDigits(std::nextafter(1.0, 2.0), 1.0) == Approx(kMaxDigits).margin(1e-9));
}

TEST_CASE("digits are never negative and NaN scores none", "[digits]") {
    CHECK(accuracyDigits(88.4, -68.4) == 0.0);  // gravity with the wrong sign
    CHECK_FALSE(std::signbit(accuracyDigits(2.0, 1.0)));  // an error as large as the value: 0, not -0
    CHECK(accuracyDigits(std::nan(""), -68.4) == 0.0);
    CHECK(accuracyDigits(std::numeric_limits<double>::infinity(), 1.0) == 0.0);
}

TEST_CASE("an exact value of zero needs a scale", "[digits]") {
    CHECK(accuracyDigits(1e-12, 0.0) == 0.0);
    // Relative to a speed of 39.2 m/s, 3.92e-9 m/s off is ten digits.
    CHECK(accuracyDigits(3.92e-9, 0.0, 39.2) == Approx(10.0).margin(1e-6));
    CHECK(accuracyDigits(0.0, 0.0, 39.2) == kMaxDigits);
}

}  // namespace digits_test
