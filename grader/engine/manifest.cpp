#include "simlab/engine/manifest.h"

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "simlab/engine/errors.h"

namespace simlab::engine {

const Assignment& Manifest::find(const std::string& id) const {
    for (const Assignment& a : assignments) {
        if (a.id == id) return a;
    }
    std::string known;
    for (const std::string& k : ids()) known += (known.empty() ? "" : ", ") + k;
    throw UsageError("unknown assignment '" + id + "'; available: " + known);
}

std::vector<std::string> Manifest::ids() const {
    std::vector<std::string> out;
    for (const Assignment& a : assignments) out.push_back(a.id);
    return out;
}

Manifest loadManifest() {
    const char* path = std::getenv("SIMLAB_MANIFEST");
    return loadManifest(path && *path ? path : SIMLAB_DEFAULT_MANIFEST);
}

Manifest loadManifest(const std::string& path) {
    std::ifstream in(path);
    if (!in) {
        throw UsageError("no build manifest at " + path + ": build simlab first (scripts/setup), or set SIMLAB_MANIFEST");
    }
    Manifest m;
    try {
        const nlohmann::json j = nlohmann::json::parse(in);
        m.path = path;
        m.version = j.at("version");
        m.sourceDir = j.at("source_dir");
        m.buildDir = j.at("build_dir");
        m.cmake = j.value("cmake", std::string("cmake"));
        m.studiesTarget = j.value("studies_target", std::string());
        m.sampleClass = j.at("sample_class");
        m.catch2Include = j.at("catch2_include");
        m.compile = j.at("compile").get<std::vector<std::string>>();
        m.link = j.at("link").get<std::vector<std::string>>();
        m.probeLibraries = j.at("probe_libraries").get<std::vector<std::string>>();
        m.probeLink = j.at("probe_link").get<std::vector<std::string>>();
        m.floorLibraries = j.at("floor_libraries").get<std::vector<std::string>>();
        m.programLibraries = j.at("program_libraries").get<std::vector<std::string>>();
        m.studyLibraries = j.value("study_libraries", std::vector<std::string>());
        for (const nlohmann::json& a : j.at("assignments")) {
            Assignment x;
            x.id = a.at("id");
            x.title = a.at("title");
            x.source = a.at("source");
            x.program = a.at("program");
            x.programPath = a.at("program_path");
            x.referenceProgramPath = a.at("reference_program_path");
            x.studyProgramPath = a.value("study_program_path", std::string());
            x.dir = a.at("dir");
            x.rubric = a.at("rubric");
            x.starter = a.at("starter");
            x.solution = a.at("solution");
            x.hiddenTestsBuilt = a.at("hidden_tests_built");
            x.hiddenTests = a.at("hidden_tests").get<std::vector<std::string>>();
            x.contractInclude = a.at("contract_include");
            x.compile = a.at("compile").get<std::vector<std::string>>();
            x.judge = a.at("judge");
            x.probeObjects = a.at("probe_objects").get<std::vector<std::string>>();
            x.floorObjects = a.at("floor_objects").get<std::vector<std::string>>();
            x.programObjects = a.at("program_objects").get<std::vector<std::string>>();
            x.studyObjects = a.value("study_objects", std::vector<std::string>());
            m.assignments.push_back(std::move(x));
        }
    } catch (const nlohmann::json::exception& e) {
        throw UsageError("build manifest " + path + " is damaged (" + e.what() + "): rebuild with scripts/setup");
    }
    return m;
}

}  // namespace simlab::engine
