// A project's description, project.toml, handed in beside its code: parsed by toml++ as the tests parse it, and each
// of its five parts read by description.h against a model and experiments such as the code declares.
#include "biosim/grading/description.h"
#include "fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace biosim;
    using namespace biosim::testing;
    toml::table t;
    try {
        t = toml::parse(std::string_view(reinterpret_cast<const char*>(data), size), std::string_view("project.toml"));
    } catch (const toml::parse_error&) {
        return 0;  // the test fails, saying where the file is not TOML
    }
    Schematic model;
    model.bodies.resize(2);
    model.bodies[0].name = "thigh";
    model.bodies[1].name = "shank";
    std::vector<ExperimentInfo> experiments(2);
    experiments[0].name = "energy";
    experiments[1].name = "period";
    schematicPart(t, model);
    paragraphPart(t);
    considerationsPart(t);
    questionPart(t);
    experimentsPart(t, experiments, 3);
    return 0;
}
