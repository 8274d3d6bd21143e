#include "simlab/replay.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "Simbody.h"
#include "simlab/messages.h"

#ifndef SIMLAB_THREE_JS
#define SIMLAB_THREE_JS "/usr/share/javascript/three/three.min.js"
#endif

namespace simlab {

namespace {

constexpr std::size_t kMostChartRows = 5000;  // a longer time series is thinned for the chart
constexpr double kNegligiblePose = 1e-9;       // m, and quaternion components: written as 0

/// `v` in JSON with `digits` significant digits: "null" when it is not finite, "0" when |v| < `zeroBelow`, and
/// exponents without padding ("1.5e-5").
std::string number(double v, int digits = 6, double zeroBelow = 0) {
    if (!std::isfinite(v)) return "null";
    if (std::abs(v) < zeroBelow || v == 0) return "0";
    char text[40];
    std::snprintf(text, sizeof text, "%.*g", digits, v);
    std::string s = text;
    const std::size_t e = s.find('e');
    if (e == std::string::npos) return s;
    std::string exponent = s.substr(e + 1);
    const bool negative = exponent[0] == '-';
    exponent.erase(0, exponent.find_first_not_of("+-0"));
    return s.substr(0, e + 1) + (negative ? "-" : "") + (exponent.empty() ? "0" : exponent);
}

std::string vec3(const SimTK::Vec3& v, double zeroBelow = 0) {
    return "[" + number(v[0], 6, zeroBelow) + "," + number(v[1], 6, zeroBelow) + "," +
           number(v[2], 6, zeroBelow) + "]";
}

/// A JSON string. '<', '>' and '&' are escaped too, so that the text can never close the <script> it is in.
std::string jsonString(const std::string& text) {
    std::string out = "\"";
    for (const char c : text) {
        const unsigned char u = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (u < 0x20 || c == '<' || c == '>' || c == '&') {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\u%04x", u);
            out += escaped;
        } else {
            out += c;
        }
    }
    return out + "\"";
}

/// A script's text made safe to inline: "</script" cannot occur in it (inside a JavaScript string or regular
/// expression, "<\/" means the same as "</").
std::string inlineScript(std::string text) {
    for (std::size_t at = 0; (at = text.find("</", at)) != std::string::npos; at += 3) {
        std::string next = text.substr(at + 2, 6);
        std::transform(next.begin(), next.end(), next.begin(), [](unsigned char c) { return std::tolower(c); });
        if (next == "script") text.insert(at + 1, "\\");
    }
    return text;
}

/// The whole of a file, or "" with `found` false when it cannot be read.
std::string readFile(const std::string& path, bool& found) {
    std::ifstream in(path, std::ios::binary);
    found = static_cast<bool>(in);
    if (!found) return "";
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/// One decoration as the page draws it, in the decoration's own frame D: "k", its kind, and its dimensions. Left
/// empty for what the page cannot draw (text, a mesh file that does not load).
class ShapeJson : public SimTK::DecorativeGeometryImplementation {
public:
    std::string json;

    void implementPointGeometry(const SimTK::DecorativePoint& g) override {
        json = "\"k\":\"point\",\"a\":" + vec3(g.getPoint());
    }
    void implementLineGeometry(const SimTK::DecorativeLine& g) override {
        json = "\"k\":\"line\",\"a\":" + vec3(g.getPoint1()) + ",\"e\":" + vec3(g.getPoint2());
    }
    void implementBrickGeometry(const SimTK::DecorativeBrick& g) override {
        json = "\"k\":\"brick\",\"h\":" + vec3(g.getHalfLengths());
    }
    void implementCylinderGeometry(const SimTK::DecorativeCylinder& g) override {
        json = "\"k\":\"cylinder\",\"r\":" + number(g.getRadius()) + ",\"h\":" + number(g.getHalfHeight());
    }
    void implementCircleGeometry(const SimTK::DecorativeCircle& g) override {
        json = "\"k\":\"circle\",\"r\":" + number(g.getRadius());
    }
    void implementSphereGeometry(const SimTK::DecorativeSphere& g) override {
        json = "\"k\":\"sphere\",\"r\":" + number(g.getRadius());
    }
    void implementEllipsoidGeometry(const SimTK::DecorativeEllipsoid& g) override {
        json = "\"k\":\"ellipsoid\",\"r\":" + vec3(g.getRadii());
    }
    void implementFrameGeometry(const SimTK::DecorativeFrame& g) override {
        json = "\"k\":\"frame\",\"l\":" + number(g.getAxisLength());
    }
    void implementTextGeometry(const SimTK::DecorativeText&) override { json.clear(); }
    void implementMeshGeometry(const SimTK::DecorativeMesh& g) override { mesh(g.getMesh()); }
    void implementMeshFileGeometry(const SimTK::DecorativeMeshFile& g) override {
        try {
            mesh(g.getMesh());
        } catch (const std::exception&) {
            json.clear();
        }
    }
    void implementTorusGeometry(const SimTK::DecorativeTorus& g) override {
        json = "\"k\":\"torus\",\"r\":" + number(g.getTorusRadius()) + ",\"t\":" + number(g.getTubeRadius());
    }
    void implementArrowGeometry(const SimTK::DecorativeArrow& g) override {
        json = "\"k\":\"arrow\",\"a\":" + vec3(g.getStartPoint()) + ",\"e\":" + vec3(g.getEndPoint()) +
               ",\"tip\":" + number(g.getTipLength());
    }
    void implementConeGeometry(const SimTK::DecorativeCone& g) override {
        json = "\"k\":\"cone\",\"a\":" + vec3(g.getOrigin()) + ",\"d\":" + vec3(g.getDirection()) +
               ",\"h\":" + number(g.getHeight()) + ",\"r\":" + number(g.getBaseRadius());
    }

private:
    // Vertices, and each face as a fan of triangles.
    void mesh(const SimTK::PolygonalMesh& m) {
        std::string vertices, triangles;
        for (int v = 0; v < m.getNumVertices(); ++v) {
            const SimTK::Vec3& p = m.getVertexPosition(v);
            for (int i = 0; i < 3; ++i) vertices += (vertices.empty() ? "" : ",") + number(p[i]);
        }
        for (int f = 0; f < m.getNumFaces(); ++f) {
            for (int i = 2; i < m.getNumVerticesForFace(f); ++i) {
                for (const int corner : {0, i - 1, i}) {
                    triangles += (triangles.empty() ? "" : ",") + std::to_string(m.getFaceVertex(f, corner));
                }
            }
        }
        json = "\"k\":\"mesh\",\"v\":[" + vertices + "],\"f\":[" + triangles + "]";
    }
};

/// A decoration with where it goes: "b", the mobilized body it is fixed to (0: Ground); "T", X_BD as p_BD and
/// the quaternion of R_BD (x, y, z, w; left out when X_BD is the identity); "s", its scale factors (left out when
/// all are 1); "c", its color (left out for the default); "o", its opacity (left out when opaque); "w", "wire" or
/// "points" for those representations. Empty when the page does not draw it.
std::string shapeJson(const SimTK::DecorativeGeometry& geometry, int body) {
    if (geometry.getRepresentation() == SimTK::DecorativeGeometry::Hide) return "";
    ShapeJson shape;
    geometry.implementGeometry(shape);
    if (shape.json.empty()) return "";
    std::string json = "{\"b\":" + std::to_string(body) + "," + shape.json;
    const SimTK::Transform& X_BD = geometry.getTransform();
    const SimTK::Quaternion q_BD = X_BD.R().convertRotationToQuaternion();
    if (X_BD.p().norm() > 0 || std::abs(q_BD[0]) < 1) {
        json += ",\"T\":[" + number(X_BD.p()[0]) + "," + number(X_BD.p()[1]) + "," + number(X_BD.p()[2]) + "," +
                number(q_BD[1], 6, kNegligiblePose) + "," + number(q_BD[2], 6, kNegligiblePose) + "," +
                number(q_BD[3], 6, kNegligiblePose) + "," + number(q_BD[0], 6, kNegligiblePose) + "]";
    }
    SimTK::Vec3 scale = geometry.getScaleFactors();
    for (int i = 0; i < 3; ++i) scale[i] = scale[i] <= 0 ? 1 : scale[i];  // <= 0: the default, 1
    if (scale != SimTK::Vec3(1)) json += ",\"s\":" + vec3(scale);
    const SimTK::Vec3& color = geometry.getColor();
    if (color[0] >= 0) {
        SimTK::Vec3 rgb;
        for (int i = 0; i < 3; ++i) rgb[i] = std::min(1.0, std::max(0.0, color[i]));
        json += ",\"c\":" + vec3(rgb);
    }
    const double opacity = geometry.getOpacity();
    if (opacity >= 0 && opacity < 1) json += ",\"o\":" + number(opacity, 3);
    if (geometry.getRepresentation() == SimTK::DecorativeGeometry::DrawWireframe) json += ",\"w\":\"wire\"";
    if (geometry.getRepresentation() == SimTK::DecorativeGeometry::DrawPoints) json += ",\"w\":\"points\"";
    return json + "}";
}

/// A figure in the page's words: 4 significant digits, no "-0".
std::string figure(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", v == 0 ? 0.0 : v);
    return text;
}

/// A coordinate of a pose in the page's words: 0 where the recording writes 0 (kNegligiblePose).
std::string coordinate(double v) { return figure(std::abs(v) < kNegligiblePose ? 0.0 : v); }

std::string point(const double* p) {
    return "(" + coordinate(p[0]) + ", " + coordinate(p[1]) + ", " + coordinate(p[2]) + ")";
}

}  // namespace

struct ReplayRecorder::Recording {
    double frameInterval = 0;            // s
    bool shapesRead = false;
    std::vector<std::string> shapes;     // one JSON object each (see shapeJson)
    int skipped = 0;                     // decorations the page cannot draw
    int bodies = 0;                      // mobilized bodies other than Ground
    std::vector<bool> massless;          // per body: no mass (a device of the joints, such as a slider), not drawn
    std::vector<std::string> looks;      // per body: the kinds of its decorations ("brick", "sphere and line")
    std::vector<double> times;           // s, one per frame
    std::vector<double> poses;           // per frame and body: p_GB (3 values), then R_GB's quaternion (x, y, z, w)
};

class ReplayRecorder::Reporter : public SimTK::PeriodicEventReporter {
public:
    Reporter(const SimTK::MultibodySystem& system, std::shared_ptr<Recording> recording)
        : SimTK::PeriodicEventReporter(recording->frameInterval), system_(system), recording_(std::move(recording)) {}

