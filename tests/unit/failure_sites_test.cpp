// Where in the student's file a test failed: the frames a probe's process tells are data, and addr2line's answer is
// read so that only a frame in the student's own file, at a line it has, is ever named.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "simlab/build/build.h"
#include "simlab/build/manifest.h"
#include "simlab/common/files.h"
#include "simlab/grading/failure_sites.h"

namespace failure_sites_test {

using namespace simlab::engine;

TEST_CASE("a probe's frames are read as data: a short list of small whole numbers or nothing", "[failure-sites]") {
    CHECK(readFailureFrames(nlohmann::json::parse("[4660, 22107]")) == std::vector<std::uint64_t>{4660, 22107});
    CHECK(readFailureFrames(nlohmann::json::parse("[]")).empty());
    CHECK(readFailureFrames(nlohmann::json::parse("[1, -2]")).empty());
    CHECK(readFailureFrames(nlohmann::json::parse("[1, 2.5]")).empty());
    CHECK(readFailureFrames(nlohmann::json::parse("[1, \"0x10\"]")).empty());
    CHECK(readFailureFrames(nlohmann::json::parse("[1099511627776]")).empty());  // past any probe
    CHECK(readFailureFrames(nlohmann::json::parse("{\"at\": 1}")).empty());
    CHECK(readFailureFrames(nlohmann::json::array_t(17, 1)).empty());  // more frames than a line tells
}

namespace {

// addr2line -f -C -i -a: a student's function, an inlined call in it, a frame of the course's (no line tables), a
// frame of a header's template.
const char* const kAnswer =
    "0x0000000000012a40\n"
    "apple::simulate(apple::Model const&, SimTK::Integrator&, SimTK::State const&, simlab::RunSettings const&)\n"
    "/tmp/simlab-apple-x/build/NewtonsApple.cpp:71\n"
    "0x0000000000012b00\n"
    "apple::(anonymous namespace)::nudge(double)\n"
    "/tmp/simlab-apple-x/build/NewtonsApple.cpp:30 (discriminator 2)\n"
    "apple::sample(apple::Model const&, SimTK::State const&)\n"
    "/tmp/simlab-apple-x/build/NewtonsApple.cpp:52\n"
    "0x0000000000020000\n"
    "??\n"
    "??:0\n"
    "0x0000000000013000\n"
    "SimTK::Vec<3, double, 1>::operator[](int)\n"
    "/usr/include/simbody/SimTKcommon/internal/Vec.h:577\n";

}  // namespace

TEST_CASE("addr2line's answer is read address by address, inlined calls first", "[failure-sites]") {
    const auto entries = readAddr2line(kAnswer);
    REQUIRE(entries.size() == 4);
    REQUIRE(entries.at(0x12b00).size() == 2);
    CHECK(entries.at(0x12b00)[0].line == 30);
    CHECK(entries.at(0x12b00)[0].file == "/tmp/simlab-apple-x/build/NewtonsApple.cpp");
    CHECK(entries.at(0x12b00)[1].function == "apple::sample(apple::Model const&, SimTK::State const&)");
    CHECK(entries.at(0x20000).at(0).line == 0);
    CHECK(entries.at(0x20000).at(0).function.empty());
}

TEST_CASE("a function is shown by its name alone", "[failure-sites]") {
    CHECK(functionShown("apple::simulate(apple::Model const&, SimTK::Integrator&)") == "apple::simulate");
    CHECK(functionShown("apple::(anonymous namespace)::nudge(double)") == "apple::nudge");
    CHECK(functionShown("Handler::handleEvent(SimTK::State&, double, bool&) const") == "Handler::handleEvent");
    CHECK(functionShown("apple::sample(apple::Model const&)::{lambda(double)#1}::operator()(double) const") ==
          "apple::sample");
    CHECK(functionShown("double apple::twice<double>(double)") == "apple::twice<double>");
    CHECK(functionShown("Box::operator()(int)") == "Box::operator()");
    CHECK(functionShown("Box::operator+(Box const&)").empty());
    CHECK(functionShown("??").empty());
    CHECK(functionShown("\x1b]0;pwned\x07(int)").empty());  // what a line table the student shaped could say
    CHECK(functionShown(std::string(200, 'a') + "()").empty());
}

TEST_CASE("only a frame in the student's file, at a line it has, is named", "[failure-sites]") {
    const auto entries = readAddr2line(kAnswer);
    // The innermost frame in the file: the course's frame and the header's are passed over.
    SourceSite site = innermostIn({0x20000, 0x13000, 0x12a40}, entries, "NewtonsApple.cpp", 80);
    CHECK(site.inReason() == " in apple::simulate() (NewtonsApple.cpp:71)");
    // An inlined call is the innermost frame of its address.
    CHECK(innermostIn({0x12b00, 0x12a40}, entries, "NewtonsApple.cpp", 80).inReason() ==
          " in apple::nudge() (NewtonsApple.cpp:30)");
    // Another file of the same folder, a line past the file's end, an address nobody looked up: nothing.
    CHECK_FALSE(innermostIn({0x12a40}, entries, "ProjectileMotion.cpp", 80).found());
    CHECK_FALSE(innermostIn({0x12a40}, entries, "NewtonsApple.cpp", 70).found());
    CHECK(innermostIn({0x12a40}, entries, "NewtonsApple.cpp", 70).inReason().empty());
    CHECK_FALSE(innermostIn({0x99999}, entries, "NewtonsApple.cpp", 80).found());
    // A function whose name cannot be shown: its line alone.
    SourceSite unnamed;
    unnamed.file = "NewtonsApple.cpp";
    unnamed.line = 12;
    CHECK(unnamed.inReason() == " (NewtonsApple.cpp:12)");
}

namespace {

// The address of the function whose symbol is `symbol` in the linked file `path` (binutils' nm reads it).
std::uint64_t addressOf(const std::string& path, const std::string& symbol) {
    std::FILE* nm = ::popen(("/usr/bin/nm " + path).c_str(), "r");
    REQUIRE(nm);
    char line[4096];
    std::uint64_t address = 0;
    while (std::fgets(line, sizeof line, nm)) {
        const std::string text(line);
        if (text.size() > 19 && text.compare(19, std::string::npos, symbol + "\n") == 0) {
            address = std::stoull(text.substr(0, 16), nullptr, 16);
        }
    }
    ::pclose(nm);
    return address;
}

}  // namespace

TEST_CASE("a probe's twin with line tables names the student's line, and only a twin of the same code serves",
          "[failure-sites][build]") {
    // The apple's reference built as a check builds it, and its twin compiled with -g1: the same code, laid out
    // elsewhere by the linker (line tables bring unwind entries of their own).
    TempDir cache("simlab-cache-test-");
    ::setenv("SIMLAB_CACHE", cache.path().c_str(), 1);
    const Manifest manifest = loadManifest();
    const Assignment& apple = manifest.find("apple");
    const Builder builder(manifest);
    ::unsetenv("SIMLAB_CACHE");
    const std::string text = readFile(apple.solution);
    TempDir work("simlab-sites-test-");
    const BuildResult graded =
        builder.buildProbe(apple, "NewtonsApple.cpp", text, work.path(), work.path() + "/probe.so");
    REQUIRE(graded.ok);
    Assignment lined = apple;
    lined.compile.push_back("-g1");
    int builds = 0;
    auto twin = [&](const std::string& folder) {
        ++builds;
        const BuildResult made =
            builder.buildProbe(lined, "NewtonsApple.cpp", text, folder, folder + "/probe.so", false);
        return FailureSites::LinedTwin{made.binary, made.object};
    };
    const std::size_t lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
    FailureSites sites(graded.binary, graded.object, "NewtonsApple.cpp", lines, work.path() + "/lines", twin);
    // A call in simulate(): the innermost frame there, at a line of the function's.
    const std::string simulate =
        "_ZN5apple8simulateERKNS_5ModelERN5SimTK10IntegratorERKNS3_5StateERKN6simlab11RunSettingsERNS9_8RecorderINS_6"
        "SampleEEE";
    const std::uint64_t at = addressOf(graded.binary, simulate);
    REQUIRE(at != 0);
    sites.lookUp({{at + 8}, {at + 16}});
    sites.lookUp({{at + 8}});  // looked up once; the twin made once
    CHECK(builds == 1);
    const SourceSite site = sites.site({at + 8});
    CHECK(site.function == "apple::simulate");
    const std::size_t declared = text.find("void simulate(");
    REQUIRE(declared != std::string::npos);
    const int line = static_cast<int>(std::count(text.begin(), text.begin() + declared, '\n')) + 1;
    CHECK(site.line >= line);
    CHECK(site.line <= line + 12);
    // An object of other code is no twin: one more statement.
    std::string other = text;
    other.replace(other.find("    stepper.initialize(initial);"), 0,
                  "    stepper.setReportAllSignificantStates(true);\n");
    createPrivateFolder(work.path() + "/other");
    const BuildResult otherBuilt = builder.buildProbe(apple, "NewtonsApple.cpp", other, work.path() + "/other",
                                                      work.path() + "/other.so");
    REQUIRE(otherBuilt.ok);
    CHECK(sameCode(readFile(graded.object), readFile(graded.object)));
    CHECK_FALSE(sameCode(readFile(graded.object), readFile(otherBuilt.object)));
    CHECK_FALSE(sameCode("not an object", "not an object"));
    auto otherTwin = [&](const std::string&) { return FailureSites::LinedTwin{otherBuilt.binary, otherBuilt.object}; };
    FailureSites notTwins(graded.binary, graded.object, "NewtonsApple.cpp", lines, work.path() + "/not", otherTwin);
    notTwins.lookUp({{at + 8}});
    CHECK_FALSE(notTwins.site({at + 8}).found());
    // The twin's addresses are not the probe's, and an address in no function goes nowhere.
    const auto mapped =
        sameFunctionAddresses({at + 8, 1}, readFile(graded.binary), readFile(work.path() + "/lines/probe.so"));
    REQUIRE(mapped.count(at + 8) == 1);
    CHECK(mapped.count(1) == 0);
}

}  // namespace failure_sites_test
