#include "simlab/plot.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
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
    std::error_code renamed;
    fs::rename(partial, target, renamed);
    if (renamed) {
        fs::remove(partial, ignored);
        throw std::runtime_error("cannot write the plot to " + path);
    }
}

}  // namespace simlab