    void handleEvent(const SimTK::State& state) const override {
        Recording& r = *recording_;
        const SimTK::SimbodyMatterSubsystem& matter = system_.getMatterSubsystem();
        if (!r.shapesRead) readShapes(state, r);
        const double t = state.getTime();
        if (!r.times.empty() && t < r.times.back()) {  // a new run
            r.times.clear();
            r.poses.clear();
        }
        if (!r.times.empty() && t == r.times.back()) {  // the same instant again: keep the later state
            r.times.pop_back();
            r.poses.resize(r.poses.size() - 7 * static_cast<std::size_t>(r.bodies));
        }
        const bool hasPrevious = !r.times.empty();
        const std::size_t previous = hasPrevious ? r.poses.size() - 7 * static_cast<std::size_t>(r.bodies) : 0;
        r.times.push_back(t);
        for (SimTK::MobilizedBodyIndex b(1); b < matter.getNumBodies(); ++b) {
            const SimTK::Transform& X_GB = matter.getMobilizedBody(b).getBodyTransform(state);
            const SimTK::Quaternion q_GB = X_GB.R().convertRotationToQuaternion();
            // q and -q are the same rotation: take the one nearer the last frame's, so that the page's
            // interpolation between frames turns the short way.
            double sign = 1;
            if (hasPrevious) {
                const double* last = &r.poses[previous + 7 * (b - 1) + 3];
                if (last[0] * q_GB[1] + last[1] * q_GB[2] + last[2] * q_GB[3] + last[3] * q_GB[0] < 0) sign = -1;
            }
            for (int i = 0; i < 3; ++i) r.poses.push_back(X_GB.p()[i]);
            for (const int i : {1, 2, 3, 0}) r.poses.push_back(sign * q_GB[i]);
        }
    }

private:
    // What every body looks like, from the decorations the system holds from its topology on: those of each
    // Body and its mobilizer, and those a DecorationSubsystem fixes to a body.
    void readShapes(const SimTK::State& state, Recording& r) const {
        const SimTK::SimbodyMatterSubsystem& matter = system_.getMatterSubsystem();
        r.bodies = matter.getNumBodies() - 1;
        r.massless.clear();
        r.looks.assign(static_cast<std::size_t>(r.bodies), "");
        for (int b = 1; b <= r.bodies; ++b) {
            r.massless.push_back(matter.getMobilizedBody(SimTK::MobilizedBodyIndex(b)).getBodyMass(state) == 0);
        }
        SimTK::Array_<SimTK::DecorativeGeometry> geometry;
        system_.calcDecorativeGeometryAndAppend(state, SimTK::Stage::Topology, geometry);
        for (const SimTK::DecorativeGeometry& g : geometry) {
            const int body = g.getBodyId();
            if (body < 0 || body > r.bodies) continue;
            const std::string json = shapeJson(g, body);
            if (json.empty()) {
                if (g.getRepresentation() != SimTK::DecorativeGeometry::Hide) ++r.skipped;
            } else {
                r.shapes.push_back(json);
                // Its kind, as shapeJson wrote it ("k":"brick").
                const std::size_t k = json.find("\"k\":\"") + 5;
                const std::string kind = json.substr(k, json.find('"', k) - k);
                if (body > 0) {
                    std::string& looks = r.looks[static_cast<std::size_t>(body - 1)];
                    if (looks.find(kind) == std::string::npos) looks += (looks.empty() ? "" : " and ") + kind;
                }
            }
        }
        r.shapesRead = true;
    }

