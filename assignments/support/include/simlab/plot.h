// Plots of a run for people: the lab programs' --plot. A Plot is data (panels of curves and marked points); one
// function draws it with gnuplot's file terminals, PNG or SVG, so that it renders on any machine, a display or not.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace simlab {

/// One curve: its points, drawn as a line, or as markers where it is a simulation's samples.
struct PlotCurve {
    explicit PlotCurve(std::string title_ = "", bool markers_ = false) : title(std::move(title_)), markers(markers_) {}
    std::string title;
    std::vector<double> x, y;  ///< same length; a point with a non-finite coordinate is left out
    bool markers = false;      ///< markers (samples) rather than a line (an exact solution)
    bool dashed = false;       ///< a dashed line, for a second line of the same kind
    int color = 0;             ///< gnuplot's colour number; 0 takes the next one in turn
};

/// A point to point out, drawn large, its label in the key (the projectile's ground hit, say).
struct PlotMark {
    double x = 0, y = 0;
    std::string label;
};

/// One panel: axes and what is drawn on them. Panels stack top to bottom and share nothing.
struct PlotPanel {
    PlotPanel(std::string xLabel_, std::string yLabel_, std::vector<PlotCurve> curves_ = {})
        : xLabel(std::move(xLabel_)), yLabel(std::move(yLabel_)), curves(std::move(curves_)) {}
    std::string xLabel, yLabel;
    std::vector<PlotCurve> curves;
    std::vector<PlotMark> marks;
    bool scientificY = false;  ///< tick labels like 1.0e-12, for relative changes
    /// Logarithmic axes (a drift against time over decades, say): a curve's point at or below zero on such an axis
    /// is left out, as a non-finite one is.
    bool logX = false, logY = false;
};

/// A figure: its title (the run's settings) and its panels.
struct Plot {
    std::string title;
    std::vector<PlotPanel> panels;
};

/// What is wrong with `path` as a plot file ("" if nothing): its name must end in .png or .svg, which also
/// chooses the format.
std::string plotPathProblem(const std::string& path);

/// Draws `plot` into `path` (PNG or SVG, by its extension) with gnuplot, replacing the file only once the
/// drawing is whole. An SVG also carries its text alternative: its <title> is the plot's, its <desc> what
/// describePlot says, and its <metadata id="simlab-plot-data"> the points drawn as JSON (plotDataJson), from which
/// a page shows them as a table. Throws std::runtime_error, in one line, when the path is not a plot file,
/// gnuplot is not installed, or gnuplot fails (its first line of complaint).
void drawPlot(const Plot& plot, const std::string& path);

/// What `plot` shows, in a few sentences of plain text for a reader who cannot see it: for each panel, what is
/// drawn against what and over which range, each curve's ends and extremes, how far a simulation's samples stray
/// from the line they are drawn on (when more than the drawing shows), and the points marked. Figures are given
/// to 4 significant digits, as read off the data, not the picture.
std::string describePlot(const Plot& plot);

/// The points `plot` draws, as JSON: {"title", "panels": [{"x", "y" (the axes' labels), "curves": [{"title",
/// "samples" (true for markers), "points" (how many it draws), "x", "y" (at most kPlotDataRows of them, evenly
/// spread, the first and the last among them)}], "marks": [{"label", "x", "y"}]}]}. Points not drawn (not finite,
/// or at or below zero on a logarithmic axis) are left out.
std::string plotDataJson(const Plot& plot);
/// The most rows of one curve in plotDataJson.
constexpr std::size_t kPlotDataRows = 60;

/// At most `most` of the indices 0 ... n-1, evenly spread, the first and the last among them: the samples to mark
/// without hiding the line beneath them.
std::vector<std::size_t> thinned(std::size_t n, std::size_t most);

}  // namespace simlab
