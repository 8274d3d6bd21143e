#include "simlab/build/manifest.h"
#include "simlab/build/lab.h"
#include "simlab/isolation/process.h"

#include <pwd.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/common/text.h"

namespace simlab::engine {

namespace fs = std::filesystem;

namespace {

constexpr const char* kPrefixMark = "@prefix@";  // what an installed manifest writes for its prefix

// Every string in `j` with the installed manifest's mark replaced by `prefix`.
void placeAt(nlohmann::json& j, const std::string& prefix) {
    if (j.is_string()) {
        std::string text = j.get<std::string>();
        for (std::size_t at = text.find(kPrefixMark); at != std::string::npos; at = text.find(kPrefixMark, at)) {
            text.replace(at, std::char_traits<char>::length(kPrefixMark), prefix);
            at += prefix.size();
        }
        j = text;
    } else if (j.is_structured()) {
        for (nlohmann::json& element : j) placeAt(element, prefix);
    }
}

// Where simlab keeps what it reuses between runs for an installed prefix (or a build this user may not write in):
// the user's cache, one folder per prefix and version (a moved prefix starts afresh).
std::string userCacheDir(const std::string& prefix, const std::string& version) {
    std::string base;
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg == '/') {
        base = xdg;
    } else if (const char* home = std::getenv("HOME"); home && *home == '/') {
        base = std::string(home) + "/.cache";
    } else if (const struct passwd* user = ::getpwuid(::getuid()); user && user->pw_dir && *user->pw_dir == '/') {
        base = std::string(user->pw_dir) + "/.cache";
    } else {
        // Never a shared folder such as /tmp, where another user could lay out the cache before simlab does.
        throw UsageError(
            "simlab keeps this user's cache in $XDG_CACHE_HOME or ~/.cache: set HOME or "
            "XDG_CACHE_HOME (this user has no home folder)");
    }
    return base + "/simlab/" + sha256Hex(prefix + "\n" + version).substr(0, 16);
}

// An installed prefix's precompiled headers are made on first use: beside their headers if this user may write
// there (a prefix of one's own), else in the user's cache, where the compile commands then look for them.
void placePrecompiledHeaders(Manifest& m) {
    for (Assignment& a : m.assignments) {
        if (a.precompiledHeader.empty()) continue;
        const std::string dir = fs::path(a.precompiledHeader).parent_path().string();
        if (::access(dir.c_str(), W_OK) == 0) continue;
        const std::string moved = m.cacheDir + "/pch";
        for (std::string& part : a.compile) {
            if (part.rfind(dir + "/", 0) == 0) part = moved + part.substr(dir.size());
        }
        a.precompiledHeader = moved + a.precompiledHeader.substr(dir.size());
    }
}

// One assignment of a manifest (simlab_add_assignment's entry).
Assignment readAssignment(const nlohmann::json& a) {
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
    x.solutionShipped = a.value("solution_shipped", false);
    x.example = a.value("example", "");
    x.projects = a.value("projects", false);
    x.longRun = a.value("long_run", false);
    x.corpus = a.value("corpus", x.dir + "/corpus");
    x.hiddenTestsBuilt = a.at("hidden_tests_built");
    x.hiddenTests = a.at("hidden_tests").get<std::vector<std::string>>();
    x.contractInclude = a.at("contract_include");
    x.compile = a.at("compile").get<std::vector<std::string>>();
    x.judge = a.at("judge");
    x.probeObjects = a.at("probe_objects").get<std::vector<std::string>>();
    x.floorObjects = a.at("floor_objects").get<std::vector<std::string>>();
    x.programObjects = a.at("program_objects").get<std::vector<std::string>>();
    x.studyObjects = a.value("study_objects", std::vector<std::string>());
    x.precompiledHeader = a.value("precompiled_header", std::string());
    x.precompileFlags = a.value("precompile_flags", std::vector<std::string>());
    x.buildDir = a.value("build_dir", std::string());
    return x;
}

}  // namespace

std::vector<Assignment> loadLabManifest(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw UsageError("no lab manifest at " + path);
    try {
        std::vector<Assignment> out;
        const nlohmann::json j = nlohmann::json::parse(in);
        for (const nlohmann::json& a : j.at("assignments")) out.push_back(readAssignment(a));
        return out;
    } catch (const nlohmann::json::exception& e) {
        throw UsageError("lab manifest " + path + " is damaged (" + e.what() + ")");
    }
}

