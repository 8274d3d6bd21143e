// The schematic of a project's model: the tree read from Simbody, its DOT graph, the picture and dot's rendering.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "Simbody.h"
#include "biosim/contract/Project.h"
#include "biosim/program/schematic.h"

using namespace SimTK;

namespace {

/// Mass properties from the central inertia (Simbody wants the inertia about the body's origin).
Body::Rigid rigid(double mass, const Vec3& com, const Vec3& centralMoments) {
    const Inertia central(centralMoments);
    return Body::Rigid(MassProperties(mass, com, central.shiftFromMassCenter(com, mass)));
}

const Vec3 kRodMoments(1.875e-5, 1e-8, 1.875e-5);  // a 0.15 m rod along y, 0.01 kg
const Vec3 kPlateMoments(4e-4, 2.5e-4, 6e-4);

/// The test model, built the way a student's buildModel does: a rod A hanging from a pin whose axis is Ground's
/// x, and a plate B on a pin at A's lower end whose axis is along the rod (A's y). Both origins at their pins.
struct TwoPins {
    std::unique_ptr<biosim::Model> model = std::make_unique<biosim::Model>();
    State state;

    explicit TwoPins(const std::string& nameOfB = "B") {
        // A Pin turns about its F's (and M's) z: turn those frames so that z is along the wanted axis.
        const Rotation zToX(Pi / 2, YAxis), zToY(-Pi / 2, XAxis);
        MobilizedBody::Pin a(model->matter.Ground(), Transform(zToX, Vec3(0)),
                             rigid(0.01, Vec3(0, -0.075, 0), kRodMoments), Transform(zToX, Vec3(0)));
        MobilizedBody::Pin b(a, Transform(zToY, Vec3(0, -0.15, 0)), rigid(0.1, Vec3(0, -0.05, 0), kPlateMoments),
                             Transform(zToY, Vec3(0)));
        model->bodies["A"] = a;
        model->bodies[nameOfB] = b;
        state = model->system.realizeTopology();
    }
};

bool near(const Vec3& a, const Vec3& b, double tolerance = 1e-12) { return (a - b).norm() <= tolerance; }

/// True if no raw line break is inside a double-quoted DOT string (backslash escapes honoured).
bool noRawNewlineInQuotes(const std::string& dot) {
    bool quoted = false;
    for (std::size_t i = 0; i < dot.size(); ++i) {
        if (quoted && dot[i] == '\\') {
            ++i;
            if (i < dot.size() && dot[i] == '\n') return false;
        } else if (dot[i] == '"') {
            quoted = !quoted;
        } else if (quoted && dot[i] == '\n') {
            return false;
        }
    }
    return !quoted;
}

bool endsWith(const std::string& text, const std::string& end) {
    return text.size() >= end.size() && text.compare(text.size() - end.size(), end.size(), end) == 0;
}

}  // namespace

TEST_CASE("the schematic reads bodies, joints and axes from the model", "[schematic]") {
    TwoPins t;
    const biosim::Schematic s = biosim::schematicOf(*t.model, t.state, "two pins");
    CHECK(s.title == "two pins");
    CHECK(s.degreesOfFreedom == 2);
    CHECK(s.constraints == 0);
    REQUIRE(s.bodies.size() == 2);
    const biosim::SchematicBody& a = s.bodies[0];
    const biosim::SchematicBody& b = s.bodies[1];
    CHECK(a.name == "A");
    CHECK(b.name == "B");
    CHECK(a.index == 1);
    CHECK(b.index == 2);
    CHECK(a.parent == 0);
    CHECK(b.parent == 1);
    CHECK(a.joint == "Pin");
    CHECK(b.joint == "Pin");
    CHECK(a.dof == 1);
    CHECK(b.dof == 1);
    REQUIRE(a.axes.size() == 1);
    REQUIRE(b.axes.size() == 1);
    CHECK(std::abs(a.axes[0][0]) == Approx(1).margin(1e-12));
    CHECK(near(Vec3(0, a.axes[0][1], a.axes[0][2]), Vec3(0)));
    CHECK(std::abs(b.axes[0][1]) == Approx(1).margin(1e-12));
    CHECK(near(Vec3(b.axes[0][0], 0, b.axes[0][2]), Vec3(0)));
}

TEST_CASE("the schematic places joints, origins and mass centers in Ground at t = 0", "[schematic]") {
    TwoPins t;
    const biosim::Schematic s = biosim::schematicOf(*t.model, t.state, "two pins");
    REQUIRE(s.bodies.size() == 2);
    CHECK(near(s.bodies[0].jointLocation, Vec3(0)));
    CHECK(near(s.bodies[0].origin, Vec3(0)));
    CHECK(near(s.bodies[0].massCenter, Vec3(0, -0.075, 0)));
    CHECK(near(s.bodies[1].jointLocation, Vec3(0, -0.15, 0)));
    CHECK(near(s.bodies[1].origin, Vec3(0, -0.15, 0)));
    CHECK(near(s.bodies[1].massCenter, Vec3(0, -0.2, 0)));
    CHECK(near(s.bodies[1].com, Vec3(0, -0.05, 0)));
}

