// The trade question's data and its scoring against a work-precision front (simlab/trade_question.h), and the
// reading of a front (simlab/work_precision.h).
#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <string>

#include "simlab/common/files.h"
#include "simlab/trade_question.h"

namespace trade_question_test {

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

TEST_CASE("a student's variant is the FNV-1a hash of the seed and their id: the same everywhere, apart for others",
          "[trade]") {
    // FNV-1a's published values, which std::hash does not promise.
    CHECK(simlab::trade::fnv1a("") == 14695981039346656037ULL);
    CHECK(simlab::trade::fnv1a("a") == 0xaf63dc4c8601ec8cULL);
    const std::size_t ada = simlab::trade::variantIndex("fall 2026", "ada", 6);
    CHECK(ada == simlab::trade::variantIndex("fall 2026", "ada", 6));
    CHECK(ada == simlab::trade::fnv1a(std::string("fall 2026") + '\0' + "ada") % 6);
    // Ids spread over the pool: twelve students fall into more than one variant, and another seed deals anew.
    std::set<std::size_t> seen, reseeded;
    for (int i = 0; i < 12; ++i) {
        seen.insert(simlab::trade::variantIndex("fall 2026", "student" + std::to_string(i), 6));
        reseeded.insert(simlab::trade::variantIndex("spring 2027", "student" + std::to_string(i), 6));
    }
    CHECK(seen.size() > 2);
    CHECK(reseeded.size() > 2);
    CHECK(simlab::trade::variantIndex("ab", "c", 1000003) != simlab::trade::variantIndex("a", "bc", 1000003));
}

TEST_CASE("a question's pool of variants is read, and a student answers on theirs only where the course says so",
          "[trade]") {
    const simlab::trade::Question q = simlab::trade::parseQuestion(
        R"({"lab": "apple", "digits": 3, "scenes": [{"name": "question", "scene": {"dropHeight": 100}, "final_time": 2}],
            "variants": [{"name": "low", "scene": {"dropHeight": 50}, "final_time": 2, "front": [[3, 400]]},
                         {"name": "high", "scene": {"dropHeight": 200}, "final_time": 2, "front": [[3, 100]]}]})",
        "a test question");
    REQUIRE(q.variants.size() == 2);
    CHECK(q.variants[1].front.at(0).cost == 100);
    CHECK(simlab::trade::sceneFor(q, false, "seed", "ada").name == "question");
    CHECK(simlab::trade::sceneFor(q, true, "seed", "").name == "question");
    const std::size_t k = simlab::trade::variantIndex("seed", "ada", 2);
    CHECK(simlab::trade::sceneFor(q, true, "seed", "ada").name == q.variants[k].name);
    // A question without a pool gives everyone its scene.
    const simlab::trade::Question plain = simlab::trade::parseQuestion(
        R"({"lab": "apple", "digits": 3, "scenes": [{"name": "question", "scene": {}, "final_time": 2}]})", "plain");
    CHECK(plain.variants.empty());
    CHECK(simlab::trade::sceneFor(plain, true, "seed", "ada").name == "question");
}

TEST_CASE("the apple's and the projectile's pools of students' scenes each differ from the question and have a front",
          "[trade]") {
    for (const std::string lab : {"apple", "projectile"}) {
        const std::string path = SIMLAB_SOURCE_DIR "/assignments/" + lab + "/grading/trade-question.json";
        const simlab::trade::Question q = simlab::trade::parseQuestion(simlab::engine::readFile(path), path);
        INFO(lab);
        CHECK(q.variants.size() >= 4);
        CHECK(q.variants.size() <= 8);
        std::set<std::string> scenes = {q.scenes.at(0).scene.dump()};
        for (const simlab::trade::Scene& s : q.variants) {
            INFO(s.name);
            CHECK(scenes.insert(s.scene.dump()).second);
            REQUIRE_FALSE(s.front.empty());
            CHECK(s.front.back().digits >= q.digits);  // the question can be answered there
        }
    }
}

}  // namespace trade_question_test