std::vector<std::string> secretPaths(const Manifest& manifest, const Assignment& assignment) {
    std::vector<std::string> secrets = assignment.hiddenTests;
    // What the build made of them: the judge, its tests' objects and the hidden trade question's text; what it made
    // of the solution (its object, the reference lab program, its study).
    std::error_code error;
    const fs::path relative = fs::path(assignment.dir).lexically_relative(manifest.sourceDir);
    // A lab built out of the tree (simlab/build/lab.h) names its build folder; its corpus holds the solution's edits.
    const bool built = !assignment.buildDir.empty() || (!relative.empty() && *relative.begin() != "..");
    const fs::path buildDir =
        assignment.buildDir.empty() ? fs::path(manifest.buildDir) / relative : fs::path(assignment.buildDir);
    // A worked example's solution is handed out: it, and what the build made of it, are no secret.
    const bool solution = !assignment.solution.empty() && !assignment.solutionShipped;
    for (const std::string& path :
         {solution ? fs::path(assignment.solution).parent_path().string() : std::string(), assignment.judge,
          manifest.sampleClass, solution ? assignment.referenceProgramPath : std::string(),
          solution ? assignment.studyProgramPath : std::string(),
          built ? (buildDir / "CMakeFiles" / (assignment.id + "_grader_tests.dir")).string() : std::string(),
          built ? (buildDir / "trade").string() : std::string(),
          built && solution ? (buildDir / (assignment.program + "_reference.o")).string() : std::string(),
          assignment.buildDir.empty() ? std::string() : assignment.dir + "/corpus"}) {
        if (!path.empty()) secrets.push_back(path);
    }
    return secrets;
}

std::vector<std::string> courseSecrets(const Manifest& manifest) {
    std::vector<std::string> secrets;
    std::vector<const Assignment*> all;
    for (const Assignment& a : manifest.assignments) all.push_back(&a);
    for (const auto& lab : manifest.labs) all.push_back(lab.get());
    for (const Assignment* a : all) {
        for (const std::string& secret : secretPaths(manifest, *a)) {
            if (std::find(secrets.begin(), secrets.end(), secret) == secrets.end()) secrets.push_back(secret);
        }
    }
    secrets.push_back(manifest.sourceDir + "/tests/corpus");
    secrets.push_back(manifest.cacheDir + "/objects");
    secrets.push_back(manifest.sourceDir + "/.git");
    secrets.push_back(manifest.buildDir + "/Testing");
    return secrets;
}

std::string installedManifestPath(const std::string& exe) {
    std::error_code error;
    const fs::path prefix = fs::canonical(exe, error).parent_path().parent_path();
    if (error) return "";
    const fs::path manifest = prefix / "lib/simlab/simlab-build.json";
    return fs::is_regular_file(manifest, error) ? manifest.string() : "";
}

const Assignment& Manifest::find(const std::string& id) const {
    // A name the course has not, which names a lab's folder here, is that folder.
    std::error_code error;
    const bool known =
        std::any_of(assignments.begin(), assignments.end(), [&](const Assignment& a) { return a.id == id; });
    if (isLabFolder(id) || (!known && fs::is_regular_file(fs::path(id) / "CMakeLists.txt", error))) {
        const std::string dir = fs::canonical(id, error).string();
        for (const Assignment& a : assignments) {  // one of the course's own, by its folder
            std::error_code other;
            if (!error && fs::canonical(a.dir, other).string() == dir && !other) return a;
        }
        for (const auto& lab : labs) {
            if (!error && lab->dir == dir) return *lab;  // built once a run
        }
        Assignment lab = buildLab(*this, id);
        // Its id is the declaration's, whatever its folder is called; one the course's labs have would mix the two
        // in every output named by it.
        for (const Assignment& a : assignments) {
            if (a.id == lab.id) {
                throw UsageError("the lab in " + printable(lab.dir) + " declares the id '" + printable(lab.id) +
                                 "', which is one of this course's labs: give it another in its CMakeLists.txt "
                                 "(simlab_add_assignment)");
            }
        }
        for (const auto& other : labs) {
            if (other->id == lab.id) {
                throw UsageError("the labs in " + printable(other->dir) + " and " + printable(lab.dir) +
                                 " both declare the id '" + printable(lab.id) + "': give one another");
            }
        }
        labs.push_back(std::make_unique<Assignment>(std::move(lab)));
        // The lab's folder whole (its history, corpus and solution too) and its build are simlab's places.
        isolation::addPlaces({labs.back()->dir, labBuildFolder(*this, id)});
        return *labs.back();
    }
    for (const Assignment& a : assignments) {
        if (a.id == id) return a;
    }
    std::string names;
    for (const std::string& k : ids()) names += (names.empty() ? "" : ", ") + k;
    throw UsageError("unknown assignment '" + id + "'; available: " + names + ", or a lab's folder");
}