TEST_CASE("the schematic gives masses and central inertias", "[schematic]") {
    TwoPins t;
    const biosim::Schematic s = biosim::schematicOf(*t.model, t.state, "two pins");
    REQUIRE(s.bodies.size() == 2);
    CHECK(s.bodies[0].mass == Approx(0.01));
    CHECK(s.bodies[1].mass == Approx(0.1));
    for (int i = 0; i < 3; ++i) {
        CHECK(s.bodies[0].moments[i] == Approx(kRodMoments[i]).margin(1e-15));
        CHECK(s.bodies[1].moments[i] == Approx(kPlateMoments[i]).margin(1e-15));
        CHECK(s.bodies[0].products[i] == Approx(0).margin(1e-15));
        CHECK(s.bodies[1].products[i] == Approx(0).margin(1e-15));
    }
}

TEST_CASE("the schematic does not change the caller's state", "[schematic]") {
    TwoPins t;
    REQUIRE(t.state.getSystemStage() < Stage::Position);
    biosim::schematicOf(*t.model, t.state, "two pins");
    CHECK(t.state.getSystemStage() < Stage::Position);
}

TEST_CASE("an unnamed body is named by its index; a Slider's axis and a Ball's none", "[schematic]") {
    biosim::Model model;
    MobilizedBody::Slider slider(model.matter.Ground(), Transform(Vec3(0, 1, 0)), rigid(2, Vec3(0), Vec3(1)),
                                 Transform());
    MobilizedBody::Ball(slider, Transform(), rigid(1, Vec3(0, -0.5, 0), Vec3(1)), Transform());
    model.bodies["cart"] = slider;
    const biosim::Schematic s = biosim::schematicOf(model, model.system.realizeTopology(), "cart");
    REQUIRE(s.bodies.size() == 2);
    CHECK(s.bodies[0].name == "cart");
    CHECK(s.bodies[1].name == "body 2");
    CHECK(s.bodies[0].joint == "Slider");
    REQUIRE(s.bodies[0].axes.size() == 1);
    CHECK(near(s.bodies[0].axes[0], Vec3(1, 0, 0)));
    CHECK(near(s.bodies[0].jointLocation, Vec3(0, 1, 0)));
    CHECK(s.bodies[1].joint == "Ball");
    CHECK(s.bodies[1].dof == 3);
    CHECK(s.bodies[1].axes.empty());
    CHECK(near(s.bodies[1].massCenter, Vec3(0, 0.5, 0)));
    CHECK(s.degreesOfFreedom == 4);
    const std::string dot = biosim::treeDot(s);
    CHECK(dot.find("Ball\\n3 dof\"") != std::string::npos);
    CHECK(dot.find("Slider\\n1 dof\\naxis (1, 0, 0)") != std::string::npos);
}

TEST_CASE("the tree in DOT names Ground, the bodies, the joints and the axes", "[schematic]") {
    TwoPins t;
    const std::string dot = biosim::treeDot(biosim::schematicOf(*t.model, t.state, "two pins"));
    CHECK(dot.rfind("digraph", 0) == 0);
    CHECK(dot.find("\"Ground\"") != std::string::npos);
    CHECK(dot.find("label=\"A\\n") != std::string::npos);
    CHECK(dot.find("label=\"B\\n") != std::string::npos);
    CHECK(dot.find("\"n0\" -> \"n1\"") != std::string::npos);
    CHECK(dot.find("\"n1\" -> \"n2\"") != std::string::npos);
    CHECK(dot.find("Pin\\n1 dof\\naxis (1, 0, 0)") != std::string::npos);
    CHECK(dot.find("axis (0, 1, 0)") != std::string::npos);
    CHECK(dot.find("m = 0.01 kg") != std::string::npos);
    CHECK(dot.find("I = diag(0.0004, 0.00025, 0.0006) kg m²") != std::string::npos);
    CHECK(dot.find("Ixy") == std::string::npos);  // no products of inertia here
    CHECK(noRawNewlineInQuotes(dot));
}

