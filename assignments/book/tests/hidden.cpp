// The spinning book: the tests only an instructor's grading runs. Other spins and other books, so a file that
// types in the lab's numbers passes the visible tests and fails these.
#include "book_testing.h"

namespace book::testing {

namespace {
// Faster spins and other books turn further in 4 s: these runs ask for accuracy 1e-12.
double worstDigits(const std::vector<Scene>& scenes) {
    double worst = simlab::kMaxDigits;
    for (const Scene& scene : scenes) {
        const double digits = finalDigits(scene, simulate(scene, settingsFor(4.0, 0.01, 1e-12)));
        INFO("w0 = (" << scene.w_B0 << ") rad/s on a " << scene.mass << " kg book of (" << scene.dimensions
                      << ") m: " << digits << " digits");
        worst = std::min(worst, digits);
    }
    return worst;
}

Scene book(double mass, double height, double width, double thickness) {
    Scene s;
    s.mass = mass;
    s.dimensions = SimTK::Vec3(height, width, thickness);
    return s;
}
}  // namespace

TEST_CASE("hidden: other spin rates follow the exact solution", "[book][hidden]") {
    std::vector<Scene> scenes;
    for (const double rate : {2.0, 15.0}) {
        for (const std::string& axis : axisNames()) scenes.push_back(spun(Scene{}, axis, rate));
    }
    CHECK(grading::atLeast(worstDigits(scenes), grading::param("floor"), grading::param("target"),
                           "digits at the worst spin"));
}

TEST_CASE("hidden: other books and masses follow the exact solution", "[book][hidden]") {
    // A paperback wider than tall, and a heavy atlas: their axes rank differently from the lab's book.
    std::vector<Scene> scenes;
    for (const Scene& b : {book(0.25, 0.18, 0.11, 0.025), book(1.9, 0.35, 0.26, 0.04)}) {
        for (const std::string& axis : axisNames()) scenes.push_back(spun(b, axis));
    }
    CHECK(grading::atLeast(worstDigits(scenes), grading::param("floor"), grading::param("target"),
                           "digits at the worst spin"));
}

}  // namespace book::testing
