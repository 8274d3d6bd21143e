#include "biosim/program/schematic.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>

#include "biosim/contract/Project.h"
#include "simlab/messages.h"
#include "simlab/model_info.h"
#include "simlab/system_tool.h"

namespace biosim {

namespace {

// ---- Text ---------------------------------------------------------------------------------------------------

/// The length of the valid UTF-8 sequence starting at text[i], or 0 if it is not one.
std::size_t utf8Length(const std::string& text, std::size_t i) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char c = byte(i);
    if (c < 0x80) return 1;
    const std::size_t n = c >= 0xC2 && c <= 0xDF ? 2 : c >= 0xE0 && c <= 0xEF ? 3 : c >= 0xF0 && c <= 0xF4 ? 4 : 0;
    if (n == 0) return 0;
    unsigned int code = c & (0x7Fu >> n);  // the lead byte's payload
    if (i + n > text.size()) return 0;
    for (std::size_t k = 1; k < n; ++k) {
        if ((byte(i + k) & 0xC0u) != 0x80u) return 0;
        code = (code << 6) | (byte(i + k) & 0x3Fu);
    }
    const bool overlong = (n == 3 && code < 0x800) || (n == 4 && code < 0x10000);
    const bool surrogate = code >= 0xD800 && code <= 0xDFFF;
    const bool c1Control = code >= 0x80 && code <= 0x9F;
    if (overlong || surrogate || c1Control || code > 0x10FFFF) return 0;
    return n;
}

/// The text as valid UTF-8 without control characters: a line break or tab becomes `lineBreak` (or a space), any
/// other control character or invalid byte is dropped.
std::string plainText(const std::string& text, const std::string& lineBreak = " ") {
    std::string out;
    for (std::size_t i = 0; i < text.size();) {
        const char c = text[i];
        if (c == '\n') {
            out += lineBreak;
            ++i;
        } else if (c == '\t' || c == '\r') {
            out += ' ';
            ++i;
        } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) {
            ++i;
        } else if (const std::size_t n = utf8Length(text, i)) {
            out.append(text, i, n);
            i += n;
        } else {
            ++i;
        }
    }
    return out;
}

/// Text for the inside of a DOT double-quoted string. A line break becomes DOT's own "\n" (centred line); a
/// backslash is doubled, so that "\N", "\G", ... in a name are not taken for Graphviz's escapes.
std::string dotEscape(const std::string& text) {
    std::string out;
    for (const char c : plainText(text, "\x01")) {
        if (c == '\x01') out += "\\n";
        else if (c == '\\') out += "\\\\";
        else if (c == '"') out += "\\\"";
        else out += c;
    }
    return out;
}

std::string xmlEscape(const std::string& text) { return simlab::markupEscaped(plainText(text)); }

/// Four significant digits; round-off below `tiny` shows as 0.
std::string number(double value, double tiny = 0) {
    if (!std::isfinite(value)) return std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
    if (std::abs(value) <= tiny || value == 0) return "0";
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", value);
    return text;
}

std::string vector3(const SimTK::Vec3& v, double tiny) {
    return "(" + number(v[0], tiny) + ", " + number(v[1], tiny) + ", " + number(v[2], tiny) + ")";
}

/// A coordinate for SVG: two decimals are a hundredth of a pixel.
std::string px(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", std::isfinite(value) ? value : 0.0);
    return std::strcmp(text, "-0.00") == 0 ? "0.00" : text;
}

// ---- The schematic ------------------------------------------------------------------------------------------

/// Each named body's index, from Model::bodies (the first name in the map's order if a body has two).
std::map<int, std::string> namesByIndex(const Model& model) {
    std::map<int, std::string> names;
    for (const auto& [name, body] : model.bodies) {
        if (body.isEmptyHandle()) continue;
        names.emplace(static_cast<int>(body.getMobilizedBodyIndex()), name);
    }
    return names;
}

/// The unit directions of a mobilizer's motion, as columns of its inboard frame F. Simbody's Pin turns about
/// F's z, the Slider moves along F's x, the Universal turns about F's x then y, the Cylinder and Screw turn about
/// (and slide along) z, the Planar turns about z (and slides in F's xy plane).
std::vector<int> motionAxesInF(const std::string& kind) {
    if (kind == "Pin" || kind == "Cylinder" || kind == "Screw" || kind == "Planar") return {2};
    if (kind == "Slider") return {0};
    if (kind == "Universal") return {0, 1};
    return {};
}