TEST_CASE("a name with quotes, a line break and markup is escaped in DOT and SVG", "[schematic]") {
    const std::string name = "say \"hi\"\n<b>&\\N\x07";
    TwoPins t(name);
    const biosim::Schematic s = biosim::schematicOf(*t.model, t.state, "it's <odd>");
    REQUIRE(s.bodies.size() == 2);
    CHECK(s.bodies[1].name == name);

    const std::string dot = biosim::treeDot(s);
    CHECK(dot.find("say \\\"hi\\\"\\n<b>&\\\\N\\n") != std::string::npos);
    CHECK(dot.find('\x07') == std::string::npos);
    CHECK(noRawNewlineInQuotes(dot));

    const std::string svg = biosim::pictureSvg(s);
    CHECK(svg.find("say &quot;hi&quot; &lt;b&gt;&amp;\\N</text>") != std::string::npos);
    CHECK(svg.find("it&#39;s &lt;odd&gt;") != std::string::npos);
    CHECK(svg.find("<b>") == std::string::npos);
    CHECK(svg.find("<odd>") == std::string::npos);
    CHECK(svg.find("say \"") == std::string::npos);
    CHECK(svg.find('\x07') == std::string::npos);

    // dot accepts the escaped graph and shows the name.
    const std::string rendered = biosim::renderSvg(dot);
    CHECK(rendered.find("say &quot;hi&quot;") != std::string::npos);
}

TEST_CASE("a Slider on the ground is drawn as a sleeve on a hatched rail, never with a pin's support", "[schematic]") {
    biosim::Model model;
    MobilizedBody::Slider slider(model.matter.Ground(), Transform(Vec3(0, 1, 0)), rigid(2, Vec3(0), Vec3(1)),
                                 Transform());
    model.bodies["cart"] = slider;
    const std::string svg = biosim::pictureSvg(biosim::schematicOf(model, model.system.realizeTopology(), "cart"));
    const auto count = [&svg](const std::string& what) {
        std::size_t n = 0;
        for (std::size_t at = svg.find(what); at != std::string::npos; at = svg.find(what, at + 1)) ++n;
        return n;
    };
    CHECK(count("fill=\"#ddd\"") == 0);  // the pin's triangle
    CHECK(count("r=\"5\" fill=\"#fff\" stroke=\"#000\" stroke-width=\"1.5\"") == 0);  // the pin's ring
    // In the front view the x axis lies in the page (a sleeve and its rail); in the side view it points out of it.
    CHECK(count("Z\" fill=\"#fff\" stroke=\"#000\" stroke-width=\"1.5\"") == 1);
    CHECK(count("width=\"10\" height=\"10\" fill=\"#fff\"") == 1);
    TwoPins t;
    const std::string pins = biosim::pictureSvg(biosim::schematicOf(*t.model, t.state, "two pins"));
    CHECK(pins.find("fill=\"#ddd\"") != std::string::npos);  // a Pin keeps its support
}

TEST_CASE("the picture is an SVG with both views, the names and a scale bar", "[schematic]") {
    TwoPins t;
    const std::string svg = biosim::pictureSvg(biosim::schematicOf(*t.model, t.state, "two pins"));
    CHECK(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0) == 0);
    CHECK(endsWith(svg, "</svg>\n"));
    CHECK(svg.find("viewBox=") != std::string::npos);
    CHECK(svg.find("front: x right, y up") != std::string::npos);
    CHECK(svg.find("side: z left, y up") != std::string::npos);
    CHECK(svg.find(">A</text>") != std::string::npos);
    CHECK(svg.find(">B</text>") != std::string::npos);
    CHECK(svg.find(">0.05 m</text>") != std::string::npos);  // 0.2 m tall model: a 0.05 m bar
    CHECK(svg.find("nan") == std::string::npos);
    CHECK(svg.find("<script") == std::string::npos);
}

TEST_CASE("a model with all its points at one spot is drawn in a 1 m box", "[schematic]") {
    biosim::Model model;
    model.bodies["P"] = MobilizedBody::Ball(model.matter.Ground(), Transform(), rigid(1, Vec3(0), Vec3(1)),
                                            Transform());
    const std::string svg = biosim::pictureSvg(biosim::schematicOf(model, model.system.realizeTopology(), "point"));
    CHECK(svg.find("nan") == std::string::npos);
    CHECK(svg.find("inf") == std::string::npos);
    CHECK(svg.find(">P</text>") != std::string::npos);
    CHECK(svg.find(" m</text>") != std::string::npos);
    CHECK(endsWith(svg, "</svg>\n"));

    const biosim::Schematic empty;  // Ground alone
    CHECK(endsWith(biosim::pictureSvg(empty), "</svg>\n"));
    CHECK(biosim::treeDot(empty).find("Ground") != std::string::npos);
}

TEST_CASE("Graphviz renders the tree as SVG", "[schematic]") {
    TwoPins t;
    const std::string svg = biosim::renderSvg(biosim::treeDot(biosim::schematicOf(*t.model, t.state, "two pins")));
    CHECK((svg.rfind("<?xml", 0) == 0 || svg.find("<svg") != std::string::npos));
    CHECK(svg.find("</svg>") != std::string::npos);
    CHECK(svg.find(">Ground</text>") != std::string::npos);
    CHECK(svg.find(">A</text>") != std::string::npos);
    CHECK(svg.find(">B</text>") != std::string::npos);
    CHECK(svg.find(">Pin</text>") != std::string::npos);
}

