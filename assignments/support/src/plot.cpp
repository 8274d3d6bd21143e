#include "simlab/plot.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "simlab/messages.h"
#include "simlab/system_tool.h"

namespace simlab {

namespace fs = std::filesystem;

namespace {

bool endsWith(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// A gnuplot string in single quotes, where only a doubled quote is special; no control characters.
std::string quoted(const std::string& text) {
    std::string out = "'";
    for (char c : text) {
        if (c == '\'') out += "''";
        else if (static_cast<unsigned char>(c) >= 0x20) out += c;
        else out += ' ';
    }
    return out + "'";
}

std::string number(double v, int digits = 10) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
    return buffer;
}

// Where a panel's values differ by less than a ten-thousandth of their size (a conserved energy, say), six-digit
// tick labels would all read the same: the panel then draws each value less one reference value, in the middle
// of their range and written in the axis label to as many digits as the range needs (10 at least, 17 at most: what
// the written value leaves over is a thousandth of the range or less, so that the ticks show the values' spread,
// not its rounding), with ticks in scientific notation. Else 0 and "".
struct Offset {
    double value = 0;
    std::string label;
};

Offset panelOffset(const PlotPanel& panel) {
    if (panel.logY) return {};  // a logarithmic axis reads small differences of large values as they are
    double low = INFINITY, high = -INFINITY;
    auto see = [&](double y) {
        if (std::isfinite(y)) low = std::min(low, y), high = std::max(high, y);
    };
    for (const PlotCurve& curve : panel.curves) {
        for (const double y : curve.y) see(y);
    }
    for (const PlotMark& mark : panel.marks) see(mark.y);
    const double size = std::max(std::abs(low), std::abs(high));
    if (!(high >= low) || !(size > 0) || high - low >= 1e-4 * size) return {};
    const int digits = high > low ? static_cast<int>(std::ceil(std::log10(size / (high - low)))) + 3 : 17;
    const std::string written = number(low + (high - low) / 2, std::clamp(digits, 10, 17));
    return {std::strtod(written.c_str(), nullptr), written};
}

// The y axis's tick labels of `panel`, as `script` formats them: how many characters the widest takes.
std::size_t tickWidth(const PlotPanel& panel, const Offset& offset) {
    if (panel.logY) return 5;                                   // "1e-16"
    if (panel.scientificY || !offset.label.empty()) return 8;  // "-1.2e-08"
    double low = 0, high = 0;
    for (const PlotCurve& curve : panel.curves) {
        for (const double y : curve.y) {
            if (std::isfinite(y)) low = std::min(low, y), high = std::max(high, y);
        }
    }
    // A tick is a round number within a step of the range's ends: as wide as they are in '% g', and its fraction.
    char text[40];
    std::size_t widest = 0;
    for (const double y : {low, high}) widest = std::max(widest, static_cast<std::size_t>(std::snprintf(text, sizeof text, "% g", y)));
    return widest + 2;
}

// Whether (x, y) can be drawn on `panel`'s axes: finite, and above zero on a logarithmic one.
bool drawable(const PlotPanel& panel, double x, double y) {
    return std::isfinite(x) && std::isfinite(y) && (!panel.logX || x > 0) && (!panel.logY || y > 0);
}

// The gnuplot script that draws `plot` into `output` with `terminal`. Each curve's points go in a datablock of
// their own, so the script is the whole figure and reads no other file.
std::string script(const Plot& plot, const std::string& terminal, const std::string& output) {
    std::ostringstream gp;
    const int panels = static_cast<int>(plot.panels.size());
    const int height = panels > 1 ? 330 * panels + 60 : 560;
    std::vector<Offset> offsets;
    std::size_t ticks = 0;
    for (const PlotPanel& panel : plot.panels) {
        offsets.push_back(panelOffset(panel));
        ticks = std::max(ticks, tickWidth(panel, offsets.back()));
    }
    // The panels line up: one left margin for all, wide enough for the widest tick labels and the axis label beside
    // them (about 7 px a character of the 11-point font, and 44 px for the label and the gaps), so that no label
    // is cut at the figure's edge.
    const double left = std::max(0.09, (7.0 * static_cast<double>(ticks) + 44) / 960);
    gp << "set terminal " << terminal << " size 960," << height << " font 'sans,11' background '#ffffff'\n"
       << "set termoption noenhanced\n"  // names like w_B and y'' are printed as written
       << "set output " << quoted(output) << "\n"
       << "set grid\nset key below\nset datafile missing 'NaN'\n"
       // Every curve at least 3:1 against the white (WCAG 1.4.11): gnuplot's third to fifth colours are lighter.
       << "set linetype 3 lc rgb '#1f6fb4'\nset linetype 4 lc rgb '#b35900'\nset linetype 5 lc rgb '#8a6d00'\n"
       << "set lmargin at screen " << number(left, 4) << "\nset rmargin at screen 0.96\n";
    int block = 0;
    for (std::size_t p = 0; p < plot.panels.size(); ++p) {
        const PlotPanel& panel = plot.panels[p];
        const Offset& offset = offsets[p];
        for (const PlotCurve& curve : panel.curves) {
            gp << "$d" << block++ << " << EOD\n";
            for (std::size_t i = 0; i < curve.x.size() && i < curve.y.size(); ++i) {
                if (drawable(panel, curve.x[i], curve.y[i])) {
                    gp << number(curve.x[i]) << ' ' << number(curve.y[i] - offset.value) << '\n';
                }
            }
            gp << "EOD\n";
        }
        for (const PlotMark& mark : panel.marks) {
            gp << "$d" << block++ << " << EOD\n" << number(mark.x) << ' ' << number(mark.y - offset.value) << "\nEOD\n";
        }
    }
    gp << "set multiplot layout " << std::max(panels, 1) << ",1 title " << quoted(plot.title) << "\n";
    block = 0;
    for (std::size_t p = 0; p < plot.panels.size(); ++p) {
        const PlotPanel& panel = plot.panels[p];
        const Offset& offset = offsets[p];
        const std::string yLabel = offset.label.empty() ? panel.yLabel : panel.yLabel + ", less " + offset.label;
        gp << "set xlabel " << quoted(panel.xLabel) << "\nset ylabel " << quoted(yLabel) << "\n"
           << (panel.logX ? "set logscale x\n" : "unset logscale x\n")
           << (panel.logY ? "set logscale y\nset format y '%.0e'\n"
               : panel.scientificY || !offset.label.empty() ? "unset logscale y\nset format y '%.1e'\n"
                                                            : "unset logscale y\nset format y '% g'\n")
           << "plot ";
        int color = 1;
        for (std::size_t c = 0; c < panel.curves.size(); ++c) {
            const PlotCurve& curve = panel.curves[c];
            gp << (c ? ", \\\n     " : "") << "$d" << block++ << " using 1:2 ";
            const int lc = curve.color > 0 ? curve.color : color++;
            if (curve.markers) {
                gp << "with points pointtype 6 pointsize 0.9 lc " << lc;  // open circles: the line shows through
            } else {
                gp << "with lines linewidth 2 lc " << lc << (curve.dashed ? " dashtype 2" : "");
            }
            gp << " title " << quoted(curve.title);
        }
        for (std::size_t m = 0; m < panel.marks.size(); ++m) {
            gp << (panel.curves.empty() && m == 0 ? "" : ", \\\n     ") << "$d" << block++
               << " using 1:2 with points pointtype 9 pointsize 2.2 lc rgb '#c00000' title "
               << quoted(panel.marks[m].label);
        }
        if (panel.curves.empty() && panel.marks.empty()) gp << "NaN notitle";
        gp << "\n";
    }
    gp << "unset multiplot\nset output\n";
    return gp.str();
}

// --- The plot in words, and its points (an SVG's text alternative) ------------------------------------------------

constexpr double kOnTheLine = 0.005;  // samples within this share of the panel's height of their line look on it

// A figure as the description gives it: 4 significant digits.
std::string figure(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", v == 0 ? 0.0 : v);  // no "-0"
    return text;
}

// The points of `curve` that `panel` draws.
std::vector<std::pair<double, double>> drawnPoints(const PlotPanel& panel, const PlotCurve& curve) {
    std::vector<std::pair<double, double>> points;
    for (std::size_t i = 0; i < curve.x.size() && i < curve.y.size(); ++i) {
        if (drawable(panel, curve.x[i], curve.y[i])) points.emplace_back(curve.x[i], curve.y[i]);
    }
    return points;
}

// The label of panel `p`'s horizontal axis: its own, or, where it has none, that of the next panel below that has
// one (stacked panels against the same variable label only the bottom one).
std::string xLabelOf(const Plot& plot, std::size_t p) {
    for (std::size_t q = p; q < plot.panels.size(); ++q) {
        if (!plot.panels[q].xLabel.empty()) return plot.panels[q].xLabel;
    }
    return "x";
}

// The line a simulation's samples are drawn on: the line of the same colour, else the panel's first line.
const PlotCurve* lineFor(const PlotPanel& panel, const PlotCurve& samples) {
    const PlotCurve* first = nullptr;
    for (const PlotCurve& c : panel.curves) {
        if (c.markers) continue;
        if (samples.color > 0 && c.color == samples.color) return &c;
        if (!first) first = &c;
    }
    return samples.color > 0 ? nullptr : first;
}

// The largest distance of `points` from `line` along y, where the line covers their x (taken as straight between
// its points, which must go one way in x), and the x where it is; a negative distance when none can be read.
std::pair<double, double> largestDistance(const std::vector<std::pair<double, double>>& points,
                                          std::vector<std::pair<double, double>> line) {
    if (line.size() < 2) return {-1, 0};
    if (line.front().first > line.back().first) std::reverse(line.begin(), line.end());
    for (std::size_t i = 1; i < line.size(); ++i) {
        if (!(line[i].first > line[i - 1].first)) return {-1, 0};
    }
    double most = -1, at = 0;
    for (const auto& [x, y] : points) {
        if (x < line.front().first || x > line.back().first) continue;
        const auto after = std::lower_bound(line.begin(), line.end(), x,
                                            [](const std::pair<double, double>& point, double v) { return point.first < v; });
        double onLine = after->second;  // x is the line's first x
        if (after != line.begin()) {
            const auto& [xa, ya] = *(after - 1);
            onLine = ya + (after->second - ya) * (x - xa) / (after->first - xa);
        }
        const double d = std::abs(y - onLine);
        if (d > most) most = d, at = x;
    }
    return {most, at};
}

}  // namespace

std::string describePlot(const Plot& plot) {
    std::ostringstream out;
    if (!plot.title.empty()) out << plot.title << ". ";
    if (plot.panels.size() > 1) out << plot.panels.size() << " panels, one above the other. ";
    for (std::size_t p = 0; p < plot.panels.size(); ++p) {
        const PlotPanel& panel = plot.panels[p];
        double xLow = INFINITY, xHigh = -INFINITY, yLow = INFINITY, yHigh = -INFINITY;
        std::vector<std::vector<std::pair<double, double>>> drawn;
        for (const PlotCurve& c : panel.curves) {
            drawn.push_back(drawnPoints(panel, c));
            for (const auto& [x, y] : drawn.back()) {
                xLow = std::min(xLow, x), xHigh = std::max(xHigh, x), yLow = std::min(yLow, y), yHigh = std::max(yHigh, y);
            }
        }
        std::string sentence = (plot.panels.size() > 1 ? "Panel " + std::to_string(p + 1) + " of " +
                                                              std::to_string(plot.panels.size()) + ": "
                                                        : std::string("Drawn: ")) +
                               (panel.yLabel.empty() ? std::string("y") : panel.yLabel) +
                               (panel.logY ? " (log scale)" : "") + " against " + xLabelOf(plot, p) +
                               (panel.logX ? " (log scale)" : "");
        if (xLow <= xHigh) sentence += ", from " + figure(xLow) + " to " + figure(xHigh);
        std::vector<std::string> parts;
        for (std::size_t c = 0; c < panel.curves.size(); ++c) {
            const PlotCurve& curve = panel.curves[c];
            const auto& points = drawn[c];
            const std::string title = curve.title.empty() ? "a curve" : curve.title;
            if (points.empty()) {
                parts.push_back(title + ": nothing to draw");
                continue;
            }
            double low = INFINITY, high = -INFINITY;
            for (const auto& point : points) low = std::min(low, point.second), high = std::max(high, point.second);
            std::string part = title + ", " +
                               (curve.markers ? std::to_string(points.size()) + (points.size() == 1 ? " sample" : " samples")
                                              : std::string("a line")) +
                               ", from " + figure(points.front().second) + " at " + figure(points.front().first) +
                               " to " + figure(points.back().second) + " at " + figure(points.back().first);
            if (low < std::min(points.front().second, points.back().second) ||
                high > std::max(points.front().second, points.back().second)) {
                part += ", between " + figure(low) + " and " + figure(high);
            }
            const PlotCurve* line = curve.markers && !panel.logY ? lineFor(panel, curve) : nullptr;
            if (line && yHigh > yLow) {
                const auto [distance, at] = largestDistance(points, drawnPoints(panel, *line));
                if (distance >= 0 && distance <= kOnTheLine * (yHigh - yLow)) {
                    part += ", on the line " + line->title + " as drawn";
                } else if (distance >= 0) {
                    part += ", up to " + figure(distance) + " off the line " + line->title + " (at " + figure(at) + ")";
                }
            }
            parts.push_back(part);
        }
        for (const PlotMark& mark : panel.marks) {
            parts.push_back("marked: " + mark.label + " at (" + figure(mark.x) + ", " + figure(mark.y) + ")");
        }
        if (parts.empty()) parts.push_back("nothing drawn");
        sentence += ": ";
        for (std::size_t i = 0; i < parts.size(); ++i) sentence += (i ? "; " : "") + parts[i];
        out << sentence << ". ";
    }
    std::string text = out.str();
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

std::string plotDataJson(const Plot& plot) {
    using nlohmann::json;
    json panels = json::array();
    for (std::size_t p = 0; p < plot.panels.size(); ++p) {
        const PlotPanel& panel = plot.panels[p];
        json curves = json::array(), marks = json::array();
        for (const PlotCurve& curve : panel.curves) {
            const auto points = drawnPoints(panel, curve);
            json x = json::array(), y = json::array();
            for (const std::size_t i : thinned(points.size(), kPlotDataRows)) {
                x.push_back(std::strtod(number(points[i].first).c_str(), nullptr));  // as gnuplot was given it
                y.push_back(std::strtod(number(points[i].second).c_str(), nullptr));
            }
            curves.push_back({{"title", curve.title}, {"samples", curve.markers}, {"points", points.size()},
                              {"x", x}, {"y", y}});
        }
        for (const PlotMark& mark : panel.marks) {
            if (std::isfinite(mark.x) && std::isfinite(mark.y)) {
                marks.push_back({{"label", mark.label}, {"x", mark.x}, {"y", mark.y}});
            }
        }
        panels.push_back({{"x", xLabelOf(plot, p)}, {"y", panel.yLabel}, {"curves", curves}, {"marks", marks}});
    }
    // Text that is not valid UTF-8 (a title from anywhere) is replaced, not thrown on.
    return json{{"title", plot.title}, {"panels", panels}}.dump(-1, ' ', false, json::error_handler_t::replace);
}

namespace {

// gnuplot's SVG with the plot's text alternative in it, in place of gnuplot's own <title> and <desc>: the title,
// the description, and the points as JSON in <metadata>.
std::string withTextAlternative(const std::string& svg, const Plot& plot) {
    const std::string own = "<title>" + markupEscaped(plot.title) + "</title>\n<desc>" +
                            markupEscaped(describePlot(plot)) + "</desc>\n<metadata id=\"simlab-plot-data\">" +
                            markupEscaped(plotDataJson(plot)) + "</metadata>\n";
    std::string out = svg;
    const std::size_t title = out.find("<title>"), desc = out.find("</desc>");
    const std::size_t open = out.find("<svg");
    if (title != std::string::npos && desc != std::string::npos && desc > title) {
        out.replace(title, desc + 7 - title, own.substr(0, own.size() - 1));
    } else if (open != std::string::npos && out.find('>', open) != std::string::npos) {
        out.insert(out.find('>', open) + 1, "\n" + own);
    }
    return out;
}

}  // namespace

std::string plotPathProblem(const std::string& path) {
    if (endsWith(path, ".png") || endsWith(path, ".svg")) return "";
    return "a plot is a .png or an .svg file, not '" + path + "'";
}

std::vector<std::size_t> thinned(std::size_t n, std::size_t most) {
    std::vector<std::size_t> kept;
    if (n == 0 || most == 0) return kept;
    const std::size_t step = n <= most ? 1 : (n - 1 + most - 2) / (most - 1);
    for (std::size_t i = 0; i < n; i += step) kept.push_back(i);
    if (kept.back() != n - 1) kept.push_back(n - 1);
    return kept;
}

void drawPlot(const Plot& plot, const std::string& path) {
    if (const std::string problem = plotPathProblem(path); !problem.empty()) throw std::runtime_error(problem);
    const fs::path target = fs::absolute(path);
    const std::string stem = target.string() + ".drawing-" + std::to_string(::getpid());
    const std::string partial = stem + (endsWith(path, ".svg") ? ".svg" : ".png");
    // gnuplot reads the script on its standard input: no file, and no name that needs quoting.
    SystemToolRun run;
    bool missing = false;
    std::string failure;
    try {
        run = runSystemTool({"gnuplot"}, script(plot, endsWith(path, ".svg") ? "svg" : "pngcairo", partial), 120,
                            1u << 20);
    } catch (const SystemToolMissing&) {
        missing = true;
    } catch (const std::runtime_error& e) {
        failure = e.what();
    }
    // Its complaints: the first line with more than the spaces and carets that point into the script.
    std::string said;
    {
        std::istringstream log(run.errors);
        std::string line;
        while (said.empty() && std::getline(log, line)) {
            if (line.find_first_not_of(" \t^") != std::string::npos) said = line;
        }
    }
    std::error_code ignored;
    const bool drawn = !missing && failure.empty() && run.succeeded() && fs::is_regular_file(partial, ignored) &&
                       fs::file_size(partial, ignored) > 0;
    if (!drawn) {
        fs::remove(partial, ignored);
        if (missing) {
            throw std::runtime_error("drawing " + path + " needs gnuplot (scripts/install-deps installs gnuplot-nox)");
        }
        if (!failure.empty()) said = failure;
        throw std::runtime_error("gnuplot could not draw " + path +
                                 (said.empty() ? std::string() : ": " + oneLineMessage(said)));
    }
    if (endsWith(path, ".svg")) {
        std::string svg;
        {
            std::ifstream in(partial, std::ios::binary);
            svg.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        }
        std::ofstream out(partial, std::ios::binary | std::ios::trunc);
        out << withTextAlternative(svg, plot);
        out.close();
        if (!out) {
            fs::remove(partial, ignored);
            throw std::runtime_error("cannot write the plot to " + path);
        }
    }
    std::error_code renamed;
    fs::rename(partial, target, renamed);
    if (renamed) {
        fs::remove(partial, ignored);
        throw std::runtime_error("cannot write the plot to " + path);
    }
}

}  // namespace simlab
