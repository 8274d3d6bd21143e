// The student's process's answers on the wire, as the judge takes them (harness/observe.cpp): one line, checked to
// answer the question asked, in the shape the wire format gives, and then read as the type the grader asked for
// (protocol/wire.h's strict reading of each lab's observations.h). The probe runs student code: every byte of its
// answer is the student's to choose.
//
// An input is the question's type on its first line ("apple.run", "book.mass", "biosim.declaration", ...; see
// kinds below) and the answer's line after it, in which $ID stands for the question's number.
#include <functional>
#include <map>

#include "apple/grading/observations.h"
#include "biosim/grading/observations.h"
#include "book/grading/observations.h"
#include "fuzz.h"
#include "projectile/grading/observations.h"
#include "simlab/harness/observe.h"
#include "transport.h"

namespace {

std::string gAnswer;  // the answer the fake probe gives to the next question

}  // namespace

// The transport, faked: the answer is the input's, with the question's number in place of $ID; past the limit it is
// the bad report the pipes' reader makes it.
namespace simlab::observe::detail {

std::string exchange(const std::string& request, std::size_t limit) {
    std::string answer = gAnswer;
    const std::string id = std::to_string(nlohmann::json::parse(request).at("id").get<int>());
    for (std::size_t at = answer.find("$ID"); at != std::string::npos; at = answer.find("$ID", at + id.size())) {
        answer.replace(at, 3, id);
    }
    if (answer.size() > limit) throw BadReport("an answer longer than the rubric's limit");
    return answer;
}

void beginTest(const std::string&) {}

std::string drain() { return ""; }

}  // namespace simlab::observe::detail

namespace {

using namespace simlab;

template <class T>
std::function<void(const nlohmann::json&, const std::string&)> as() {
    return [](const nlohmann::json& value, const std::string& kind) { observe::decode<T>(value, kind); };
}

// Every type a lab's grader reads an answer as, by the question that asks for it.
const std::map<std::string, std::function<void(const nlohmann::json&, const std::string&)>>& kinds() {
    static const std::map<std::string, std::function<void(const nlohmann::json&, const std::string&)>> all = {
        {"model", as<ModelInfo>()},
        {"apple.run", as<RunResult<apple::Sample>>()},
        {"apple.choice", as<ChoiceRun<apple::Sample>>()},
        {"projectile.run", as<RunResult<projectile::Sample>>()},
        {"projectile.choice", as<ChoiceRun<projectile::Sample>>()},
        {"projectile.landing", as<projectile::Landing>()},
        {"book.run", as<RunResult<book::Sample>>()},
        {"book.choice", as<ChoiceRun<book::Sample>>()},
        {"book.mass", as<book::MassObservation>()},
        {"biosim.declaration", as<biosim::Declaration>()},
        {"biosim.run", as<biosim::Observed>()},
        {"biosim.schematic", as<biosim::Schematic>()},
        {"biosim.experiments", as<std::vector<biosim::ExperimentInfo>>()},
        {"biosim.traits", as<std::vector<biosim::ColumnTraits>>()},
        {"biosim.answer", as<biosim::Answer>()},
        {"biosim.evaluate", as<std::vector<double>>()},
        {"biosim.problems", as<std::vector<std::string>>()}};
    return all;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::vector<std::string> input = fuzz::parts(fuzz::text(data, size), "\n", 2);
    if (input.size() < 2) return 0;
    const auto kind = kinds().find(input[0]);
    if (kind == kinds().end()) return 0;
    gAnswer = input[1];
    observe::startTest("fuzz");
    observe::clearFailure();
    try {
        kind->second(observe::ask(kind->first, nlohmann::json::object()), kind->first);
    } catch (const observe::BadReport&) {
    } catch (const observe::StudentError&) {
    } catch (const observe::NonFinite&) {
    }
    observe::finishTest();
    return 0;
}
