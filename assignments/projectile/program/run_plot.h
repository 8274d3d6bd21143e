// The figure of a projectile's run: what the lab program's --plot draws and what a student's feedback shows of
// their run. The flight y(x) as simulated, every few samples, on the exact parabola, and the ground hit the event
// handler found (if `hit.found`); `how` says what ran.
#pragma once

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "projectile/contract/ProjectileMotion.h"
#include "projectile/program/exact.h"
#include "simlab/plot.h"

namespace projectile {

inline simlab::Plot runPlot(const Scene& scene, const std::string& how, const std::vector<Sample>& samples,
                              const GroundHit& hit) {
    simlab::Plot plot;
    char title[300];
    std::snprintf(title, sizeof title, "Projectile: %g m/s at %g degrees, g = %g m/s^2 - %s", scene.launchSpeed,
                  scene.launchAngleDegrees, scene.gravity, how.c_str());
    plot.title = title;
    simlab::PlotCurve simulated("simulated", true), parabola("exact parabola");
    for (std::size_t i : simlab::thinned(samples.size(), 60)) {
        simulated.x.push_back(samples[i].x), simulated.y.push_back(samples[i].y);
    }
    const double end = std::min(samples.back().time, exact::flightTime(scene));
    for (int k = 0; k <= 200; ++k) {
        const double t = end * k / 200;
        parabola.x.push_back(exact::x(scene, t)), parabola.y.push_back(exact::y(scene, t));
    }
    simlab::PlotPanel panel("range x (m)", "height y (m)", {parabola, simulated});
    if (hit.found) {
        char label[96];
        std::snprintf(label, sizeof label, "ground hit: t = %.6g s, x = %.6g m", hit.time, hit.x);
        panel.marks.push_back({hit.x, 0.0, label});
    }
    plot.panels.push_back(panel);
    return plot;
}

}  // namespace projectile
