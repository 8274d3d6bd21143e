// The figure of an apple's run: what the lab program's --plot draws and what a student's feedback shows of their
// run. y(t) and y'(t) as simulated, every few samples, on the exact fall drawn as a line; `how` says what ran (the
// settings, or the results file it was read from).
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "apple/contract/NewtonsApple.h"
#include "apple/program/exact.h"
#include "simlab/plot.h"

namespace apple {

inline simlab::Plot runPlot(const Scene& scene, const std::string& how, const std::vector<Sample>& samples) {
    simlab::Plot plot;
    char title[300];
    std::snprintf(title, sizeof title, "Newton's apple: dropped from %g m, g = %g m/s^2 - %s", scene.dropHeight,
                  scene.gravity, how.c_str());
    plot.title = title;
    simlab::PlotCurve y("simulated y", true), vy("simulated y'", true);
    simlab::PlotCurve yExact("exact: h - g t^2/2"), vyExact("exact: -g t");
    for (std::size_t i : simlab::thinned(samples.size(), 60)) {
        y.x.push_back(samples[i].time), y.y.push_back(samples[i].yLocation);
        vy.x.push_back(samples[i].time), vy.y.push_back(samples[i].yVelocity);
    }
    const double end = samples.back().time;
    for (int k = 0; k <= 200; ++k) {
        const double t = end * k / 200;
        yExact.x.push_back(t), yExact.y.push_back(exact::yLocation(scene, t));
        vyExact.x.push_back(t), vyExact.y.push_back(exact::yVelocity(scene, t));
    }
    plot.panels.emplace_back("", "height y (m)", std::vector<simlab::PlotCurve>{yExact, y});
    plot.panels.emplace_back("time t (s)", "velocity y' (m/s)", std::vector<simlab::PlotCurve>{vyExact, vy});
    return plot;
}

}  // namespace apple
