// The spinning book: the tests only an instructor's grading runs. Other spins and other books, so a file that
// types in the lab's numbers passes the visible tests and fails these; and the answers file against the key, which
// is why these tests are not in what students receive.
#include "book_testing.h"

namespace book::testing {

namespace {
// Faster spins and other books turn further in 4 s: these runs ask for accuracy 1e-12.
WorstDigits worstDigits(const std::vector<Scene>& scenes) {
    WorstDigits worst;
    for (const Scene& scene : scenes) {
        worst.add(finalDigits(scene, simulate(scene, settingsFor(4.0, 0.01, 1e-12))),
                  "(w0 = (" + components(scene.w_B0) + ") rad/s on a " + grading::show(scene.mass) + " kg book of (" +
                      components(scene.dimensions) + ") m)");
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
    CHECK(atLeast(worstDigits(scenes), grading::param("floor"), grading::param("target"), "digits at the worst spin"));
}

TEST_CASE("hidden: other books and masses follow the exact solution", "[book][hidden]") {
    // A paperback wider than tall, and a heavy atlas: their axes rank differently from the lab's book.
    std::vector<Scene> scenes;
    for (const Scene& b : {book(0.25, 0.18, 0.11, 0.025), book(1.9, 0.35, 0.26, 0.04)}) {
        for (const std::string& axis : axisNames()) scenes.push_back(spun(b, axis));
    }
    CHECK(atLeast(worstDigits(scenes), grading::param("floor"), grading::param("target"), "digits at the worst spin"));
}

TEST_CASE("the answers say which quantities are conserved", "[book][answers]") {
    // The feedback counts right answers and names unreadable ones, never which answers are wrong.
    const Answers answers = readAnswers();
    const std::map<std::string, std::string> truth = {{"wx", "no"}, {"wy", "no"},   {"wz", "no"},
                                                      {"K", "yes"}, {"Hx", "no"},   {"Hy", "no"},
                                                      {"Hz", "no"}, {"Hmag", "yes"}, {"HG", "yes"}};
    int right = 0;
    std::vector<std::string> unreadable;
    for (const auto& [quantity, answer] : truth) {
        const auto given = answers.conserved.find(quantity);
        if (given == answers.conserved.end() || (given->second != "yes" && given->second != "no")) {
            unreadable.push_back(quantity);
        } else if (given->second == answer) {
            ++right;
        }
    }
    grading::measured(right, "right", countLine(right, truth.size(), unreadable, "yes or no"));
    grading::partialCredit(double(right) / truth.size());
    CHECK(right == static_cast<int>(truth.size()));
}

TEST_CASE("the answers say which spins are stable", "[book][answers]") {
    // What the whole motion does, as the handout asks: spin about the minimum and maximum axes is stable (the wobble
    // stays as small as it started, for all time: K and |H| are conserved), about the intermediate axis unstable.
    // "Neutrally stable" is where a linear analysis stops, not an answer to the question (stabilityWords). As
    // above, wrong answers are counted, not named.
    const Answers answers = readAnswers();
    const std::map<std::string, std::string> truth = {{"minimum", "stable"}, {"intermediate", "unstable"}, {"maximum", "stable"}};
    int right = 0;
    std::vector<std::string> unreadable;
    for (const auto& [axis, answer] : truth) {
        const auto given = answers.stability.find(axis);
        const std::string value = given == answers.stability.end() ? "" : given->second;
        if (value != "stable" && value != "unstable") unreadable.push_back(axis);
        else if (value == answer) ++right;
    }
    grading::measured(right, "right", countLine(right, truth.size(), unreadable, stabilityWords()));
    grading::partialCredit(right / 3.0);
    CHECK(right == 3);
}

TEST_CASE("hidden: the trade's answer holds on other tumbling books", "[book][hidden][trade]") {
    // The same answer on two other books spun about their intermediate axes: a setting with a margin keeps its
    // digits there; one that just scrapes 8 on the question's book, or that happens to land well there, does not.
    static const simlab::trade::Question variants = simlab::trade::parseQuestion(
#include "trade_hidden.inc"
        , "the book's trade-hidden.json");
    gradeTradeVariants<Sample, Scene>(variants, tradeDigits);
}

}  // namespace book::testing