/// The ends of a rod-like decoration (a cylinder's end centres, a line's points) in Ground; nothing for the
/// other shapes. A decoration is a handle: only its own implementGeometry knows which shape it holds.
class RodEnds : public SimTK::DecorativeGeometryImplementation {
public:
    explicit RodEnds(const SimTK::Transform& X_GB) : X_GB_(X_GB) {}
    std::vector<SimTK::Vec3> ends;

    void implementCylinderGeometry(const SimTK::DecorativeCylinder& g) override {
        const SimTK::Transform X_GD = X_GB_ * g.getTransform();
        const SimTK::Vec3 half = X_GD.R() * SimTK::Vec3(0, g.getHalfHeight(), 0);  // a cylinder's axis is D's y
        ends = {X_GD.p() - half, X_GD.p() + half};
    }
    void implementLineGeometry(const SimTK::DecorativeLine& g) override {
        const SimTK::Transform X_GD = X_GB_ * g.getTransform();
        ends = {X_GD * g.getPoint1(), X_GD * g.getPoint2()};
    }
    void implementPointGeometry(const SimTK::DecorativePoint&) override {}
    void implementBrickGeometry(const SimTK::DecorativeBrick&) override {}
    void implementCircleGeometry(const SimTK::DecorativeCircle&) override {}
    void implementSphereGeometry(const SimTK::DecorativeSphere&) override {}
    void implementEllipsoidGeometry(const SimTK::DecorativeEllipsoid&) override {}
    void implementFrameGeometry(const SimTK::DecorativeFrame&) override {}
    void implementTextGeometry(const SimTK::DecorativeText&) override {}
    void implementMeshGeometry(const SimTK::DecorativeMesh&) override {}
    void implementMeshFileGeometry(const SimTK::DecorativeMeshFile&) override {}
    void implementTorusGeometry(const SimTK::DecorativeTorus&) override {}
    void implementArrowGeometry(const SimTK::DecorativeArrow&) override {}
    void implementConeGeometry(const SimTK::DecorativeCone&) override {}

private:
    SimTK::Transform X_GB_;
};

SchematicBody describeBody(const SimTK::SimbodyMatterSubsystem& matter, const SimTK::State& s, int index,
                           const std::map<int, std::string>& names) {
    const SimTK::MobilizedBody& body = matter.getMobilizedBody(SimTK::MobilizedBodyIndex(index));
    const SimTK::MobilizedBody& parent = body.getParentMobilizedBody();
    SchematicBody b;
    const auto named = names.find(index);
    b.name = named != names.end() ? named->second : "body " + std::to_string(index);
    b.index = index;
    b.parent = static_cast<int>(parent.getMobilizedBodyIndex());

    // Simbody keeps the inertia about the body's origin; the schematic shows it about the mass center.
    const SimTK::MassProperties& mp = body.getBodyMassProperties(s);
    b.mass = mp.getMass();
    b.com = mp.getMassCenter();
    const SimTK::Inertia central = mp.calcCentralInertia();
    b.moments = central.getMoments();
    b.products = central.getProducts();

    b.joint = simlab::mobilizerKind(matter, index);
    b.dof = body.getNumU(s);
    // The inboard frame F is fixed on the parent: X_GF = X_GP * X_PF.
    const SimTK::Transform X_GF = parent.getBodyTransform(s) * body.getInboardFrame(s);
    for (const int axis : motionAxesInF(b.joint)) b.axes.push_back(SimTK::Vec3(X_GF.R().col(axis)));
    b.jointLocation = X_GF.p();
    b.origin = body.getBodyOriginLocation(s);
    b.massCenter = body.findMassCenterLocationInGround(s);
    const SimTK::Body& shape = body.getBody();
    for (int k = 0; k < shape.getNumDecorations(); ++k) {
        RodEnds rod(body.getBodyTransform(s));
        shape.getDecoration(k).implementGeometry(rod);
        b.ends.insert(b.ends.end(), rod.ends.begin(), rod.ends.end());
    }
    return b;
}

// ---- The tree in DOT ----------------------------------------------------------------------------------------

