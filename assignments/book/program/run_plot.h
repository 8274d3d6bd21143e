// The figure of a book's run: what the lab program's --plot draws and what a student's feedback shows of their
// run. w_B's components as simulated, every few samples, on Euler's equations integrated apart (a plot needs no
// more than 1e-12 of them), and the relative changes of K and |H|, which should stay at zero. `spin` says which
// spin ("about the intermediate axis"), `how` what ran.
#pragma once

#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "book/contract/BookSpin.h"
#include "book/program/exact.h"
#include "simlab/plot.h"

namespace book {

inline simlab::Plot runPlot(const Scene& scene, const std::string& spin, const std::string& how,
                            const std::vector<Sample>& samples) {
    simlab::Plot plot;
    char title[240];
    std::snprintf(title, sizeof title, "The spinning book: %s, w0 = (%g, %g, %g) rad/s - %s", spin.c_str(),
                  scene.w_B0[0], scene.w_B0[1], scene.w_B0[2], how.c_str());
    plot.title = title;
    const char* names[] = {"wx", "wy", "wz"};
    std::vector<simlab::PlotCurve> w;
    for (const char* name : names) w.emplace_back(std::string("exact ") + name);
    for (const char* name : names) w.emplace_back(std::string("simulated ") + name, true);
    for (int i = 0; i < 3; ++i) w[i].color = w[3 + i].color = i + 1;  // a component's samples on its own line
    simlab::OdeReference<3> reference = exact::eulerReference(scene, 1e-12L);
    const double end = samples.back().time;
    for (int k = 0; k <= 400; ++k) {
        const double t = end * k / 400;
        const std::array<long double, 3>& w_exact = reference.at(t);
        for (int i = 0; i < 3; ++i) w[i].x.push_back(t), w[i].y.push_back(static_cast<double>(w_exact[i]));
    }
    for (std::size_t k : simlab::thinned(samples.size(), 80)) {
        for (int i = 0; i < 3; ++i) w[3 + i].x.push_back(samples[k].time), w[3 + i].y.push_back(samples[k].w_B[i]);
    }
    simlab::PlotCurve K("K / K(0) - 1"), H("|H| / |H(0)| - 1");
    for (const Sample& s : samples) {
        K.x.push_back(s.time), K.y.push_back(s.kineticEnergy / samples.front().kineticEnergy - 1);
        H.x.push_back(s.time), H.y.push_back(s.Hmag / samples.front().Hmag - 1);
    }
    plot.panels.emplace_back("", "w in the book's axes (rad/s)", w);
    plot.panels.emplace_back("time t (s)", "relative change", std::vector<simlab::PlotCurve>{K, H});
    plot.panels.back().scientificY = true;
    return plot;
}

}  // namespace book
