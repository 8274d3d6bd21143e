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

}  // namespace

struct ReplayRecorder::Recording {
    double frameInterval = 0;            // s
    bool shapesRead = false;
    std::vector<std::string> shapes;     // one JSON object each (see shapeJson)
    int skipped = 0;                     // decorations the page cannot draw
    int bodies = 0;                      // mobilized bodies other than Ground
    std::vector<bool> massless;          // per body: no mass (a device of the joints, such as a slider), not drawn
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
            }
        }
        r.shapesRead = true;
    }

    const SimTK::MultibodySystem& system_;  // owns this reporter
    std::shared_ptr<Recording> recording_;
};

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

// The page's style sheet and script, at the end of this file.
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
    html += "</style>\n</head>\n<body>\n<header>\n<h1>" + heading + "</h1>\n<div class=\"controls\">\n"
            "<button id=\"play\" type=\"button\">Play</button>\n"
            "<label>Speed <select id=\"speed\"><option value=\"0.25\">0.25&times;</option>"
            "<option value=\"0.5\">0.5&times;</option><option value=\"1\" selected>1&times;</option>"
            "<option value=\"2\">2&times;</option><option value=\"4\">4&times;</option></select></label>\n"
            "<input id=\"time\" type=\"range\" min=\"0\" max=\"1\" step=\"any\" value=\"0\" aria-label=\"time\">\n"
            "<output id=\"now\">t = 0 s</output>\n</div>\n</header>\n<main>\n"
            "<section id=\"view\" aria-label=\"the bodies' motion in 3-D\"><p id=\"view-note\"></p></section>\n"
            "<section id=\"chart\" aria-label=\"the run's time series\"></section>\n</main>\n"
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

