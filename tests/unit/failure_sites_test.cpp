// Where in the student's file a test failed: the frames a probe's process tells are data, and addr2line's answer is
// read so that only a frame in the student's own file, at a line it has, is ever named.
#include <catch2/catch.hpp>

#include "simlab/grading/failure_sites.h"

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
