// The biosimulation project: the experiments the grader runs on any project through its contract, and the checks
// of its description. Points and thresholds are in ../rubric.toml; the parts only a person can judge are its
// [[manual]] items.
#include <functional>
#include <iomanip>
#include <set>
#include <sstream>

#include "biosim_testing.h"

namespace biosim::testing {

namespace {

std::string show(double value) { return grading::show(value); }

/// A parameter's value to six significant digits, so that the ends of a narrow range stay apart.
std::string exact(double value) {
    std::ostringstream text;
    text << std::setprecision(6) << value;
    return text.str();
}

/// One of the five parts of project.toml: whether it is there with substance, and if not, what to do.
struct Part {
    std::string name;
    std::string missing;  ///< empty when the part is complete
};

Part schematicPart(const toml::table& t, const Schematic& model) {
    Part part{"schematic", ""};
    const toml::array* bodies = t["schematic"]["bodies"].as_array();
    const toml::array* points = t["schematic"]["points"].as_array();
    if (!bodies || bodies->empty() || !points || points->empty()) {
        part.missing = "[schematic] lists the model's points and bodies: points = [...], bodies = [...]";
        return part;
    }
    std::set<std::string> listed, built;
    for (const auto& b : *bodies) listed.insert(b.value_or(std::string()));
    for (const SchematicBody& b : model.bodies) built.insert(b.name);
    if (listed != built) {
        std::string names;
        for (const std::string& n : built) names += (names.empty() ? "" : ", ") + n;
        part.missing = "[schematic] bodies must name the bodies the model builds (" + names + ")";
    }
    return part;
}

Part paragraphPart(const toml::table& t) {
    const std::string text = t["description"]["text"].value_or(std::string());
    if (isPlaceholder(text) || wordCount(text) < 40) {
        return {"description", "[description] text is a paragraph of at least 40 words about the system (has " +
                                   std::to_string(wordCount(text)) + ")"};
    }
    return {"description", ""};
}

Part considerationsPart(const toml::table& t) {
    const toml::array* list = t["considerations"]["list"].as_array();
    int substantial = 0;
    if (list) {
        for (const auto& item : *list) {
            const std::string text = item.value_or(std::string());
            if (!isPlaceholder(text) && wordCount(text) >= 3) ++substantial;
        }
    }
    if (substantial < 3) {
        return {"considerations", "[considerations] list holds at least 3 modelling considerations of 3 words or more (has " +
                                      std::to_string(substantial) + ")"};
    }
    return {"considerations", ""};
}

Part questionPart(const toml::table& t) {
    const std::string text = t["question"]["text"].value_or(std::string());
    const auto answer = t["question"]["answer"].value<double>();
    if (isPlaceholder(text) || wordCount(text) < 6 || text.find('?') == std::string::npos) {
        return {"question", "[question] text asks an interesting question, of 6 words or more, ending in '?'"};
    }
    if (!answer || !std::isfinite(*answer) || t["question"]["unit"].value_or(std::string()).empty()) {
        return {"question", "[question] gives the answer your program computes (answer = <number>, unit = \"...\")"};
    }
    return {"question", ""};
}

Part experimentsPart(const toml::table& t, const std::vector<ExperimentInfo>& inCode, int minimum) {
    const toml::array* list = t["experiment"].as_array();
    std::set<std::string> described;
    if (list) {
        for (const auto& item : *list) {
            const toml::table* e = item.as_table();
            if (!e) continue;
            const std::string name = (*e)["name"].value_or(std::string());
            const std::string shows = (*e)["shows"].value_or(std::string());
            if (!name.empty() && !isPlaceholder(shows) && wordCount(shows) >= 4) described.insert(name);
        }
    }
    std::set<std::string> coded;
    for (const ExperimentInfo& e : inCode) coded.insert(e.name);
    if (static_cast<int>(described.size()) < minimum) {
        return {"experiments", "[[experiment]] entries describe at least " + std::to_string(minimum) +
                                   " of your experiments (name = ..., shows = \"what it validates\")"};
    }
    for (const std::string& name : described) {
        if (!coded.count(name)) return {"experiments", "experiment '" + name + "' is described but experiments() has none of that name"};
    }
    for (const std::string& name : coded) {
        if (!described.count(name)) return {"experiments", "experiment '" + name + "' is in experiments() but not described in project.toml"};
    }
    return {"experiments", ""};
}

/// The outcome of one of the student's own experiments on one run: the figure it measured and whether it holds;
/// and what the run showed of the column, for the words of a verdict that no mutant changed.
struct Verdict {
    bool holds = false;
    std::string line;
    bool columnMoved = true;     ///< the column changed in the run
    bool columnMirrored = true;  ///< (symmetric) the mirrored run's column differs from the first's
};

/// Whether a list of values changes at all.
bool moves(const std::vector<double>& c) {
    return std::any_of(c.begin(), c.end(), [&](double v) { return v != c.front(); });
}

/// The column an experiment is about, in one run: the course's own reading where the column is one (a coordinate,
/// a speed, the energy), else the student's values; with the scale errors are measured against and its words: the
/// column's largest magnitude in the run, as the handout says (a 0.5 degree swing is judged against 0.5 degree, not
/// against one radian), the energy against the energy the motion exchanges. Near a zero a column's own magnitude is
/// no scale: where a drift is measured from the start (`fromStart`, a conserved column) and the column starts at
/// zero, or where it is zero all the way, it is measured against the scale its experiment states (.against); without
/// one a coordinate or a speed against one radian or unit, and a column of the student's has none (`unscaled`).
struct Series {
    std::vector<double> values;
    double scale = 1;
    std::string scaleWords;  ///< e.g. "against the energy the motion exchanges, 0.83 J"
    bool unscaled = false;   ///< it starts at zero and nothing gives it a scale
};

Series seriesOf(const Observed& run, int column, const std::string& name, double stated, bool fromStart) {
    Series s;
    const std::vector<double> c = columnOf(run, static_cast<std::size_t>(column));
    const Reading reading = readingOf(run, c);
    s.values = reading.what.empty() ? c : reading.values;
    double largest = 0;
    for (const double v : s.values) largest = std::max(largest, std::abs(v));
    if (reading.what == "the mechanical energy") {
        s.scale = reading.scale;
        const bool zero = std::abs(s.values.front()) <= 1e-9 * s.scale;
        s.scaleWords = std::string(zero ? "it starts at zero: " : "") + "against the energy the motion exchanges, " +
                       show(s.scale) + " J";
    } else if (!reading.what.empty()) {
        const bool zero = !(largest > 0) || (fromStart && !(std::abs(s.values.front()) > 1e-9 * largest));
        s.scale = !zero ? largest : stated > 0 ? stated : reading.scale;
        s.scaleWords = std::string(zero ? name + " starts at zero: " : "") + "against " +
                       (!zero ? "its largest magnitude, " : stated > 0 ? "the stated scale, " : "one radian or unit, ") +
                       show(s.scale);
    } else if (stated > 0) {
        s.scale = stated;
        s.scaleWords = "against the stated scale, " + show(stated);
    } else {
        s.scale = largest > 0 ? largest : 1.0;
        s.unscaled = !(std::abs(s.values.front()) > 1e-9 * largest) || !(largest > 0);
        s.scaleWords = std::string(s.unscaled ? name + " starts at zero: " : "") + "against its largest magnitude, " +
                       show(s.scale);
    }
    if (!reading.what.empty()) s.scaleWords += "; judged on the course's reading of " + reading.what;
    return s;
}

/// One of the student's own experiments judged on the model, or on a mutant of it.
Verdict judgeExperiment(const Declaration& d, const ExperimentInfo& e, const Mutation& mutation = {}) {
    if (!(e.tolerance >= 1e-15 && e.tolerance <= 1e-2)) {
        return {false, "tolerance " + show(e.tolerance) + " is outside [1e-15, 1e-2]: too loose to test anything"};
    }
    if (!(e.scale >= 0 && std::isfinite(e.scale))) {
        return {false, "its stated scale " + show(e.scale) + " is not a positive number"};
    }
    const bool needsColumn = e.kind != "at rest";
    int column = -1;
    if (needsColumn) {
        try {
            column = columnIndex(d, e.column);
        } catch (const std::invalid_argument&) {
            return {false, "names no declared column ('" + e.column + "')"};
        }
    }
    auto within = [&](double figure, const std::string& what) {
        return Verdict{figure <= e.tolerance, what + " " + show(figure) + ", allowed " + show(e.tolerance)};
    };
    // A run of a few samples shows nothing: each experiment runs for at least `minimum_samples` of the
    // declaration's sample interval.
    const double shortest = grading::param("minimum_samples") * d.run.dt;
    const double span = e.kind == "periodic" ? e.period : (e.finalTime > 0 ? e.finalTime : d.run.finalTime);
    if (!(span >= shortest) || !(span <= 1e4)) {
        return {false, "runs " + show(span) + " s; it must run at least " + show(shortest) + " s (" +
                           show(grading::param("minimum_samples")) + " samples)"};
    }
    if (e.kind == "periodic") {
        const Observed run = runWith(e.set, settingsFor(d, e.period), mutation);
        const Series c = seriesOf(run, column, e.column, e.scale, false);
        const auto [low, high] = std::minmax_element(c.values.begin(), c.values.end());
        if (!((*high - *low) / c.scale >= grading::param("least_variation"))) {
            return {false, e.column + " hardly changes over the period (a constant repeats with any period)"};
        }
        Verdict v = within(std::abs(c.values.back() - c.values.front()) / c.scale,
                           e.column + "(T) - " + e.column + "(0), " + c.scaleWords + ",");
        return v;
    }
    const Observed run = runWith(e.set, settingsFor(d, e.finalTime), mutation);
    if (e.kind == "at rest") {
        return within(std::max(largestDrift(run.q), largestDrift(run.u)), "largest change of q or u");
    }
    const Series c = seriesOf(run, column, e.column, e.scale, e.kind == "conserved");
    if (e.kind == "conserved") {
        if (c.unscaled && moves(c.values)) {
            return {false, e.column + " starts at zero, and a drift measured against the drift itself is always 1: "
                           "state the scale it is small against with .against(value)"};
        }
        double drift = 0;
        for (const double v : c.values) drift = std::max(drift, std::abs(v - c.values.front()));
        Verdict v = within(drift / c.scale, "relative drift of " + e.column + " (" + c.scaleWords + "),");
        v.columnMoved = moves(c.values);
        return v;
    }
    if (e.kind == "symmetric") {
        const Observed mirrored = runWith(merged(e.set, e.mirror), settingsFor(d, e.finalTime), mutation);
        if (!(largestDifference(run.q, mirrored.q) >= grading::param("least_variation") * largestMagnitude(run.q))) {
            return {false, "the mirror changes nothing: the mirrored run moves as the first one does"};
        }
        const Series m = seriesOf(mirrored, column, e.column, e.scale, false);
        double worst = 0;
        bool differ = false;
        for (std::size_t k = 0; k < std::min(c.values.size(), m.values.size()); ++k) {
            worst = std::max(worst, std::abs(m.values[k] - e.sign * c.values[k]));
            differ = differ || m.values[k] != c.values[k];
        }
        Verdict v = within(worst / c.scale, "largest mirror mismatch, relative,");
        v.columnMirrored = differ;
        return v;
    }
    if (e.kind == "formula") {
        if (!e.hasFormula) return {false, "has no formula"};
        const std::vector<double> f = observe::decode<std::vector<double>>(
            observe::ask("formula", {{"name", e.name}, {"times", simlab::wire::toJson(run.time)}}), "formula");
        if (f.size() != c.values.size()) {
            return {false, "its formula gave " + std::to_string(f.size()) + " values for " +
                               std::to_string(c.values.size()) + " samples"};
        }
        double worst = 0;
        for (std::size_t k = 0; k < c.values.size(); ++k) worst = std::max(worst, std::abs(c.values[k] - f[k]));
        return within(worst / c.scale, "largest departure from the formula (" + c.scaleWords + "),");
    }
    return {false, "unknown kind '" + e.kind + "'"};
}

/// An experiment that holds on the model must fail on some mutant of it, or it shows nothing: the course damps the
/// motion (at a rate that takes most of its energy over the run), scales gravity, moves the start, and moves each
/// parameter the experiment does not set, stopping at the first mutant on which the experiment fails.
Verdict judgeWithMutants(const Declaration& d, const ExperimentInfo& e) {
    const Verdict model = judgeExperiment(d, e);
    if (!model.holds) return model;
    const double span = e.kind == "periodic" ? e.period : (e.finalTime > 0 ? e.finalTime : d.run.finalTime);
    std::vector<std::pair<std::string, Mutation>> mutants;
    Mutation damped;
    damped.damping = 2 / span;
    mutants.push_back({"damped", damped});
    Mutation heavier;
    heavier.gravityScale = 1.25;
    mutants.push_back({"gravity x1.25", heavier});
    Mutation nudged;
    nudged.nudge = grading::param("nudge");
    mutants.push_back({"start moved by " + show(nudged.nudge), nudged});
    std::string tried;
    bool moved = model.columnMoved, mirrored = model.columnMirrored;
    auto failsOn = [&](const ExperimentInfo& variant, const Mutation& mutation) {
        try {
            const Verdict v = judgeExperiment(d, variant, mutation);
            moved = moved || v.columnMoved;
            mirrored = mirrored || v.columnMirrored;
            return !v.holds;
        } catch (const observe::StudentError&) {
            return true;  // the mutant did not even run: the experiment's scene depends on what changed
        } catch (const observe::NonFinite&) {
            return true;
        }
    };
    for (const auto& [name, mutation] : mutants) {
        tried += (tried.empty() ? "" : ", ") + name;
        if (failsOn(e, mutation)) return {true, model.line + "; it fails on a mutant (" + name + "), so it can fail"};
    }
    for (const Parameter& p : d.parameters) {
        if (e.set.count(p.name)) continue;
        ExperimentInfo variant = e;
        variant.set[p.name] = movedValueOf(p, e.set);
        if (variant.set[p.name] == p.value) continue;
        tried += ", " + p.name + " = " + show(variant.set[p.name]);
        if (failsOn(variant, {})) {
            return {true, model.line + "; it fails on a mutant (" + p.name + " moved), so it can fail"};
        }
    }
    std::string why = "it holds on every mutant the course made (" + tried + "): it cannot fail, so it shows nothing";
    if (e.kind == "at rest") why = "nothing could move: it stays at rest when its start is moved too, so no force acts in that scene";
    else if (e.kind == "conserved" && !moved) why = e.column + " never moves, in the model or in any mutant: a constant is conserved by anything";
    else if (e.kind == "symmetric" && !mirrored) why = e.column + " is the same in both runs though the mirror changes the motion: it ignores what the mirror changes";
    const ColumnVerdict columns = columnVerdict(d);
    if (const auto found = columns.byColumn.find(e.column); found != columns.byColumn.end()) {
        why += " (" + e.column + " " + found->second + ")";
    }
    return {false, model.line + "; but " + why};
}

}  // namespace

TEST_CASE("the description has all five parts", "[biosim][description]") {
    const toml::table t = description();
    // The schematic's bodies and the experiments' names are checked against the code; the rest is text.
    auto fromCode = [](const std::string& part, const std::function<Part()>& check) {
        try {
            return check();
        } catch (const observe::StudentError& e) {
            return Part{part, "the code must run to check this part: " + std::string(e.what())};
        }
    };
    const int minimum = static_cast<int>(grading::param("minimum_experiments"));
    const std::vector<Part> parts = {
        fromCode("schematic", [&] { return schematicPart(t, schematicWith({})); }), paragraphPart(t),
        considerationsPart(t), questionPart(t),
        fromCode("experiments", [&] { return experimentsPart(t, declaredExperiments(), minimum); })};
    int complete = 0;
    for (const Part& part : parts) {
        if (part.missing.empty()) ++complete;
        else grading::feedback("next: " + part.missing);
    }
    grading::measured(complete, "parts", std::to_string(complete) + " of 5 parts complete");
    grading::partialCredit(complete / 5.0);
    CHECK(complete == 5);
}

TEST_CASE("the default scene runs to the final time and every column reads the state", "[biosim][run]") {
    const Declaration d = declared();
    const Observed run = runWith({}, d.run);
    const std::size_t expected = static_cast<std::size_t>(d.run.sampleCount()) + 1;
    REQUIRE(run.time.size() == expected);
    REQUIRE(run.time.back() == Approx(d.run.finalTime).margin(1e-9));
    // Each column is an observation of the state: the same state gives the same value, and a change of a
    // coordinate or a speed moves it (unless it is declared constant). The course samples states it changes one
    // thing at a time (course.h's columnTraits); a column that follows the time or the parameters alone says
    // nothing of the model.
    const ColumnVerdict columns = columnVerdict(d);
    const int n = static_cast<int>(d.columns.size());
    grading::measured(columns.good, "columns",
                      std::to_string(run.time.size()) + " samples to t = " + show(run.time.back()) + " s (" +
                          run.integrator.method + ", " + std::to_string(run.integrator.stepsTaken) + " steps); " +
                          std::to_string(columns.good) + " of " + std::to_string(n) + " columns read from the state" +
                          (columns.problems.empty() ? "" : ": " + columns.problems));
    if (!columns.problems.empty()) {
        grading::feedback("sample() returns what the state shows: read each column from `state` (a coordinate, a "
                          "speed, a position, an energy), or declare it constant = true if it is one");
    }
    grading::partialCredit(n > 0 ? static_cast<double>(columns.good) / n : 0);
    CHECK(columns.good == n);
}

TEST_CASE("with no gravity and no motion the model stays at rest", "[biosim][rest]") {
    const Declaration d = declared();
    requireReportedModel(d);
    if (d.claims.atRest.empty()) {
        FAIL("the declaration's claims.atRest gives no settings for a scene at rest (no gravity, no initial motion)");
    }
    // From the declared configuration, and from one nearby with every q moved: a model that stays put only because
    // it starts in an equilibrium (a force left on, gravity hard-wired) moves when nudged.
    const Observed run = runWith(d.claims.atRest, d.run);
    const Observed nudged = nudgedRun(d.claims.atRest, d.run, grading::param("nudge"));
    const double fromDeclared = std::max(largestDrift(run.q), largestDrift(run.u));
    const double fromNudged = std::max(largestDrift(nudged.q), largestDrift(nudged.u));
    if (fromNudged > fromDeclared) {
        grading::feedback("it stays at rest where it starts but not when every q is moved by " +
                          show(grading::param("nudge")) + ": is a force (gravity?) still on in claims.atRest?");
    }
    CHECK(grading::atMost(std::max(fromDeclared, fromNudged), grading::param("tolerance"),
                          "largest change of any q (rad or m) or u (rad/s or m/s)"));
}

TEST_CASE("the mechanical energy is conserved when nothing is claimed to dissipate", "[biosim][energy]") {
    const Declaration d = declared();
    requireReportedModel(d);
    // At the declared accuracy, but never looser than the rubric's loosest: a loose accuracy asked for must not
    // make any drift acceptable.
    simlab::RunSettings s = d.run;
    s.accuracy = std::min(s.accuracy, grading::param("loosest_accuracy"));
    const Observed run = runWith(d.claims.energyWhen, s);
    if (run.customForces > 0) {
        grading::feedback("the potential energy of a Force::Custom is not counted (its code is yours to check, not "
                          "the course's): build conservative forces from Simbody's own force elements");
    }
    // Near a zero of the total, a relative error means nothing: the drift is measured against the energy the
    // motion exchanges, the largest kinetic energy or change of potential energy in the run.
    const biosim::EnergyBalance balance = biosim::energyBalance(run);
    const double scale = balance.exchanged, drift = balance.drift, e0 = balance.initial;
    if (!(scale > 0)) FAIL("nothing moved, so there is no energy to conserve: choose claims.energyWhen with some motion");
    if (!d.claims.energyConserved) {
        // The opposite claim, that the model dissipates, is checked too: by the final time the energy has fallen.
        const double lost = (e0 - run.kinetic.back() - run.potential.back()) / scale;
        grading::measured(lost, "", "energy lost by t = " + show(run.time.back()) + " s, relative to the energy "
                                    "exchanged, " + show(lost) + ", need " + show(grading::param("dissipated")) +
                                    " (the declaration claims that the model dissipates)");
        CHECK(lost >= grading::param("dissipated"));
        return;
    }
    const double allowed = grading::param("tolerance") * s.accuracy;
    CHECK(grading::atMost(drift / scale, allowed, "energy drift relative to the energy exchanged"));
}

TEST_CASE("a tenfold tighter accuracy gains digits until double precision runs out", "[biosim][convergence]") {
    const Declaration d = declared();
    requireReportedModel(d);
    // Runs at accuracy 1e-3 ... 1e-10 with RungeKuttaMerson, sampled only ten times so that the sampling never
    // caps the steps. Each is compared with the next, ten times tighter, in every generalized coordinate and speed
    // at the final time (read from the state).
    simlab::RunSettings s = d.run;
    s.integrator = "RungeKuttaMerson";
    s.fixedStep = false;
    s.dt = s.finalTime / 10;
    std::vector<Observed> runs;
    for (int exponent = 3; exponent <= 10; ++exponent) {
        s.accuracy = std::pow(10.0, -exponent);
        runs.push_back(runWith({}, s));
    }
    std::vector<double> digits;
    std::ostringstream list;
    for (std::size_t k = 0; k + 1 < runs.size(); ++k) {
        digits.push_back(agreementDigits(runs[k], runs[k + 1]));
        list << (k ? ", " : "") << std::fixed << std::setprecision(1) << digits.back();
    }
    // The gain per decade over the last three decades before double precision's limit (or the end): where the
    // error is the integrator's own, not yet swamped by round-off, and past any start where the runs have not
    // converged at all (a chaotic model's loose runs share no digits).
    const double saturated = grading::param("saturated");
    std::size_t last = 0;
    while (last + 1 < digits.size() && digits[last] < saturated) ++last;
    const std::size_t first = last >= 3 ? last - 3 : 0;
    const double gain = last > first ? (digits[last] - digits[first]) / static_cast<double>(last - first) : 0.0;
    grading::feedback("digits agreed at t = " + show(s.finalTime) + " s between accuracies 1e-3/1e-4 ... 1e-9/1e-10: " +
                      list.str());
    CHECK(grading::atLeast(gain, grading::param("floor"), grading::param("target"), "digits gained per decade"));
}

TEST_CASE("the model has exactly the degrees of freedom claimed", "[biosim][model]") {
    const Declaration d = declared();
    requireReportedModel(d);
    // The schematic, drawn from the model the student built, goes to their feedback.
    const Schematic schematic = schematicWith({});
    grading::attach("schematic-t0.svg", pictureSvg(schematic));
    const std::string dot = treeDot(schematic);
    try {
        grading::attach("schematic-tree.svg", renderSvg(dot));
    } catch (const std::runtime_error& e) {
        grading::attach("schematic-tree.dot", dot);
        grading::feedback(std::string("the tree is in schematic-tree.dot: ") + e.what());
    }
    const Observed run = runWith({}, settingsFor(d, std::min(d.run.finalTime, d.run.dt)));
    const simlab::ModelInfo& info = run.model;
    grading::measured(info.degreesOfFreedom(), "degrees of freedom",
                      info.summary() + "; claimed " + std::to_string(d.claims.degreesOfFreedom));
    if (info.mobilities != info.degreesOfFreedom()) {
        grading::feedback("constraints take back motions the mobilizers gave: give each body a mobilizer with only "
                          "the motions the scene needs");
    }
    if (run.auxiliaryStates > 0) {
        grading::feedback("the model has " + std::to_string(run.auxiliaryStates) + " auxiliary state variable(s) (z) "
                          "beside its mobilities: the scene's motions belong in mobilizers, where they are counted");
    }
    if (run.addedSubsystems > 0) {
        grading::feedback("buildModel added " + std::to_string(run.addedSubsystems) + " subsystem(s): build bodies in "
                          "model.matter and forces in model.forces");
    }
    INFO(info.summary() << "; the declaration claims " << d.claims.degreesOfFreedom
                        << (d.claims.degreesOfFreedom == 1 ? " degree" : " degrees") << " of freedom");
    CHECK(run.auxiliaryStates == 0);
    CHECK(run.addedSubsystems == 0);
    CHECK(d.claims.degreesOfFreedom > 0);
    CHECK(info.degreesOfFreedom() == d.claims.degreesOfFreedom);
    CHECK(info.mobilities == d.claims.degreesOfFreedom);
}

TEST_CASE("every parameter changes the motion", "[biosim][parameters]") {
    const Declaration d = declared();
    requireReportedModel(d);
    REQUIRE_FALSE(d.parameters.empty());
    const simlab::RunSettings s = settingsFor(d, std::min(d.run.finalTime, grading::param("seconds")));
    const Observed base = runWith({}, s);
    int changing = 0;
    std::string inert, least;
    double leastChange = INFINITY;
    for (const Parameter& p : d.parameters) {
        const Observed other = runWith({{p.name, movedValueOf(p)}}, s);
        // The motion (q, u) or, for a parameter the motion does not depend on (a pendulum's mass, say), the
        // kinetic energy Simbody computes from the model: read from the state, never from the student's columns.
        // (Not the potential energy: a body welded in place could make that follow any parameter.) Each change is
        // relative to the larger run's own size, so that a parameter scaled down to a trace does not count.
        double kineticChange = 0, kineticScale = 0;
        for (std::size_t k = 0; k < std::min(base.time.size(), other.time.size()); ++k) {
            kineticChange = std::max(kineticChange, std::abs(base.kinetic[k] - other.kinetic[k]));
            kineticScale = std::max({kineticScale, base.kinetic[k], other.kinetic[k]});
        }
        const double change =
            std::max({largestDifference(base.q, other.q) / std::max(largestMagnitude(base.q), largestMagnitude(other.q)),
                      largestDifference(base.u, other.u) / std::max(largestMagnitude(base.u), largestMagnitude(other.u)),
                      kineticScale > 0 ? kineticChange / kineticScale : 0.0});
        if (change < leastChange) {
            leastChange = change;
            least = p.name + ", " + show(change);
        }
        if (change >= grading::param("relative_change")) ++changing;
        else inert += (inert.empty() ? "" : ", ") + p.name + " (" + show(change) + ")";
    }
    const int n = static_cast<int>(d.parameters.size());
    grading::measured(changing, "parameters", std::to_string(changing) + " of " + std::to_string(n) +
                                                   " parameters change the motion" +
                                                   (inert.empty() ? " (least: " + least + ")" : "; not: " + inert));
    if (!inert.empty()) {
        grading::feedback("is a number hard-wired where " + inert + " belongs? Read it with p[\"name\"]: a change "
                          "halfway to the far end of its range must change the motion by " +
                          show(grading::param("relative_change")) + " of its size or more (declare the range the "
                          "parameter is meant for, wide enough for its effect to show)");
    }
    grading::partialCredit(static_cast<double>(changing) / n);
    CHECK(changing == n);
}

TEST_CASE("no NaN or Inf or integrator failure across the parameter ranges", "[biosim][ranges]") {
    const Declaration d = declared();
    requireReportedModel(d);
    int tried = 0, ran = 0;
    std::string first, narrow, ruled;
    const double narrowest = grading::param("narrowest");
    for (const Parameter& p : d.parameters) {
        // A range that holds little more than its default claims little: it counts as two runs that failed.
        if (!(p.max - p.min > narrowest * std::abs(p.value)) || !(p.max > p.min)) {
            tried += 2;
            narrow += (narrow.empty() ? "" : ", ") + p.name + " [" + exact(p.min) + ", " + exact(p.max) + "]";
            continue;
        }
        for (double value : {p.min, p.max}) {
            ++tried;
            // Where a rule of the declaration refuses the end of the range (the others at their defaults), the
            // run goes as far toward it as the rules allow.
            const double reached = reachable(p, value, [&](double v) { return refusal({{p.name, v}}).empty(); });
            if (reached != value) {
                if (ruled.size() < 300) ruled += (ruled.empty() ? "" : ", ") + p.name + " to " + show(reached);
                value = reached;
            }
            try {
                runWith({{p.name, value}}, d.run);
                ++ran;
            } catch (const observe::StudentError& e) {
                if (first.empty()) first = p.name + " = " + show(value) + ": " + e.what();
            } catch (const observe::NonFinite& e) {
                if (first.empty()) first = p.name + " = " + show(value) + ": " + e.what();
            }
        }
    }
    grading::measured(ran, "runs", std::to_string(ran) + " of " + std::to_string(tried) +
                                       " runs at the ends of the ranges finished" + (first.empty() ? "" : "; first failure: " + first));
    if (!narrow.empty()) {
        grading::feedback("ranges narrower than " + show(narrowest) + " of their default, not tried: " + narrow +
                          "; declare the range the model is meant for");
    }
    if (!ruled.empty()) grading::feedback("as far as the declaration's rules allow: " + ruled);
    grading::partialCredit(tried ? static_cast<double>(ran) / tried : 0);
    CHECK(tried > 0);
    CHECK(ran == tried);
}

TEST_CASE("the project's own experiments pass", "[biosim][experiments]") {
    const Declaration d = declared();
    const std::vector<ExperimentInfo> list = declaredExperiments();
    const int minimum = static_cast<int>(grading::param("minimum_experiments"));
    int passed = 0;
    for (const ExperimentInfo& e : list) {
        Verdict v;
        try {
            v = judgeWithMutants(d, e);
        } catch (const observe::StudentError& error) {
            v = {false, error.what()};
        } catch (const observe::NonFinite& error) {
            v = {false, error.what()};
        }
        if (v.holds) ++passed;
        grading::feedback((v.holds ? "holds: " : "fails: ") + e.name + " (" + e.kind + "): " + v.line);
    }
    const int counted = std::max(static_cast<int>(list.size()), minimum);
    grading::measured(passed, "experiments", std::to_string(passed) + " of " + std::to_string(list.size()) +
                                                 " experiments hold (at least " + std::to_string(minimum) + " needed)");
    grading::partialCredit(static_cast<double>(passed) / counted);
    CHECK(passed == counted);
}

TEST_CASE("the question is answered with the number the program computes", "[biosim][answer]") {
    const toml::table t = description();
    const auto written = t["question"]["answer"].value<double>();
    if (!written) FAIL("project.toml's [question] has no answer = <number>");
    auto answerWith = [](const Settings& set) {
        return observe::decode<Answer>(observe::ask("answer", {{"set", simlab::wire::toJson(set)}}), "answer");
    };
    const Answer answer = answerWith({});
    const double computed = answer.value;
    const double difference = std::abs(*written - computed) / std::max(std::abs(computed), 1e-300);
    grading::measured(computed, t["question"]["unit"].value_or(std::string()),
                      "the program computes " + show(computed) + " from " + std::to_string(answer.simulations) +
                          " simulation(s); project.toml says " + show(*written));
    if (answer.simulations < 1) grading::feedback("answer() must compute its number by calling simulate()");
    CHECK(answer.simulations >= 1);
    CHECK(difference <= grading::param("tolerance"));
    if (answer.simulations < 1 || !(difference <= grading::param("tolerance"))) return;  // failed already
    // The answer comes from the simulation: with a parameter moved (one at a time, until one does) the motion
    // changes, and so must the answer. One that stays put whatever the model is typed in, not computed.
    const Declaration d = declared();
    const int most = static_cast<int>(grading::param("parameters_tried"));
    std::string tried;
    bool follows = false;
    int count = 0;
    for (const Parameter& p : d.parameters) {
        if (count >= most) break;
        const double value = movedValueOf(p);
        if (value == p.value) continue;
        ++count;
        const double other = answerWith({{p.name, value}}).value;
        tried += (tried.empty() ? "" : ", ") + p.name + " = " + show(value) + ": " + show(other);
        if (std::abs(other - computed) > 1e-9 * std::max(std::abs(computed), std::abs(other))) {
            follows = true;
            break;
        }
    }
    if (!follows) {
        grading::feedback("the answer stays " + show(computed) + " when the model changes (" + tried + "): it must "
                          "come from what simulate() returns");
    }
    CHECK(follows);
}

}  // namespace biosim::testing