std::string nodeLabel(const SchematicBody& b) {
    std::string label = dotEscape(b.name);
    if (b.mass == 0) return label + "\\nmassless";
    label += "\\nm = " + number(b.mass) + " kg";
    // Round-off in the shift to the mass center is not a product of inertia.
    const double scale = std::max({std::abs(b.moments[0]), std::abs(b.moments[1]), std::abs(b.moments[2])});
    const double tiny = 1e-9 * scale;
    label += "\\nI = diag" + vector3(b.moments, tiny) + " kg m²";
    const SimTK::Vec3& p = b.products;
    if (std::abs(p[0]) > tiny || std::abs(p[1]) > tiny || std::abs(p[2]) > tiny) {
        label += "\\nIxy, Ixz, Iyz = " + vector3(p, tiny) + " kg m²";
    }
    return label;
}

std::string edgeLabel(const SchematicBody& b) {
    std::string label = dotEscape(b.joint) + "\\n" + std::to_string(b.dof) + " dof";
    for (std::size_t i = 0; i < b.axes.size(); ++i) {
        label += (i == 0 ? (b.axes.size() == 1 ? "\\naxis " : "\\naxes ") : ", ") + vector3(b.axes[i], 1e-9);
    }
    return label;
}

// ---- The picture ----------------------------------------------------------------------------------------------

// The page: a heading, two panels side by side, a scale bar and a legend under them. Pixels.
constexpr double kPanelWidth = 400, kPanelGap = 20, kSide = 10;
constexpr double kPanelTop = 34, kPanelHeight = 360, kPlotMargin = 40, kTitleHeight = 26;
constexpr double kPageWidth = 2 * kSide + 2 * kPanelWidth + kPanelGap, kPageHeight = 460;

/// An orthographic view: which Ground coordinates go right and up on the page.
struct View {
    std::string title;
    SimTK::Vec3 right, up;
};

const View kViews[2] = {{"front: x right, y up", {1, 0, 0}, {0, 1, 0}},  // looking along -z
                        {"side: z left, y up", {0, 0, -1}, {0, 1, 0}}};  // looking along -x

SimTK::Vec3 finite(const SimTK::Vec3& v) {
    SimTK::Vec3 out;
    for (int i = 0; i < 3; ++i) out[i] = std::isfinite(v[i]) ? v[i] : 0.0;
    return out;
}

/// Meters to page pixels: one scale for both views, so that their heights (both y) agree.
struct Frame {
    double scale = 1;   ///< px per m
    SimTK::Vec3 center;  ///< m, the middle of the points' bounding box

    /// The point as seen in `view`, on the panel whose left edge is `left`.
    std::pair<double, double> page(const View& view, double left, const SimTK::Vec3& p) const {
        const SimTK::Vec3 d = finite(p) - center;
        const double middleX = left + kPanelWidth / 2;
        const double middleY = kPanelTop + kTitleHeight + (kPanelHeight - kTitleHeight) / 2;
        return {middleX + scale * SimTK::dot(d, view.right), middleY - scale * SimTK::dot(d, view.up)};
    }
};

Frame fitFrame(const Schematic& schematic) {
    SimTK::Vec3 low(0), high(0);
    bool any = false;
    for (const SchematicBody& b : schematic.bodies) {
        std::vector<SimTK::Vec3> points = {b.jointLocation, b.origin, b.massCenter};
        points.insert(points.end(), b.ends.begin(), b.ends.end());
        for (const SimTK::Vec3& p : points) {
            const SimTK::Vec3 q = finite(p);
            for (int i = 0; i < 3; ++i) {
                low[i] = any ? std::min(low[i], q[i]) : q[i];
                high[i] = any ? std::max(high[i], q[i]) : q[i];
            }
            any = true;
        }
    }
    Frame frame;
    frame.center = (low + high) / 2;
    SimTK::Vec3 span = high - low;
    // All points at one spot (or none): show a 1 m box around it.
    if (std::max({span[0], span[1], span[2]}) < 1e-9) span = SimTK::Vec3(1);
    const double tiny = 1e-6 * std::max({span[0], span[1], span[2]});
    const double width = kPanelWidth - 2 * kPlotMargin;
    const double height = kPanelHeight - kTitleHeight - 2 * kPlotMargin;
    frame.scale = std::min(width / std::max({span[0], span[2], tiny}), height / std::max(span[1], tiny));
    return frame;
}

/// The largest 1, 2 or 5 times a power of ten not longer than `meters`.
double roundLength(double meters) {
    const double decade = std::pow(10.0, std::floor(std::log10(meters)));
    for (const double step : {5.0, 2.0, 1.0}) {
        if (step * decade <= meters * (1 + 1e-12)) return step * decade;
    }
    return decade;
}