    const SimTK::MultibodySystem& system_;  // owns this reporter
    std::shared_ptr<Recording> recording_;
};

namespace {

/// The motion in words, for a reader who cannot see the 3-D view: over which times, and for each body drawn where
/// its origin starts and ends, the box it stays in, and how far it turns in all.
std::string motionInWords(const std::vector<double>& times, const std::vector<double>& poses, int bodies,
                          const std::vector<bool>& massless, const std::vector<std::string>& looks) {
    const std::size_t frames = times.size(), perFrame = 7 * static_cast<std::size_t>(bodies);
    std::string text = "From t = " + figure(times.front()) + " s to t = " + figure(times.back()) + " s, " +
                       std::to_string(frames) + (frames == 1 ? " frame" : " frames") + ".";
    int shown = 0;
    for (int b = 0; b < bodies; ++b) {
        if (massless[static_cast<std::size_t>(b)]) continue;
        ++shown;
        double low[3] = {INFINITY, INFINITY, INFINITY}, high[3] = {-INFINITY, -INFINITY, -INFINITY}, turned = 0;
        for (std::size_t f = 0; f < frames; ++f) {
            const double* pose = &poses[f * perFrame + 7 * static_cast<std::size_t>(b)];
            for (int i = 0; i < 3; ++i) low[i] = std::min(low[i], pose[i]), high[i] = std::max(high[i], pose[i]);
            if (f > 0) {  // the angle between this frame's attitude and the last one's
                const double* last = pose - perFrame;
                double dot = 0;
                for (int i = 3; i < 7; ++i) dot += last[i] * pose[i];
                turned += 2 * std::acos(std::min(1.0, std::abs(dot)));
            }
        }
        const double* first = &poses[7 * static_cast<std::size_t>(b)];
        const double* end = &poses[(frames - 1) * perFrame + 7 * static_cast<std::size_t>(b)];
        const std::string& look = looks[static_cast<std::size_t>(b)];
        const bool vowel = !look.empty() && std::string("aeiou").find(look[0]) != std::string::npos;
        text += " Body " + std::to_string(b + 1) + " (" +
                (look.empty() ? "drawn as a small sphere" : (vowel ? "an " : "a ") + look) + "): ";
        std::string within;
        for (int i = 0; i < 3; ++i) {
            if (coordinate(low[i]) != coordinate(high[i])) {
                within += std::string(within.empty() ? "" : ", ") + "xyz"[i] + " " + coordinate(low[i]) + " to " +
                          coordinate(high[i]);
            }
        }
        text += within.empty() ? "its origin stays at " + point(first) + " m"
                               : "its origin goes from " + point(first) + " m to " + point(end) + " m, within " +
                                     within + " m";
        const double degrees = turned * 180 / SimTK::Pi;
        text += degrees < 0.05 ? "; it does not turn."
                               : "; it turns through " + figure(degrees) + " degrees in all" +
                                     (degrees >= 360 ? " (" + figure(degrees / 360) + " turns)." : ".");
    }
    if (shown == 0) text += " No body is drawn.";
    return text;
}

}  // namespace

ReplayRecorder::ReplayRecorder(SimTK::MultibodySystem& system, double frameInterval)
    : recording_(std::make_shared<Recording>()) {
    if (!(frameInterval > 0) || !std::isfinite(frameInterval)) {
        throw std::invalid_argument("the replay's frame interval must be a positive number of seconds, not " +
                                    number(frameInterval));
    }
    recording_->frameInterval = frameInterval;
    system.addEventReporter(new Reporter(system, recording_));  // the system adopts it
}

std::size_t ReplayRecorder::frames() const { return recording_->times.size(); }

namespace {

// The page's style sheet and script (assets/replay.css and assets/replay.js), at the end of this file.
extern const char* const kStyle;
extern const char* const kScript;

}  // namespace

void ReplayRecorder::write(const std::string& path, const std::string& title, const std::vector<std::string>& columns,
                           const std::vector<std::vector<double>>& rows) const {
    bool found = false;
    const std::string threeJs = readFile(SIMLAB_THREE_JS, found);
    if (!found) {
        throw std::runtime_error(
            "--replay needs three.js from Debian's libjs-three (scripts/install-deps installs it)");
    }
    const std::string threeDir = std::string(SIMLAB_THREE_JS).substr(0, std::string(SIMLAB_THREE_JS).rfind('/'));
    const std::string orbitControls = readFile(threeDir + "/examples/js/controls/OrbitControls.js", found);
    for (const std::vector<double>& row : rows) {
        if (row.size() != columns.size()) {
            throw std::invalid_argument("a replay row has " + std::to_string(row.size()) + " values for " +
                                        std::to_string(columns.size()) + " columns");
        }
    }
    const Recording& r = *recording_;
    if (r.times.empty()) {
        throw std::runtime_error("the replay recorded no frames (did a TimeStepper run the system?)");
    }

    std::string data = "{\"dt\":" + number(r.frameInterval, 7) + ",\"t\":[";
    for (std::size_t f = 0; f < r.times.size(); ++f) data += (f ? "," : "") + number(r.times[f], 7);
    data += "],\"bodies\":[";
    const std::size_t perFrame = 7 * static_cast<std::size_t>(r.bodies);
    for (int b = 0; b < r.bodies; ++b) {
        std::string p, q;
        for (std::size_t f = 0; f < r.times.size(); ++f) {
            const double* pose = &r.poses[f * perFrame + 7 * static_cast<std::size_t>(b)];
            for (int i = 0; i < 3; ++i) p += (p.empty() ? "" : ",") + number(pose[i], 6, kNegligiblePose);
            for (int i = 3; i < 7; ++i) q += (q.empty() ? "" : ",") + number(pose[i], 6, kNegligiblePose);
        }
        data += std::string(b ? "," : "") + "{\"p\":[" + p + "],\"q\":[" + q + "]" +
                (r.massless[static_cast<std::size_t>(b)] ? ",\"massless\":true" : "") + "}";
    }
    data += "],\"shapes\":[";
    for (std::size_t s = 0; s < r.shapes.size(); ++s) data += (s ? ",\n" : "\n") + r.shapes[s];
    data += "],\"skipped\":" + std::to_string(r.skipped);
    data += ",\"series\":{\"names\":[";
    for (std::size_t c = 0; c < columns.size(); ++c) data += (c ? "," : "") + jsonString(columns[c]);
    data += "],\"values\":[";
    const std::size_t stride = (rows.size() + kMostChartRows - 1) / kMostChartRows;
    for (std::size_t c = 0; c < columns.size(); ++c) {
        data += c ? ",\n[" : "\n[";
        for (std::size_t i = 0; i < rows.size(); i += stride) {
            // Thinned, the series still ends with the last row.
            const std::size_t row = i + stride >= rows.size() ? rows.size() - 1 : i;
            data += (i ? "," : "") + number(rows[row][c]);
            if (row == rows.size() - 1) break;
        }
        data += "]";
    }
    data += "]}}";

    const std::string heading = markupEscaped(title);
    std::string html;
    html.reserve(threeJs.size() + orbitControls.size() + data.size() + 32768);
    html += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
            "<title>" + heading + "</title>\n<link rel=\"icon\" href=\"data:,\">\n<style>\n";
    html += kStyle;
    // Every control works from the keyboard (the 3-D view too, once focused), and what the view and the chart show
    // is also said in words and given as a table, below them.
    html += "</style>\n</head>\n<body>\n<header>\n<h1>" + heading + "</h1>\n<div class=\"controls\">\n"
            "<button id=\"play\" type=\"button\">Play</button>\n"
            "<label>Speed <select id=\"speed\"><option value=\"0.25\">0.25&times;</option>"
            "<option value=\"0.5\">0.5&times;</option><option value=\"1\" selected>1&times;</option>"
            "<option value=\"2\">2&times;</option><option value=\"4\">4&times;</option></select></label>\n"
            "<input id=\"time\" type=\"range\" min=\"0\" max=\"1\" step=\"any\" value=\"0\" aria-label=\"time\">\n"
            "<output id=\"now\" aria-live=\"off\">t = 0 s</output>\n</div>\n</header>\n<main>\n"
            "<section id=\"view\" tabindex=\"0\" aria-label=\"the bodies' motion in 3-D\" "
            "aria-describedby=\"view-note motion\"><p id=\"view-note\"></p>\n"
            "<div id=\"view-turn\" role=\"group\" aria-label=\"turn and zoom the view\" hidden>"
            "<button type=\"button\" data-key=\"ArrowLeft\" aria-label=\"turn left\">&larr;</button>"
            "<button type=\"button\" data-key=\"ArrowRight\" aria-label=\"turn right\">&rarr;</button>"
            "<button type=\"button\" data-key=\"ArrowUp\" aria-label=\"turn up\">&uarr;</button>"
            "<button type=\"button\" data-key=\"ArrowDown\" aria-label=\"turn down\">&darr;</button>"
            "<button type=\"button\" data-key=\"+\" aria-label=\"zoom in\">+</button>"
            "<button type=\"button\" data-key=\"-\" aria-label=\"zoom out\">&minus;</button>"
            "<button type=\"button\" data-key=\"0\" aria-label=\"reset the view\">Reset</button></div>"
            "</section>\n"
            "<section id=\"chart\" tabindex=\"0\" aria-label=\"the run's time series\"></section>\n</main>\n"
            "<footer>\n<details id=\"in-words\"><summary>The motion in words, and the time series as a table</summary>\n"
            "<p id=\"motion\">" + markupEscaped(motionInWords(r.times, r.poses, r.bodies, r.massless, r.looks)) +
            "</p>\n<div id=\"series-table\" role=\"region\" tabindex=\"0\" aria-label=\"the time series as a table\"></div>\n</details>\n</footer>\n"
            "<script type=\"application/json\" id=\"replay-data\">" + data + "</script>\n<script>\n";
    html += inlineScript(threeJs);
    html += "\n</script>\n";
    if (!orbitControls.empty()) html += "<script>\n" + inlineScript(orbitControls) + "\n</script>\n";
    html += "<script>\n";
    html += kScript;
    html += "</script>\n</body>\n</html>\n";

    std::ofstream out(path, std::ios::binary);
    if (!out) throw std::runtime_error("cannot write replay page '" + path + "': " + std::strerror(errno));
    out << html;
    out.close();
    if (!out) throw std::runtime_error("cannot write replay page '" + path + "'");
}

namespace {

// assets/replay.css and assets/replay.js, made raw string literals at build time (cmake/EmbedText.cmake).
const char* const kStyle =
#include "replay.css.inc"
    ;
const char* const kScript =
#include "replay.js.inc"
    ;

}  // namespace

}  // namespace simlab
