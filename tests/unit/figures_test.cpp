// The numbers of a grader test's reasons: a measured value beside the expected one, and the worst point of many.
#include <catch2/catch.hpp>
#include <cmath>

#include "simlab/digits.h"
#include "simlab/harness/grading.h"
#include "simlab/harness/testing.h"

namespace figures_test {

using simlab::accuracyDigits;
using simlab::grading::at;
using simlab::grading::compared;
using simlab::testing::WorstDigits;
using simlab::testing::WorstDrift;

TEST_CASE("a comparison signs both values where their signs differ", "[figures]") {
    // Gravity with the wrong sign: the apple rises to 10 + 4.9 * 16 = 88.4 m where it should fall to -68.4 m.
    CHECK(compared("y(4)", 88.4, -68.4, "m") == "y(4) = +88.4 m, expected -68.4 m");
    CHECK(compared("y(5.2)", 266.0, 0.8316, "m") == "y(5.2) = 266 m, expected 0.832 m");
    CHECK(compared("t*", 0.0, 5.2324, "s") == "t* = 0 s, expected 5.23 s");  // zero has no sign to differ
}

TEST_CASE("a comparison shows as many digits as tell the two values apart", "[figures]") {
    // 8 digits of y(4): 8 figures show the difference.
    CHECK(compared("y(4)", -68.4 + 6.84e-7, -68.4, "m") == "y(4) = -68.399999 m, expected -68.4 m");
    CHECK(compared("x*", 1.0, 1.0, "m") == "x* = 1 m, expected 1 m");  // equal to the last bit: 17 digits
    CHECK(compared("n", 3.0, 4.0, "") == "n = 3, expected 4");
}

TEST_CASE("a quantity at a time names the time as the run has it", "[figures]") {
    CHECK(at("y", 4) == "y(4)");
    CHECK(at("E", 3.99) == "E(3.99)");
    CHECK(at("t", 0.0792) == "t(0.0792)");
}

TEST_CASE("the worst digits keep the comparison that had them", "[figures]") {
    WorstDigits worst;
    CHECK(worst.figure() == simlab::kMaxDigits);
    CHECK(worst.point().empty());
    CHECK(worst.add(accuracyDigits(-68.0, -68.4), at("y", 4), -68.0, -68.4, "m"));
    CHECK_FALSE(worst.add(accuracyDigits(-68.3, -68.4), at("y", 4), -68.3, -68.4, "m"));  // more digits: not worse
    CHECK(worst.point() == "y(4) = -68 m, expected -68.4 m");
    CHECK(worst.figure() == Approx(accuracyDigits(-68.0, -68.4)));
    // A scene's worst joins another's with its context, where it is worse.
    WorstDigits scene;
    scene.add(0.0, at("y", 0.5), 3.72, 1.27, "m");
    worst.add(scene, "(dropped from 2.5 m)");
    CHECK(worst.figure() == 0.0);
    CHECK(worst.point() == "y(0.5) = 3.72 m, expected 1.27 m (dropped from 2.5 m)");
    // Nothing measured: the figure counts, with nothing to compare.
    WorstDigits none;
    none.add(0.0);
    CHECK(none.figure() == 0.0);
    CHECK(none.point().empty());
}

TEST_CASE("the largest drift keeps its comparison and NaN is the worst drift", "[figures]") {
    WorstDrift drift;
    CHECK(drift.figure() == 0.0);
    drift.add(1e-14, at("E", 1), 13.9, 13.9, "J");
    drift.add(2.0, at("E", 4), -13.9, 13.9, "J");
    drift.add(1e-10, at("E", 2), 13.9, 13.9, "J");
    CHECK(drift.figure() == 2.0);
    CHECK(drift.point() == "E(4) = -13.9 J, expected +13.9 J");
    drift.add(std::nan(""), at("E", 3), std::nan(""), 13.9, "J");
    CHECK(std::isinf(drift.figure()));
    CHECK(drift.point().rfind("E(3) = ", 0) == 0);
}

}  // namespace figures_test