/// A disk's radius in px: its area grows with the mass, between 2.5 and 10 px.
double diskRadius(double mass, double heaviest) {
    if (!(mass > 0) || !(heaviest > 0)) return 2.5;
    return std::clamp(10 * std::sqrt(mass / heaviest), 2.5, 10.0);
}

void line(std::ostringstream& svg, std::pair<double, double> a, std::pair<double, double> b,
          const char* style = "stroke=\"#555\" stroke-width=\"2\"") {
    svg << "<line x1=\"" << px(a.first) << "\" y1=\"" << px(a.second) << "\" x2=\"" << px(b.first) << "\" y2=\""
        << px(b.second) << "\" " << style << "/>\n";
}

void text(std::ostringstream& svg, double x, double y, const std::string& content, const char* extra = "") {
    svg << "<text x=\"" << px(x) << "\" y=\"" << px(y) << "\"" << extra << ">" << xmlEscape(content)
        << "</text>\n";
}

/// A ground support: a triangle with its apex at the joint and hatching along its base, on the side away from
/// the body (above a hanging pendulum, below a standing one). `away` is +1 for below, -1 for above.
void groundMark(std::ostringstream& svg, std::pair<double, double> at, double away) {
    const auto [x, y] = at;
    svg << "<path d=\"M" << px(x) << " " << px(y + away * 5) << " L" << px(x - 8) << " " << px(y + away * 15)
        << " L" << px(x + 8) << " " << px(y + away * 15) << " Z\" fill=\"#ddd\" stroke=\"#000\"/>\n";
    for (int k = 0; k < 4; ++k) {
        const double x0 = x - 10 + 5 * k;
        line(svg, {x0 + 4, y + away * 15}, {x0, y + away * 20}, "stroke=\"#000\" stroke-width=\"1\"");
    }
}

/// A Slider: a sleeve (a small rectangle) on a rail along its axis, the rail hatched on the side away from the body
/// when it is fixed to the ground. `along` is a point one metre along the axis from `at`, on the page; an axis seen
/// end on (along this view) draws the sleeve square, with no rail.
void sliderMark(std::ostringstream& svg, std::pair<double, double> at, std::pair<double, double> along, bool ground,
                double away) {
    const auto [x, y] = at;
    double dx = along.first - x, dy = along.second - y;
    const double length = std::hypot(dx, dy);
    if (!(length > 1e-9)) {
        svg << "<rect x=\"" << px(x - 5) << "\" y=\"" << px(y - 5) << "\" width=\"10\" height=\"10\" fill=\"#fff\" "
            << "stroke=\"#000\" stroke-width=\"1.5\"/>\n";
        return;
    }
    dx /= length;
    dy /= length;
    const double nx = -dy, ny = dx;  // across the rail
    line(svg, {x - 24 * dx, y - 24 * dy}, {x + 24 * dx, y + 24 * dy}, "stroke=\"#000\" stroke-width=\"1.5\"");
    if (ground) {
        const double side = ny * away >= 0 ? 1 : -1;  // the hatching goes on the side away from the body
        for (int k = 0; k < 5; ++k) {
            const double t = -20 + 10 * k;
            line(svg, {x + t * dx, y + t * dy}, {x + t * dx + side * 6 * nx - 4 * dx, y + t * dy + side * 6 * ny - 4 * dy},
                 "stroke=\"#000\" stroke-width=\"1\"");
        }
    }
    svg << "<path d=\"M" << px(x - 8 * dx - 5 * nx) << " " << px(y - 8 * dy - 5 * ny) << " L" << px(x + 8 * dx - 5 * nx)
        << " " << px(y + 8 * dy - 5 * ny) << " L" << px(x + 8 * dx + 5 * nx) << " " << px(y + 8 * dy + 5 * ny) << " L"
        << px(x - 8 * dx + 5 * nx) << " " << px(y - 8 * dy + 5 * ny) << " Z\" fill=\"#fff\" stroke=\"#000\" "
        << "stroke-width=\"1.5\"/>\n";
}

