// Observations: what a grader test learns about a student's simulation, and the only way it learns it.
//
// A grader test runs in the judge, a process that never loads student code. When it needs to know what the
// student's code does, it asks: observe::run(scene, settings) sends the request to the probe, a separate
// sandboxed process that holds the student's code, calls the contract through the course's driver and answers
// with data (the samples, the model's description, the integrator's statistics). The answer is validated here
// before any test sees it: one line of JSON, under a size cap, answering the request that was made, in the shape
// the wire format gives. Anything else is a BadReport, whose outcome is "bad report", never a pass. The judge
// then computes every figure and every point from those observations, the exact solutions and the rubric.
//
//     TEST_CASE("y at the final time has the target accuracy digits", "[apple]") {
//         const auto run = simlab::observe::run<Sample>(Scene{}, defaultRunSettings());
//         ...
//     }
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "simlab/driver.h"
#include "simlab/measured_run.h"
#include "simlab/model_info.h"
#include "simlab/run_settings.h"
#include "simlab/wire_types.h"

namespace simlab::observe {

/// The student's code threw while answering (a SIMLAB_TODO, say): the test fails with its message.
class StudentError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The answer broke the protocol (not JSON, too large, out of turn, the wrong shape): outcome "bad report".
class BadReport : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The student's process ended before it answered (it exited, crashed or ran out of a limit). The engine names
/// the outcome from how the process ended.
class ProcessEnded : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// An answer held a number that is not finite: the test fails, saying where ("samples[37].yLocation").
class NonFinite : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Ask the probe for an observation of `kind` ("run", "model", ...) with `arguments`; returns the answer,
/// checked to be well formed and finite. Throws the exceptions above.
nlohmann::json ask(const std::string& kind, const nlohmann::json& arguments);

/// ask(), for a question the tests of a judge ask alike (a run of the lab's default scene, say): its answer,
/// once a student's process has given it, checked, is the answer for every later test of this judge that asks
/// the same, which then need not start a process at all. For questions whose repetition is not itself what a test
/// looks at.
nlohmann::json askShared(const std::string& kind, const nlohmann::json& arguments);

/// The shared questions the test under way has used (at most kMaxSharedReported), each by a digest of the
/// question: the seconds its answer took where this test asked the student's process, 0 where an earlier test's
/// answer served. The harness reports them, so that the next self-check can give tests that ask alike to one
/// judge, where the answer is computed once.
constexpr std::size_t kMaxSharedReported = 256;
std::map<std::string, double> sharedUsed();

/// `answer` read as a T; a field missing or of the wrong type is a BadReport naming it.
template <class T>
T decode(const nlohmann::json& answer, const std::string& kind) {
    T value{};
    try {
        wire::readValue(answer, value, "");
    } catch (const wire::WireError& e) {
        throw BadReport("the answer to '" + kind + "' is malformed: " + e.what());
    }
    return value;
}

/// The student's simulation of `scene` with `settings`, driven by the course's driver as the lab program drives
/// it: every sample, the model's description and the integrator's statistics (an answer shared, see askShared).
template <class Sample, class Scene>
RunResult<Sample> run(const Scene& scene, const RunSettings& settings) {
    return decode<RunResult<Sample>>(
        askShared("run", {{"scene", wire::toJson(scene)}, {"settings", wire::toJson(settings)}}), "run");
}

/// The model the student builds for `scene`: its bodies, mobilizers and degrees of freedom.
template <class Scene>
ModelInfo model(const Scene& scene) {
    return decode<ModelInfo>(ask("model", {{"scene", wire::toJson(scene)}}), "model");
}

/// The student's answer to the trade question (their cheapest setting), measured on their model of `scene` to
/// `finalTime`, stopped past `maxEvaluations`: the choice, the samples at the checked states and the run's cost.
template <class Sample, class Scene>
ChoiceRun<Sample> choice(const Scene& scene, double finalTime, double maxEvaluations) {
    return decode<ChoiceRun<Sample>>(ask("choice", {{"scene", wire::toJson(scene)},
                                                    {"final_time", finalTime},
                                                    {"max_evaluations", maxEvaluations}}),
                                     "choice");
}

/// A test case begins: the next question goes to a new student's process of its own. Called by the harness.
void startTest(const std::string& test);

/// What the channel said when the test ended: empty if all was well, else why it is a bad report (bytes nobody
/// asked for, say). Called once by the harness after each test case; closes the channel.
std::string finishTest();

/// How the last failure of the channel is to be reported (set when ask() throws BadReport or ProcessEnded).
enum class ChannelFailure { None, BadReport, ProcessEnded };
ChannelFailure lastFailure();
void clearFailure();

}  // namespace simlab::observe