TEST_CASE("invalid DOT is a one-line runtime_error from renderSvg", "[schematic]") {
    std::string message;
    try {
        biosim::renderSvg("digraph { this is not -> -> dot");
    } catch (const std::runtime_error& e) {
        message = e.what();
    }
    CHECK(message.rfind("dot failed: ", 0) == 0);
    CHECK(message.find('\n') == std::string::npos);
    CHECK_THROWS_AS(biosim::renderSvg(""), std::runtime_error);
    // dot stops reading at the error: the rest of a long input meets a closed pipe, which must not end the test.
    CHECK_THROWS_AS(biosim::renderSvg("digraph { -> " + std::string(4 << 20, 'x')), std::runtime_error);
}

TEST_CASE("a large graph goes through dot's pipes without a deadlock", "[schematic]") {
    // More than a pipe's buffer (64 KiB) each way: the writer must not wait for a reader that waits for it.
    const std::string word(2000, 'w');
    std::string dot = "digraph {\n";
    for (int i = 0; i < 50; ++i) dot += "  n" + std::to_string(i) + " [label=\"" + word + std::to_string(i) + "\"];\n";
    dot += "}\n";
    REQUIRE(dot.size() > 65536);
    const std::string svg = biosim::renderSvg(dot);
    CHECK(svg.size() > 65536);
    CHECK(svg.find(word + "49</text>") != std::string::npos);
}

TEST_CASE("a rod drawn as a cylinder or a line is drawn to its ends, not only to its mass center", "[schematic]") {
    TwoPins t;
    // A's rod reaches B's mass center, 0.2 m down, as the baby boot's does; B's line, 0.1 m across, is B's own.
    MobilizedBody a = t.model->bodies.at("A");
    a.updBody().addDecoration(Vec3(0, -0.1, 0), DecorativeCylinder(0.01, 0.1));
    MobilizedBody b = t.model->bodies.at("B");
    b.updBody().addDecoration(Transform(), DecorativeLine(Vec3(-0.05, 0, 0), Vec3(0.05, 0, 0)));
    b.updBody().addDecoration(Transform(), DecorativeSphere(0.02));  // no ends: not a rod
    t.state = t.model->system.realizeTopology();
    const biosim::Schematic s = biosim::schematicOf(*t.model, t.state, "rods");
    REQUIRE(s.bodies.size() == 2);
    REQUIRE(s.bodies[0].ends.size() == 2);
    const std::vector<Vec3>& rod = s.bodies[0].ends;
    CHECK(((near(rod[0], Vec3(0)) && near(rod[1], Vec3(0, -0.2, 0))) ||
           (near(rod[1], Vec3(0)) && near(rod[0], Vec3(0, -0.2, 0)))));
    // B's frame is turned (its pin's z along A's y), so its line lies along Ground's z or x: 0.1 m long, at B.
    REQUIRE(s.bodies[1].ends.size() == 2);
    CHECK((s.bodies[1].ends[0] - s.bodies[1].ends[1]).norm() == Approx(0.1));
    CHECK(near((s.bodies[1].ends[0] + s.bodies[1].ends[1]) / 2, Vec3(0, -0.15, 0)));
    // The picture draws a link from A's mass center to its rod's far end.
    const std::string svg = biosim::pictureSvg(s);
    CHECK(svg.find("nan") == std::string::npos);
}

TEST_CASE("names whose mass centers coincide in a view are placed apart, each readable", "[schematic]") {
    // A and B both hang 0.1 m below the origin, B 0.2 m further along z: one spot in the front view.
    biosim::Model model;
    model.bodies["A"] = MobilizedBody::Ball(model.matter.Ground(), Transform(),
                                            rigid(1, Vec3(0, -0.1, 0), Vec3(1e-3)), Transform());
    model.bodies["B"] = MobilizedBody::Ball(model.matter.Ground(), Transform(Vec3(0, 0, 0.2)),
                                            rigid(1, Vec3(0, -0.1, 0), Vec3(1e-3)), Transform());
    const std::string svg = biosim::pictureSvg(biosim::schematicOf(model, model.system.realizeTopology(), "apart"));
    // The first label of each name is the front view's; its y is the text's baseline.
    auto labelY = [&](const std::string& name) {
        const std::size_t end = svg.find(">" + name + "</text>");
        REQUIRE(end != std::string::npos);
        const std::size_t y = svg.rfind(" y=\"", end);
        return std::stod(svg.substr(y + 4));
    };
    CHECK(std::abs(labelY("A") - labelY("B")) >= 14);
}