std::vector<std::string> Manifest::ids() const {
    std::vector<std::string> out;
    for (const Assignment& a : assignments) out.push_back(a.id);
    return out;
}

std::vector<std::string> Manifest::ids(bool (*has)(const Assignment&)) const {
    std::vector<std::string> out;
    for (const Assignment& a : assignments) {
        if (has(a)) out.push_back(a.id);
    }
    return out;
}

const Assignment* Manifest::projectsLab() const {
    for (const Assignment& a : assignments) {
        if (a.projects) return &a;
    }
    return nullptr;
}

// The manifest of the build this engine was built in: a file of that build alone (grader/CMakeLists.txt), so that
// this object is the same in every copy of the sources.
extern const char* const kDefaultManifest;

Manifest loadManifest() {
    const char* path = std::getenv("SIMLAB_MANIFEST");
    if (path && *path) return loadManifest(path);
    const std::string installed = installedManifestPath("/proc/self/exe");
    return loadManifest(installed.empty() ? kDefaultManifest : installed);
}

Manifest loadManifest(const std::string& path) {
    std::ifstream in(path);
    if (!in) {
        throw UsageError("no build manifest at " + path +
                         ": build simlab first (scripts/setup), or set SIMLAB_MANIFEST");
    }
    Manifest m;
    try {
        nlohmann::json j = nlohmann::json::parse(in);
        m.path = path;
        m.installed = j.value("installed", false);
        if (m.installed) {
            // <prefix>/lib/simlab/simlab-build.json
            std::error_code error;
            m.prefix = fs::canonical(path, error).parent_path().parent_path().parent_path().string();
            if (error) throw UsageError("cannot resolve the installed manifest " + path + ": " + error.message());
            placeAt(j, m.prefix);
        }
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
        m.probeHost = j.at("probe_host");
        m.floorLibraries = j.at("floor_libraries").get<std::vector<std::string>>();
        m.programLibraries = j.at("program_libraries").get<std::vector<std::string>>();
        m.studyLibraries = j.value("study_libraries", std::vector<std::string>());
        for (const nlohmann::json& a : j.at("assignments")) m.assignments.push_back(readAssignment(a));
        if (const auto kit = j.find("kit"); kit != j.end()) {
            m.kit.include = kit->at("include").get<std::vector<std::string>>();
            m.kit.cmakeDir = kit->at("cmake_dir");
            for (const nlohmann::json& t : kit->at("targets")) {
                m.kit.targets.push_back({t.at("name"), t.at("kind"), t.at("files").get<std::vector<std::string>>(),
                                         t.at("links").get<std::vector<std::string>>()});
            }
        }
        // A build's cache is in it, for its owner; another user of the build (a TA on the course's machine), who
        // may not write there, keeps one in their own cache folder, as for an installation.
        const std::string buildCache = m.buildDir + "/cache";
        const bool buildCacheOurs = ::access(buildCache.c_str(), W_OK | X_OK) == 0 ||
                                    (::access(buildCache.c_str(), F_OK) != 0 && ::access(m.buildDir.c_str(), W_OK | X_OK) == 0);
        m.cacheDir = m.installed ? userCacheDir(m.prefix, m.version)
                     : buildCacheOurs ? buildCache
                                      : userCacheDir(m.buildDir, m.version);
        if (const char* cache = std::getenv("SIMLAB_CACHE"); cache && *cache) {
            std::error_code error;
            m.cacheDir = fs::absolute(cache, error).lexically_normal().string();
            if (error || m.cacheDir.empty()) throw UsageError("SIMLAB_CACHE is '" + printable(cache) + "': a folder's path");
        }
        if (m.installed) placePrecompiledHeaders(m);
    } catch (const nlohmann::json::exception& e) {
        throw UsageError("build manifest " + path + " is damaged (" + e.what() + "): rebuild with scripts/setup");
    }
    // Nothing of simlab's own is any sandbox's to read but what each process is lent (isolation/reach.h): a
    // sandbox lets its processes read the system's folders, and an installation in /usr/local lies among them.
    std::vector<std::string> places = {m.sourceDir, m.buildDir, m.cacheDir, m.sampleClass,
                                       fs::path(m.path).parent_path().string()};
    if (m.installed) {
        for (const char* place : {"/lib/simlab", "/share/simlab"}) places.push_back(m.prefix + place);
    }
    for (const Assignment& a : m.assignments) places.push_back(a.dir);
    // Every lab built against this simlab before, wherever it lies, and whether this run names it or not.
    for (const std::string& lab : labsBuilt(m)) places.push_back(lab);
    isolation::addPlaces(places);
    isolation::useProbeHost(m.probeHost);
    return m;
}

}  // namespace simlab::engine