void drawPanel(std::ostringstream& svg, const Schematic& schematic, const View& view, double left,
               const Frame& frame) {
    svg << "<rect x=\"" << px(left) << "\" y=\"" << px(kPanelTop) << "\" width=\"" << px(kPanelWidth)
        << "\" height=\"" << px(kPanelHeight) << "\" fill=\"none\" stroke=\"#bbb\"/>\n";
    text(svg, left + kPanelWidth / 2, kPanelTop + 18, view.title, " text-anchor=\"middle\" font-weight=\"bold\"");
    const auto at = [&](const SimTK::Vec3& p) { return frame.page(view, left, p); };
    // The links: a body from its joint to its mass center, and on from there to the joints it carries and to the
    // ends of the rods it is drawn with.
    for (const SchematicBody& b : schematic.bodies) {
        line(svg, at(b.jointLocation), at(b.massCenter));
        for (const SchematicBody& child : schematic.bodies) {
            if (child.parent == b.index) line(svg, at(b.massCenter), at(child.jointLocation));
        }
        for (const SimTK::Vec3& end : b.ends) line(svg, at(b.massCenter), at(end));
    }
    double heaviest = 0;
    for (const SchematicBody& b : schematic.bodies) heaviest = std::max(heaviest, b.mass);
    for (const SchematicBody& b : schematic.bodies) {
        const auto origin = at(b.origin);
        line(svg, {origin.first - 3, origin.second - 3}, {origin.first + 3, origin.second + 3},
             "stroke=\"#08c\" stroke-width=\"1\"");
        line(svg, {origin.first - 3, origin.second + 3}, {origin.first + 3, origin.second - 3},
             "stroke=\"#08c\" stroke-width=\"1\"");
        const auto joint = at(b.jointLocation);
        const double away = at(b.massCenter).second > joint.second + 0.5 ? -1 : 1;
        if (b.joint == "Slider" && !b.axes.empty()) {
            sliderMark(svg, joint, at(b.jointLocation + b.axes.front()), b.parent == 0, away);
            continue;
        }
        if (b.parent == 0) groundMark(svg, joint, away);
        svg << "<circle cx=\"" << px(joint.first) << "\" cy=\"" << px(joint.second)
            << "\" r=\"5\" fill=\"#fff\" stroke=\"#000\" stroke-width=\"1.5\"/>\n";
    }
    // Labels beside their disks; one that would cover a label already placed (mass centers that coincide in this
    // view) goes a line further down, so that every name can be read.
    struct Placed {
        double x, y, width;
    };
    std::vector<Placed> placed;
    for (const SchematicBody& b : schematic.bodies) {
        const auto center = at(b.massCenter);
        const double r = diskRadius(b.mass, heaviest);
        svg << "<circle cx=\"" << px(center.first) << "\" cy=\"" << px(center.second) << "\" r=\"" << px(r)
            << "\" fill=\"" << (b.mass > 0 ? "#c33" : "#999") << "\"/>\n";
        double x = center.first + r + 4, y = center.second - r - 2;
        const double width = 7.5 * static_cast<double>(b.name.size());  // px, about the text's at 12 px
        for (bool moved = true; moved;) {
            moved = false;
            for (const Placed& other : placed) {
                if (std::abs(y - other.y) < 14 && x < other.x + other.width && other.x < x + width) {
                    y = other.y + 14;
                    moved = true;
                }
            }
        }
        placed.push_back({x, y, width});
        text(svg, x, y, b.name);
    }
}

void drawScaleBar(std::ostringstream& svg, const Frame& frame) {
    const double length = roundLength(120 / frame.scale);  // about a hundred pixels
    const double x = kSide + 10, y = kPanelTop + kPanelHeight + 30, w = length * frame.scale;
    line(svg, {x, y}, {x + w, y}, "stroke=\"#000\" stroke-width=\"2\"");
    line(svg, {x, y - 5}, {x, y + 5}, "stroke=\"#000\" stroke-width=\"2\"");
    line(svg, {x + w, y - 5}, {x + w, y + 5}, "stroke=\"#000\" stroke-width=\"2\"");
    char label[32];
    std::snprintf(label, sizeof label, "%g m", length);
    text(svg, x + w + 8, y + 4, label);
}

