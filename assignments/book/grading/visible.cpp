// The spinning book: the tests a student's self-check runs. Points and thresholds are in ../rubric.toml.
#include "book_testing.h"

namespace book::testing {

TEST_CASE("the principal moments of inertia come from the book's dimensions", "[book][inertia]") {
    // A uniform 0.4 kg book, 20 x 30 x 5 cm: Ixx = m (Ly^2 + Lz^2)/12 = 3.083e-3, Iyy = 1.417e-3, Izz = 4.333e-3.
    const Scene scene;
    const MassObservation props = massProperties(scene);
    const SimTK::Vec3 moments = props.moments, products = props.products;
    const SimTK::Vec3 expected = exact::principalMoments(scene);
    if (std::abs(moments[0] / expected[0] - 4) < 1e-6) {
        grading::feedback("every moment is 4 times too large: UnitInertia::brick takes half the edge lengths");
    }
    INFO("the book's inertia about its center is (" << moments << ") kg m^2 with products (" << products
                                                    << "), mass " << props.mass << " kg, center " << props.center
                                                    << "; expected (" << expected << ") kg m^2 about its x, y, z");
    CHECK(props.mass == Approx(scene.mass).epsilon(1e-12));
    CHECK(props.center.norm() < 1e-12);
    for (int i = 0; i < 3; ++i) {
        CHECK(moments[i] == Approx(expected[i]).epsilon(1e-9));
        CHECK(products[i] == Approx(0.0).margin(1e-15));
    }
}

TEST_CASE("the book starts with the spin asked for", "[book][initial]") {
    const Scene scene = spun(Scene{}, "intermediate");
    const Run run = simulate(scene);
    requireSamples(run);
    const Sample& first = run.samples.front();
    INFO("w at t = " << first.time << " s is (" << components(first.w_B) << ") rad/s; expected ("
                        << components(scene.w_B0) << ")");
    CHECK(first.time == 0.0);
    CHECK((first.w_B - scene.w_B0).norm() < 1e-12);
}

TEST_CASE("samples run from t = 0 to the final time every dt", "[book][sampling]") {
    const simlab::RunSettings settings = settingsFor(/*finalTime=*/2.0, /*dt=*/0.25);
    checkSampleTimes(simulate(Scene{}, settings), settings);
}

TEST_CASE("the integrator is the one asked for at the accuracy asked for", "[book][integrator]") {
    checkIntegratorRequests<Sample>(Scene{}, settingsFor(1.0, 0.05));
}

TEST_CASE("omega at 4 s matches the exact solution for all three spins", "[book][accuracy]") {
    // The exact solution is in Jacobi elliptic functions (exact.h).
    WorstDigits worst;
    for (const std::string& axis : axisNames()) {
        const Scene scene = spun(Scene{}, axis);
        worst.add(finalDigits(scene, simulate(scene)), "(spun about the " + axis + " axis)");
    }
    CHECK(atLeast(worst, grading::param("floor"), grading::param("target"), "digits at the worst spin"));
}

TEST_CASE("K and |H| stay constant and so does H in Ground", "[book][conservation]") {
    // No torque: kinetic energy and the angular momentum vector (seen from Ground) do not change.
    const double allowed = grading::param("tolerance") * defaultRunSettings().accuracy;
    struct Conserved {
        const char *quantity, *name, *unit;
        int components;
    };
    WorstDrift worst;
    for (const std::string& axis : axisNames()) {
        const Run run = simulateWhole(spun(Scene{}, axis));
        for (const auto& [quantity, read] : quantities()) {
            for (const Conserved& c : {Conserved{"K", "K", "J", 1}, Conserved{"Hmag", "|H|", "kg m^2/s", 1},
                                       Conserved{"HG", "H_G", "kg m^2/s", 3}}) {
                if (quantity == c.quantity) {
                    worst.add(driftOf(run, read, c.name, c.unit, c.components), "(spun about the " + axis + " axis)");
                }
            }
        }
    }
    CHECK(atMost(worst, allowed, "largest relative change"));
}

TEST_CASE("the body components of omega and H change", "[book][conservation]") {
    // Seen from the turning book, H's components (and w's) do change: checked on the student's own output.
    std::vector<Run> runs;
    for (const std::string& axis : axisNames()) runs.push_back(simulateWhole(spun(Scene{}, axis)));
    std::vector<std::string> constant;
    for (const auto& [quantity, read] : quantities()) {
        if (quantity == "K" || quantity == "Hmag" || quantity == "HG") continue;  // the conserved ones
        double largest = 0;
        for (const Run& run : runs) largest = std::max(largest, relativeChange(run, read));
        if (!(largest > 1e-3)) constant.push_back(quantity);
    }
    std::string list;
    for (const std::string& c : constant) list += (list.empty() ? "" : ", ") + c;
    INFO("in the simulation's own output these body components stay constant: " << list
                                                                              << "; are they expressed in the book?");
    CHECK(constant.empty());
}

TEST_CASE("the answers agree with the student's own simulation", "[book][answers]") {
    // What the student's own numbers show: a quantity that changes by less than a millionth is constant, by more
    // than a thousandth is not; a spin that reverses is unstable, one whose wobble stays under 1 rad/s is not.
    // Only the number of disagreements is reported: naming them would read the key off the student's run.
    const Answers answers = readAnswers();
    std::map<std::string, Run> runs;
    for (const std::string& axis : axisNames()) runs.emplace(axis, simulateWhole(spun(Scene{}, axis)));
    int compared = 0, disagree = 0, unanswered = 0;  // unanswered: still "?" in the file, or not there
    for (const auto& [quantity, read] : quantities()) {
        double largest = 0;
        for (const auto& [axis, run] : runs) largest = std::max(largest, relativeChange(run, read));
        const std::string shown = largest < 1e-6 ? "yes" : largest > 1e-3 ? "no" : "";
        if (shown.empty()) continue;
        const auto given = answers.conserved.find(quantity);
        ++compared;
        disagree += given == answers.conserved.end() || given->second != shown;
        unanswered += given == answers.conserved.end() || given->second == "?";
    }
    const std::map<std::string, std::string> label = {{"min", "minimum"}, {"intermediate", "intermediate"}, {"max", "maximum"}};
    for (const auto& [axis, run] : runs) {
        const Wobble w = wobbleOf(spun(Scene{}, axis), axis, run);
        const auto given = answers.stability.find(label.at(axis));
        const std::string value = given == answers.stability.end() ? "missing" : given->second;
        const bool saysUnstable = value == "unstable", saysSteady = value == "stable";
        if (!w.spinReverses && w.largestWobble >= 1) continue;  // the run does not say
        ++compared;
        disagree += (w.spinReverses && !saysUnstable) || (!w.spinReverses && !saysSteady);
        unanswered += value == "missing" || value == "?";
    }
    // An answer not given yet is not a disagreement with the simulation: the line says which it is.
    std::string line;
    if (unanswered > 0 && unanswered == disagree) {
        line = std::to_string(unanswered) + " of " + std::to_string(compared) +
               " answers are not given yet (still \"?\" in BookAnswers.toml): run your simulation and write what it shows";
    } else {
        line = std::to_string(disagree) + " of " + std::to_string(compared) +
               " answers disagree with what your own simulation shows";
        if (unanswered > 0) line += " (" + std::to_string(unanswered) + " of them not given yet, still \"?\")";
    }
    grading::measured(disagree, "disagreements", line);
    CHECK(disagree == 0);
}

TEST_CASE("spin about the intermediate axis tumbles while the others hold steady", "[book][stability]") {
    // Measured on the student's simulation: within 4 s the intermediate-axis spin reverses; about the minimum and
    // maximum axes the 0.2 rad/s wobble stays under 1 rad/s.
    std::string problems;
    for (const std::string& axis : axisNames()) {
        const Scene scene = spun(Scene{}, axis);
        const Run run = simulateWhole(scene);
        if (!run.samples.empty()) {  // each spin as the feedback page shows it, whatever this test finds of it
            grading::attachPlot("your-run-" + axis + ".svg",
                                runPlot(scene, "about the " + axis + " axis",
                                        "your run: " + simlab::describeRun(defaultRunSettings()), run.samples));
        }
        const Wobble w = wobbleOf(scene, axis, run);
        if (axis == "intermediate" && !w.spinReverses) problems += "the intermediate-axis spin never reverses; ";
        if (axis != "intermediate" && (w.spinReverses || w.largestWobble >= 1)) {
            problems += "about the " + axis + " axis the wobble grows to " + grading::show(w.largestWobble) + " rad/s; ";
        }
    }
    INFO(problems);
    CHECK(problems.empty());
}

TEST_CASE("the model has only the three rotational degrees of freedom a spin about a fixed point needs",
          "[book][model]") {
    checkDegreesOfFreedom(simlab::observe::model(Scene{}), 3,
                          "a rotation about the book's center",
                          "a Ball mobilizer at its center gives the book exactly its three rotations");
}

TEST_CASE("the trade: 8 digits of the question's tumbling spin for the fewest evaluations", "[book][trade]") {
    // cheapestSettings(), measured on the student's own model as `simlab study trade book --question` measures a
    // setting - every step's w_B against Euler's equations in long double - from each of the question's starts,
    // against the front of the question's book and spin about its intermediate axis (not the lab's).
    gradeTrade<Sample, Scene>(tradeQuestion(), studentScene(tradeQuestion()), tradeDigits);
}

}  // namespace book::testing
