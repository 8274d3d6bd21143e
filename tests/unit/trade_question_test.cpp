// The trade question's data and its scoring against a work-precision front (simlab/trade_question.h), and the
// reading of a front (simlab/work_precision.h).
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "simlab/trade_question.h"

using simlab::work_precision::Point;

namespace {

// A method whose work grows tenfold per digit past 2 (explicit Euler's, say), with a dearer point that keeps no
// more digits than a cheaper one and so is off the front.
std::vector<Point> eulerLike() {
    return simlab::work_precision::frontOf({{2, 100, 0}, {3, 1000, 0}, {4, 10000, 0}, {5, 100000, 0}, {3.5, 50000, 0}});
}

}  // namespace

TEST_CASE("a front keeps, in order of cost, each point that keeps more digits than every cheaper one", "[trade]") {
    const std::vector<Point> front = eulerLike();
    REQUIRE(front.size() == 4);
    CHECK(front.front().cost == 100);
    CHECK(front.back().digits == 5);
}

TEST_CASE("a front is read log-linearly between its points, and at its first point below it", "[trade]") {
    const std::vector<Point> front = eulerLike();
    // Halfway from 3 to 4 digits: the geometric mean of 1000 and 10000.
    CHECK(simlab::work_precision::costAt(front, 3.5)->cost == Approx(std::sqrt(1e7)).epsilon(1e-12));
    CHECK(simlab::work_precision::costAt(front, 1)->cost == 100);
    CHECK_FALSE(simlab::work_precision::costAt(front, 6).has_value());
}

TEST_CASE("an answer is scored against the front at the digits it keeps, counted up to `beyond` past those asked",
          "[trade]") {
    const std::vector<Point> front = eulerLike();
    // On the front at 4 digits: full credit.
    CHECK(simlab::trade::score(front, 4, 4.0, 10000, 0, 2, 10).credit == 1);
    // Twice the front's cost: still full credit; ten times: none; in between, by the logarithm of the ratio.
    CHECK(simlab::trade::score(front, 4, 4.0, 20000, 0, 2, 10).credit == 1);
    CHECK(simlab::trade::score(front, 4, 4.0, 100000, 0, 2, 10).credit == 0);
    const double between = simlab::trade::score(front, 4, 4.0, 44721.36, 0, 2, 10).credit;  // sqrt(20) x
    CHECK(between == Approx(0.5).epsilon(1e-6));
    // A step ten times smaller keeps a digit more at ten times the cost: with beyond = 0 that digit is not asked for
    // (ratio 10, nothing); with beyond = 1 it is on the front (full credit).
    CHECK(simlab::trade::score(front, 4, 5.0, 100000, 0, 2, 10).ratio == Approx(10));
    CHECK(simlab::trade::score(front, 4, 5.0, 100000, 1, 2, 10).credit == 1);
    // Past the front's last point, its dearest cost is the measure.
    CHECK(simlab::trade::score(front, 4, 7.0, 100000, 3, 2, 10).frontCost == 100000);
}

TEST_CASE("the most an answer may cost to earn anything is none_past times the front at the digits counted",
          "[trade]") {
    CHECK(simlab::trade::cap(eulerLike(), 4, 0, 10) == Approx(100000));
    CHECK(simlab::trade::cap(eulerLike(), 3, 1, 10) == Approx(100000));
}

TEST_CASE("a start moves the scene's number by units in its last place, and nothing else", "[trade]") {
    const nlohmann::json scene = {{"dropHeight", 40.0}, {"gravity", 9.8}, {"w", {0.1, 5.0, 0.1}}};
    CHECK(simlab::trade::nudged(scene, "/dropHeight", 0) == scene);
    const nlohmann::json two = simlab::trade::nudged(scene, "/dropHeight", 2);
    CHECK(two["dropHeight"].get<double>() == std::nextafter(std::nextafter(40.0, 100.0), 100.0));
    CHECK(two["gravity"] == scene["gravity"]);
    CHECK(simlab::trade::nudged(scene, "/w/1", 1)["w"][1].get<double>() == std::nextafter(5.0, 10.0));
}

TEST_CASE("a question's data file is read whole, or refused in one line naming it", "[trade]") {
    const simlab::trade::Question q = simlab::trade::parseQuestion(
        R"({"lab": "apple", "digits": 4, "integrators": ["ExplicitEuler"], "fixed_step_only": true,
            "nudge": "/dropHeight", "starts": 3,
            "scenes": [{"name": "question", "scene": {"dropHeight": 40}, "final_time": 2.5,
                        "front": [[3.1, 1002], [4.1, 10002]]}]})",
        "apple's question");
    CHECK(q.digits == 4);
    CHECK(q.starts == 3);
    REQUIRE(q.scenes.size() == 1);
    CHECK(q.scenes[0].front.size() == 2);
    CHECK(simlab::trade::allows(q, "ExplicitEuler", true));
    CHECK_FALSE(simlab::trade::allows(q, "ExplicitEuler", false));
    CHECK_FALSE(simlab::trade::allows(q, "Verlet", true));
    CHECK_THROWS_WITH(simlab::trade::parseQuestion(R"({"lab": "apple"})", "apple's question"),
                      Catch::Contains("apple's question is damaged"));
}