const char* const kStyle = R"css(* { box-sizing: border-box; }
html, body { height: 100%; margin: 0; }
body { display: flex; flex-direction: column; font: 14px/1.4 system-ui, -apple-system, "Segoe UI", sans-serif;
       color: #1d232b; background: #fafbfc; }
header { padding: 10px 16px 8px; border-bottom: 1px solid #d8dde3; background: #fff; }
h1 { font-size: 18px; margin: 0 0 8px; font-weight: 600; }
.controls { display: flex; align-items: center; gap: 12px; }
#play { min-width: 5.5em; padding: 4px 10px; font: inherit; cursor: pointer; }
#time { flex: 1; min-width: 120px; }
#now { font-variant-numeric: tabular-nums; min-width: 10em; text-align: right; }
main { flex: 1; display: flex; min-height: 0; }
#view { flex: 1; position: relative; min-width: 0; background: #eef1f5; overflow: hidden; }
#view canvas { display: block; width: 100%; height: 100%; }
#view-note { position: absolute; left: 12px; bottom: 8px; margin: 0; color: #5a6470; font-size: 12px; }
#view-note.alone { left: 0; right: 0; bottom: auto; top: 45%; text-align: center; font-size: 15px; }
#chart { width: 380px; overflow-y: auto; border-left: 1px solid #d8dde3; background: #fff; padding: 6px 8px; }
#chart svg { display: block; width: 100%; cursor: pointer; }
#chart text { font-size: 11px; fill: #3a434d; }
#chart .name { font-weight: 600; }
#chart .value { font-variant-numeric: tabular-nums; }
#chart .series { fill: none; stroke: #2f6db3; stroke-width: 1.5; }
#chart .cursor { stroke: #d0402a; stroke-width: 1; }
#chart .plot { fill: #fbfcfd; stroke: #e1e5ea; }
@media (max-width: 800px) {
  html, body { height: auto; }
  main { flex-direction: column; }
  #view { height: 60vh; flex: none; }
  #chart { width: auto; border-left: 0; border-top: 1px solid #d8dde3; }
}
)css";

const char* const kScript = R"js((function () {
  "use strict";
  var data = JSON.parse(document.getElementById("replay-data").textContent);
  var times = data.t, frameCount = times.length, tStart = times[0], tEnd = times[frameCount - 1];
  var playButton = document.getElementById("play"), speedSelect = document.getElementById("speed");
  var slider = document.getElementById("time"), now = document.getElementById("now");
  var note = document.getElementById("view-note");
  var decimals = Math.max(2, Math.min(6, Math.ceil(-Math.log(data.dt) / Math.LN10) + 1));
  var current = tStart, playing = false, lastWall = null;

  // The frame at or before t, and how far t is on the way to the next one.
  function locate(list, t) {
    var lo = 0, hi = list.length - 1;
    if (!(t > list[0])) return { i: 0, j: 0, a: 0 };
    if (t >= list[hi]) return { i: hi, j: hi, a: 0 };
    while (hi - lo > 1) {
      var mid = (lo + hi) >> 1;
      if (list[mid] <= t) lo = mid; else hi = mid;
    }
    return { i: lo, j: hi, a: (t - list[lo]) / (list[hi] - list[lo]) };
  }

  // A number in a few characters; 0 when it is negligible beside `scale`.
  function short(v, scale) {
    if (v === null || !isFinite(v)) return "\u2013";
    var a = Math.abs(v);
    if (scale && a < 1e-9 * scale) return "0";
    if (a !== 0 && (a >= 1e5 || a < 1e-3)) return v.toExponential(2);
    return String(parseFloat(v.toPrecision(4)));
  }

  // --- The time series: one small plot per column, each on its own scale --------------------------------------
  function createChart() {
    var box = document.getElementById("chart");
    var names = data.series.names, values = data.series.values;
    var panels = [];
    if (names.length < 2 || values[0].length === 0) {
      box.style.display = "none";
      return { draw: function () {}, cursor: function () {} };
    }
    var ts = values[0], t0 = ts[0], t1 = ts[ts.length - 1];
    var left = 58, right = 10, top = 20, plotHeight = 58, bottom = 8;
    function escape(s) {
      return s.replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;").replace(/"/g, "&quot;");
    }
    function x(t, width) { return left + (t1 > t0 ? (t - t0) / (t1 - t0) : 0) * (width - left - right); }
    function draw() {
      var width = Math.max(220, box.clientWidth - 16), html = "", scales = [];
      for (var c = 1; c < names.length; ++c) {
        var v = values[c], lo = Infinity, hi = -Infinity;
        for (var k = 0; k < v.length; ++k) if (v[k] !== null) { lo = Math.min(lo, v[k]); hi = Math.max(hi, v[k]); }
        if (!(lo <= hi)) { lo = -1; hi = 1; }
        scales[c] = Math.max(Math.abs(lo), Math.abs(hi));
        if (hi === lo) { var pad = Math.abs(hi) * 0.1 || 1; lo -= pad; hi += pad; }
        var last = c === names.length - 1, height = top + plotHeight + bottom + (last ? 14 : 0);
        var d = "", open = false;
        for (k = 0; k < v.length; ++k) {
          if (v[k] === null) { open = false; continue; }
          var px = x(ts[k], width), py = top + (hi - v[k]) / (hi - lo) * plotHeight;
          d += (open ? "L" : "M") + px.toFixed(1) + " " + py.toFixed(1);
          open = true;
        }
        html += '<svg class="panel" width="' + width + '" height="' + height + '" viewBox="0 0 ' + width + " " +
          height + '" data-column="' + c + '">' +
          '<text class="name" x="' + left + '" y="13">' + escape(names[c]) + "</text>" +
          '<text class="value" x="' + (width - right) + '" y="13" text-anchor="end"></text>' +
          '<rect class="plot" x="' + left + '" y="' + top + '" width="' + (width - left - right) + '" height="' +
          plotHeight + '"></rect>' +
          '<text x="' + (left - 4) + '" y="' + (top + 9) + '" text-anchor="end">' + short(hi, scales[c]) +
          "</text>" +
          '<text x="' + (left - 4) + '" y="' + (top + plotHeight) + '" text-anchor="end">' + short(lo, scales[c]) +
          "</text>" +
          '<path class="series" d="' + d + '"></path>' +
          '<line class="cursor" y1="' + (top - 2) + '" y2="' + (top + plotHeight + 2) + '"></line>' +
          (last ? '<text x="' + left + '" y="' + (height - 2) + '">' + short(t0) + " s</text>" +
                  '<text x="' + (width - right) + '" y="' + (height - 2) + '" text-anchor="end">' + short(t1) +
                  " s</text>" : "") +
          "</svg>";
      }
      box.innerHTML = html;
      panels = [];
      var svgs = box.querySelectorAll("svg");
      for (var s = 0; s < svgs.length; ++s) {
        panels.push({ column: s + 1, width: width, cursor: svgs[s].querySelector(".cursor"),
                      value: svgs[s].querySelector(".value"), scale: scales[s + 1] });
        svgs[s].addEventListener("click", seekFromChart);
      }
      cursor(current);
    }
    function seekFromChart(event) {
      var rect = event.currentTarget.getBoundingClientRect(), width = rect.width;
      var f = (event.clientX - rect.left - left) / (width - left - right);
      pause();
      show(t0 + Math.min(1, Math.max(0, f)) * (t1 - t0));
    }
    function cursor(t) {
      var at = locate(ts, t);
      for (var p = 0; p < panels.length; ++p) {
        var v = values[panels[p].column], a = v[at.i], b = v[at.j];
        var value = a === null || b === null ? (at.a < 0.5 ? a : b) : a + (b - a) * at.a;
        var cx = x(Math.min(t1, Math.max(t0, t)), panels[p].width).toFixed(1);
        panels[p].cursor.setAttribute("x1", cx);
        panels[p].cursor.setAttribute("x2", cx);
        panels[p].value.textContent = short(value, panels[p].scale);
      }
    }
    return { draw: draw, cursor: cursor };
  }

  // --- The bodies in 3-D ------------------------------------------------------------------------------------------
  function createScene() {
    var view = document.getElementById("view");
    var canvas = document.createElement("canvas");
    var attributes = { alpha: false, depth: true, stencil: true, antialias: true, premultipliedAlpha: true,
                       preserveDrawingBuffer: false, powerPreference: "default" };
    var gl = null;
    try { gl = canvas.getContext("webgl", attributes); } catch (e) { gl = null; }
    if (!gl) {
      note.textContent = "This browser cannot draw WebGL, so the 3-D view is off; the time series still works.";
      note.className = "alone";
      return null;
    }
    view.insertBefore(canvas, view.firstChild);
    var renderer = new THREE.WebGLRenderer({ canvas: canvas, context: gl, antialias: true });
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    var scene = new THREE.Scene();
    scene.background = new THREE.Color(0xeef1f5);
    // Light from the sky, from above and aside, and from the camera, so that no face the camera sees is dark.
    scene.add(new THREE.HemisphereLight(0xffffff, 0x8a929c, 0.45));
    var sun = new THREE.DirectionalLight(0xffffff, 0.35);
    sun.position.set(0.5, 1, 0.75);
    scene.add(sun);
    var headlight = new THREE.DirectionalLight(0xffffff, 0.55);
    scene.add(headlight);

    var surfaceColor = new THREE.Color(0x8c9db5), lineColor = new THREE.Color(0x404850);
    var pointColor = new THREE.Color(1, 0, 1);
    var yAxis = new THREE.Vector3(0, 1, 0);

    // Where each body is in each frame; its decorations go in its group.
    var bodies = data.bodies.map(function (b) {
      var group = new THREE.Group();
      scene.add(group);
      return { group: group, p: b.p, q: b.q, shapes: 0, massless: b.massless === true };
    });
    var motion = new THREE.Box3(), point = new THREE.Vector3();
    bodies.forEach(function (b) {
      for (var f = 0; f < frameCount; ++f) motion.expandByPoint(point.fromArray(b.p, 3 * f));
    });
    var motionSize = motion.isEmpty() ? 0 : motion.getSize(new THREE.Vector3()).length();

    function withOpacity(material, s) {
      if (s.o !== undefined) { material.transparent = true; material.opacity = s.o; material.depthWrite = false; }
      return material;
    }
    function solid(geometry, s, doubleSided) {
      var color = s.c ? new THREE.Color(s.c[0], s.c[1], s.c[2]) : surfaceColor;
      if (s.w === "points") {
        return new THREE.Points(geometry, withOpacity(new THREE.PointsMaterial(
          { color: color, size: 3, sizeAttenuation: false }), s));
      }
      return new THREE.Mesh(geometry, withOpacity(new THREE.MeshPhongMaterial({
        color: color, specular: 0x222222, shininess: 30, wireframe: s.w === "wire",
        side: doubleSided ? THREE.DoubleSide : THREE.FrontSide }), s));
    }
    function segments(points, s, color) {
      var geometry = new THREE.BufferGeometry();
      geometry.setAttribute("position", new THREE.Float32BufferAttribute(points, 3));
      var c = s.c ? new THREE.Color(s.c[0], s.c[1], s.c[2]) : color || lineColor;
      return new THREE.LineSegments(geometry, withOpacity(new THREE.LineBasicMaterial({ color: c }), s));
    }
    // A shape along `direction` (three.js builds cylinders and cones along y), centered at `center`.
    function along(object, direction, center) {
      var group = new THREE.Group();
      object.quaternion.setFromUnitVectors(yAxis, direction.clone().normalize());
      object.position.copy(center);
      group.add(object);
      return group;
    }
    function stick(from, to, radius, color, s) {
      var axis = new THREE.Vector3().subVectors(to, from), length = axis.length();
      var mesh = new THREE.Mesh(new THREE.CylinderBufferGeometry(radius, radius, length, 12),
        withOpacity(new THREE.MeshPhongMaterial({ color: color, specular: 0x222222, shininess: 30 }), s));
      return along(mesh, axis, from.clone().add(to).multiplyScalar(0.5));
    }
    function vector(a) { return new THREE.Vector3(a[0], a[1], a[2]); }

    function makeShape(s) {
      var group;
      switch (s.k) {
      case "sphere": return solid(new THREE.SphereBufferGeometry(s.r, 32, 20), s);
      case "ellipsoid":
        var ellipsoid = solid(new THREE.SphereBufferGeometry(1, 32, 20), s);
        ellipsoid.scale.set(s.r[0], s.r[1], s.r[2]);
        group = new THREE.Group();
        group.add(ellipsoid);
        return group;
      case "brick": return solid(new THREE.BoxBufferGeometry(2 * s.h[0], 2 * s.h[1], 2 * s.h[2]), s);
      case "cylinder": return solid(new THREE.CylinderBufferGeometry(s.r, s.r, 2 * s.h, 32), s);
      case "torus": return solid(new THREE.TorusBufferGeometry(s.r, s.t, 16, 48), s);
      case "circle":
        if (s.w === "wire") {
          var ring = [];
          for (var k = 0; k < 64; ++k) {
            var a0 = 2 * Math.PI * k / 64, a1 = 2 * Math.PI * (k + 1) / 64;
            ring.push(s.r * Math.cos(a0), s.r * Math.sin(a0), 0, s.r * Math.cos(a1), s.r * Math.sin(a1), 0);
          }
          return segments(ring, s);
        }
        return solid(new THREE.CircleBufferGeometry(s.r, 48), s, true);
      case "cone":
        var direction = vector(s.d).normalize();
        return along(solid(new THREE.ConeBufferGeometry(s.r, s.h, 32), s), direction,
                     vector(s.a).addScaledVector(direction, s.h / 2));
      case "frame":
        group = new THREE.Group();
        var axisColors = s.c ? [0, 0, 0].map(function () { return new THREE.Color(s.c[0], s.c[1], s.c[2]); })
                             : [new THREE.Color(0xd03030), new THREE.Color(0x30a030), new THREE.Color(0x3050d0)];
        for (var i = 0; i < 3; ++i) {
          var end = new THREE.Vector3();
          end.setComponent(i, s.l);
          group.add(stick(new THREE.Vector3(), end, s.l * 0.02, axisColors[i], s));
        }
        return group;
      case "line": return segments(s.a.concat(s.e), s);
      case "point":
        var p = s.a, h = 0.05;
        return segments([p[0] - h, p[1], p[2], p[0] + h, p[1], p[2], p[0], p[1] - h, p[2], p[0], p[1] + h, p[2],
                         p[0], p[1], p[2] - h, p[0], p[1], p[2] + h], s, pointColor);
      case "arrow":
        var start = vector(s.a), tipEnd = vector(s.e), shaft = new THREE.Vector3().subVectors(tipEnd, start);
        var length = shaft.length(), tip = Math.min(s.tip, length);
        group = new THREE.Group();
        if (length === 0) return group;
        var tipBase = tipEnd.clone().addScaledVector(shaft, -tip / length);
        group.add(segments([start.x, start.y, start.z, tipBase.x, tipBase.y, tipBase.z], s));
        if (tip > 0) {
          var cone = solid(new THREE.ConeBufferGeometry(tip * 0.35, tip, 16), s);
          if (!s.c) cone.material.color.copy(lineColor);
          group.add(along(cone, shaft, tipBase.clone().addScaledVector(shaft, tip / length / 2)));
        }
        return group;
      case "mesh":
        var geometry = new THREE.BufferGeometry();
        geometry.setAttribute("position", new THREE.Float32BufferAttribute(s.v, 3));
        geometry.setIndex(s.f);
        geometry.computeVertexNormals();
        return solid(geometry, s, true);
      }
      return null;
    }

    var ground = new THREE.Group();
    scene.add(ground);
    data.shapes.forEach(function (s) {
      var object = makeShape(s);
      if (!object) return;
      if (s.T) {
        object.position.set(s.T[0], s.T[1], s.T[2]);
        object.quaternion.set(s.T[3], s.T[4], s.T[5], s.T[6]);
      }
      if (s.s) object.scale.set(s.s[0], s.s[1], s.s[2]);
      if (s.b === 0) {
        ground.add(object);
      } else {
        bodies[s.b - 1].group.add(object);
        bodies[s.b - 1].shapes++;
      }
    });
    // A body that has no decoration is a small sphere, so that nothing moves unseen; a massless one (a slider that
    // only carries a joint) is no matter, and is not drawn.
    var defaultRadius = motionSize > 0 ? 0.03 * motionSize : 0.05;
    bodies.forEach(function (b) {
      if (b.shapes === 0 && !b.massless) b.group.add(solid(new THREE.SphereBufferGeometry(defaultRadius, 24, 16), {}));
    });

    // The camera sees the whole motion: every body's reach around its origin, at every frame.
    var extent = new THREE.Box3(), corner = new THREE.Vector3();
    // How far a body's decorations reach from its origin: its farthest vertex, its group still at the origin.
    function reachOf(group) {
      var reach = 0;
      group.updateMatrixWorld(true);
      group.traverse(function (object) {
        var position = object.geometry && object.geometry.getAttribute("position");
        if (!position) return;
        for (var k = 0; k < position.count; ++k) {
          reach = Math.max(reach, corner.fromBufferAttribute(position, k).applyMatrix4(object.matrixWorld).length());
        }
      });
      return reach;
    }
    bodies.forEach(function (b) {
      var reach = reachOf(b.group);
      var pad = new THREE.Vector3(reach, reach, reach);
      for (var f = 0; f < frameCount; ++f) {
        point.fromArray(b.p, 3 * f);
        extent.expandByPoint(point.clone().sub(pad));
        extent.expandByPoint(point.clone().add(pad));
      }
      // A body that goes far beyond its own size leaves a trail.
      if (motionSize > 0 && frameCount > 1) {
        var own = new THREE.Box3();
        for (f = 0; f < frameCount; ++f) own.expandByPoint(point.fromArray(b.p, 3 * f));
        if (own.getSize(new THREE.Vector3()).length() > 3 * reach) {
          var geometry = new THREE.BufferGeometry();
          geometry.setAttribute("position", new THREE.Float32BufferAttribute(b.p, 3));
          b.trail = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: 0xc8783c }));
          scene.add(b.trail);
          // ... and a dot of a fixed size on screen where it is: a body small beside its motion (an apple in a
          // 78 m fall) stays in sight at any distance.
          var dot = new THREE.BufferGeometry();
          dot.setAttribute("position", new THREE.Float32BufferAttribute([0, 0, 0], 3));
          b.group.add(new THREE.Points(dot, new THREE.PointsMaterial({ color: 0xb0202c, size: 10, sizeAttenuation: false })));
        }
      }
    });
    if (extent.isEmpty()) extent.setFromObject(ground);
    if (extent.isEmpty()) extent.set(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
    var center = extent.getCenter(new THREE.Vector3()), size = extent.getSize(new THREE.Vector3()).length();
    if (!(size > 0)) size = 1;

    // A grid on the ground (y = 0) when the motion is near it.
    if (extent.min.y - 0.5 * size <= 0 && extent.max.y + 0.5 * size >= 0) {
      var cell = Math.pow(10, Math.floor(Math.log(size / 8) / Math.LN10)), steps = [1, 2, 5, 10];
      for (var k = 0; k < steps.length && size / 8 > steps[k] * cell * 1.5; ++k);
      cell *= steps[Math.min(k, 3)];
      var cells = 2 * Math.ceil((Math.max(extent.max.x - extent.min.x, extent.max.z - extent.min.z) + size) / cell / 2);
      var grid = new THREE.GridHelper(cells * cell, cells, 0xb4bcc6, 0xd2d8de);
      grid.position.set(Math.round(center.x / cell) * cell, 0, Math.round(center.z / cell) * cell);
      scene.add(grid);
    }

    var camera = new THREE.PerspectiveCamera(25, 1, size / 1000, size * 100);
    var viewFrom = new THREE.Vector3(0.35, 0.3, 1).normalize();  // looking at the x-y plane, from above and aside
    var controls = null, moved = false;
    if (THREE.OrbitControls) {
      controls = new THREE.OrbitControls(camera, renderer.domElement);
      controls.enableKeys = false;
      controls.addEventListener("change", function () { moved = true; dirty = true; });
      note.textContent = "Drag to turn, scroll to zoom, right-drag to move.";
    }
    if (data.skipped > 0) {
      note.textContent += (note.textContent ? " " : "") + data.skipped +
        (data.skipped === 1 ? " decoration (text) is" : " decorations (text) are") + " not shown.";
    }

    // Places the camera on viewFrom so that every corner of the extent is in view.
    function frameAll() {
      var aspect = camera.aspect, tanV = Math.tan(camera.fov * Math.PI / 360), tanH = tanV * aspect;
      var xc = new THREE.Vector3().crossVectors(yAxis, viewFrom).normalize();
      var yc = new THREE.Vector3().crossVectors(viewFrom, xc);
      var distance = 0;
      for (var k = 0; k < 8; ++k) {
        corner.set(k & 1 ? extent.max.x : extent.min.x, k & 2 ? extent.max.y : extent.min.y,
                   k & 4 ? extent.max.z : extent.min.z).sub(center);
        var depth = corner.dot(viewFrom);
        distance = Math.max(distance, depth + 1.08 * Math.abs(corner.dot(xc)) / tanH,
                            depth + 1.08 * Math.abs(corner.dot(yc)) / tanV);
      }
      camera.position.copy(center).addScaledVector(viewFrom, Math.max(distance, size / 100));
      camera.up.set(0, 1, 0);
      camera.lookAt(center);
      if (controls) { controls.target.copy(center); controls.update(); moved = false; }
    }

    var dirty = true, qa = new THREE.Quaternion(), qb = new THREE.Quaternion();
    function resize() {
      var width = Math.max(1, view.clientWidth), height = Math.max(1, view.clientHeight);
      renderer.setSize(width, height, false);
      camera.aspect = width / height;
      camera.updateProjectionMatrix();
      if (!moved) frameAll();
      dirty = true;
    }
    function pose(t) {
      var at = locate(times, t);
      bodies.forEach(function (b) {
        b.group.position.set(b.p[3 * at.i] + (b.p[3 * at.j] - b.p[3 * at.i]) * at.a,
                             b.p[3 * at.i + 1] + (b.p[3 * at.j + 1] - b.p[3 * at.i + 1]) * at.a,
                             b.p[3 * at.i + 2] + (b.p[3 * at.j + 2] - b.p[3 * at.i + 2]) * at.a);
        qa.fromArray(b.q, 4 * at.i);
        qb.fromArray(b.q, 4 * at.j);
        THREE.Quaternion.slerp(qa, qb, b.group.quaternion, at.a);
        if (b.trail) b.trail.geometry.setDrawRange(0, at.i + 1);
      });
      dirty = true;
    }
    function render() {
      if (!dirty) return;
      headlight.position.subVectors(camera.position, controls ? controls.target : center);
      renderer.render(scene, camera);
      dirty = false;
    }
    resize();
    return { pose: pose, render: render, resize: resize };
  }

  var chart = createChart();
  chart.draw();
  var view3d = createScene();

  function show(t) {
    current = Math.min(tEnd, Math.max(tStart, t));
    slider.value = current;
    now.textContent = "t = " + current.toFixed(decimals) + " s";
    if (view3d) view3d.pose(current);
    chart.cursor(current);
  }
  function play() {
    if (current >= tEnd) show(tStart);
    playing = true;
    lastWall = null;
    playButton.textContent = "Pause";
  }
  function pause() {
    playing = false;
    playButton.textContent = "Play";
  }
  function tick(wall) {
    if (playing) {
      if (lastWall !== null) {
        var t = current + (wall - lastWall) / 1000 * Number(speedSelect.value);
        if (t >= tEnd) { t = tEnd; pause(); }
        show(t);
      }
      lastWall = wall;
    }
    if (view3d) view3d.render();
    window.requestAnimationFrame(tick);
  }
  // "#t=1.5": paused at t = 1.5 s.
  function timeInLink() {
    var match = /(?:^#|&)t=([^&]*)/.exec(window.location.hash);
    var t = match ? parseFloat(decodeURIComponent(match[1])) : NaN;
    return isFinite(t) ? t : null;
  }

  slider.min = tStart;
  slider.max = tEnd;
  playButton.addEventListener("click", function () { if (playing) pause(); else play(); });
  slider.addEventListener("input", function () { show(Number(slider.value)); lastWall = null; });
  window.addEventListener("resize", function () { chart.draw(); if (view3d) view3d.resize(); });
  window.addEventListener("hashchange", function () {
    var t = timeInLink();
    if (t !== null) { pause(); show(t); }
  });
  document.addEventListener("keydown", function (event) {
    var tag = event.target.tagName;
    if (event.key !== " " || tag === "BUTTON" || tag === "SELECT" || tag === "INPUT") return;
    event.preventDefault();
    if (playing) pause(); else play();
  });

  var start = timeInLink();
  show(start === null ? tStart : start);
  if (start === null) play();
  window.requestAnimationFrame(tick);
})();
)js";

}  // namespace

}  // namespace simlab