void drawLegend(std::ostringstream& svg) {
    const double y = kPageHeight - 18, x = kPageWidth / 2 - 60;
    svg << "<circle cx=\"" << px(x) << "\" cy=\"" << px(y - 4) << "\" r=\"5\" fill=\"#fff\" stroke=\"#000\"/>\n";
    text(svg, x + 10, y, "joint");
    svg << "<circle cx=\"" << px(x + 70) << "\" cy=\"" << px(y - 4) << "\" r=\"5\" fill=\"#c33\"/>\n";
    text(svg, x + 80, y, "mass center (area grows with mass)");
    line(svg, {x + 310, y - 7}, {x + 316, y - 1}, "stroke=\"#08c\" stroke-width=\"1\"");
    line(svg, {x + 310, y - 1}, {x + 316, y - 7}, "stroke=\"#08c\" stroke-width=\"1\"");
    text(svg, x + 322, y, "body origin");
}

// ---- Running dot ----------------------------------------------------------------------------------------------

constexpr std::size_t kMaxOutput = 8u << 20;  // bytes of SVG
constexpr int kTimeLimit = 60;                 // s

[[noreturn]] void fail(const std::string& what) { throw std::runtime_error(plainText(what)); }

}  // namespace

Schematic schematicOf(const Model& model, const SimTK::State& state, const std::string& title) {
    // A copy, realized to Position: the caller's state stays as it was.
    SimTK::State s = state;
    model.system.realize(s, SimTK::Stage::Position);
    const simlab::ModelInfo info = simlab::describeModel(model.matter, s);
    Schematic schematic;
    schematic.title = title;
    schematic.degreesOfFreedom = info.degreesOfFreedom();
    schematic.constraints = info.constraintEquations;
    const std::map<int, std::string> names = namesByIndex(model);
    for (int i = 1; i < model.matter.getNumBodies(); ++i) {
        schematic.bodies.push_back(describeBody(model.matter, s, i, names));
    }
    return schematic;
}

std::string treeDot(const Schematic& schematic) {
    std::ostringstream dot;
    const int n = schematic.degreesOfFreedom;
    std::string graphLabel = dotEscape(schematic.title) + "\\n" + std::to_string(n) +
                             (n == 1 ? " degree" : " degrees") + " of freedom";
    if (schematic.constraints > 0) {
        graphLabel += ", " + std::to_string(schematic.constraints) + " constraint equations";
    }
    dot << "digraph \"tree\" {\n"
        << "  graph [label=\"" << graphLabel << "\", labelloc=\"t\", fontname=\"Helvetica\"];\n"
        << "  node [shape=\"box\", style=\"rounded\", fontname=\"Helvetica\", fontsize=\"11\"];\n"
        << "  edge [fontname=\"Helvetica\", fontsize=\"10\"];\n"
        << "  \"n0\" [label=\"Ground\", shape=\"box\", style=\"filled\", fillcolor=\"#dddddd\"];\n";
    for (const SchematicBody& b : schematic.bodies) {
        dot << "  \"n" << b.index << "\" [label=\"" << nodeLabel(b) << "\"];\n";
    }
    for (const SchematicBody& b : schematic.bodies) {
        dot << "  \"n" << b.parent << "\" -> \"n" << b.index << "\" [label=\"" << edgeLabel(b) << "\"];\n";
    }
    dot << "}\n";
    return dot.str();
}

std::string pictureSvg(const Schematic& schematic) {
    const Frame frame = fitFrame(schematic);
    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << px(kPageWidth)
        << "\" height=\"" << px(kPageHeight) << "\" viewBox=\"0 0 " << px(kPageWidth) << " " << px(kPageHeight)
        << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
        << "<title>" << xmlEscape(schematic.title) << "</title>\n"
        << "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
    text(svg, kPageWidth / 2, 22, schematic.title + " at t = 0", " text-anchor=\"middle\" font-size=\"14\"");
    for (int v = 0; v < 2; ++v) drawPanel(svg, schematic, kViews[v], kSide + v * (kPanelWidth + kPanelGap), frame);
    drawScaleBar(svg, frame);
    drawLegend(svg);
    svg << "</svg>\n";
    return svg.str();
}

std::string renderSvg(const std::string& dot) {
    simlab::SystemToolRun run;
    try {
        run = simlab::runSystemTool({"dot", "-Tsvg"}, dot, kTimeLimit, kMaxOutput);
    } catch (const simlab::SystemToolMissing&) {
        fail("Graphviz's dot is not installed; run scripts/install-deps");
    } catch (const std::runtime_error& e) {
        fail(e.what());  // "dot failed: ..."
    }
    if (!run.succeeded()) fail("dot failed: " + run.reason());
    if (run.output.empty()) fail("dot failed: it wrote nothing");
    return run.output;
}

}  // namespace biosim
