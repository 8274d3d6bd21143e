// The figure of a pendulum's run: what the lab program's --plot draws and what a student's feedback shows of
// their run. theta(t) and theta'(t) as simulated, every few samples, on the exact swing drawn as a line; `how`
// says what ran (the settings, or the results file it was read from).
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "pendulum/contract/Pendulum.h"
#include "pendulum/program/exact.h"
#include "simlab/plot.h"

namespace pendulum {

inline simlab::Plot runPlot(const Scene& scene, const std::string& how, const std::vector<Sample>& samples) {
    simlab::Plot plot;
    char title[300];
    std::snprintf(title, sizeof title, "A pendulum's swing: L = %g m, g = %g m/s^2, released at %g degrees - %s",
                  scene.length_m, scene.gravity_mps2, scene.releaseAngle_deg, how.c_str());
    plot.title = title;
    simlab::PlotCurve theta("simulated theta", true), thetaDot("simulated theta'", true);
    simlab::PlotCurve thetaExact("exact: 2 asin(k sn(K - w0 t, k))"), thetaDotExact("exact: -2 k w0 cn(K - w0 t, k)");
    for (std::size_t i : simlab::thinned(samples.size(), 80)) {
        theta.x.push_back(samples[i].time), theta.y.push_back(samples[i].theta_rad);
        thetaDot.x.push_back(samples[i].time), thetaDot.y.push_back(samples[i].thetaDot_radps);
    }
    const double end_s = samples.empty() ? 0.0 : samples.back().time;
    for (int k = 0; k <= 400; ++k) {
        const double t_s = end_s * k / 400;
        const exact::Angle a = exact::at(scene, t_s);
        thetaExact.x.push_back(t_s), thetaExact.y.push_back(a.theta_rad);
        thetaDotExact.x.push_back(t_s), thetaDotExact.y.push_back(a.thetaDot_radps);
    }
    plot.panels.emplace_back("", "angle theta (rad)", std::vector<simlab::PlotCurve>{thetaExact, theta});
    plot.panels.emplace_back("time t (s)", "rate theta' (rad/s)", std::vector<simlab::PlotCurve>{thetaDotExact, thetaDot});
    return plot;
}

}  // namespace pendulum
