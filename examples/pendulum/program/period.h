// The period a run's samples show: theta' changes sign at every turning point, each half a period after the last.
// Each sign change is placed between its two samples by linear interpolation of theta'. The error of that is set by
// theta' 's curvature, theta''' = -(g / L) cos(theta) theta', which is zero where theta' is: so it is of third order
// in the sampling interval. The period is twice the mean time between the first and the last turning points found.
#pragma once

#include <cmath>
#include <vector>

#include "pendulum/contract/Pendulum.h"

namespace pendulum {

struct MeasuredPeriod {
    int turningPoints = 0;  ///< sign changes of theta' after t = 0
    double period_s = NAN;  ///< NaN with fewer than two turning points
};

inline MeasuredPeriod measuredPeriod(const std::vector<Sample>& samples) {
    MeasuredPeriod result;
    double first_s = NAN, last_s = NAN;
    for (std::size_t i = 1; i < samples.size(); ++i) {
        const Sample &a = samples[i - 1], &b = samples[i];
        // By their signs, never by their product, which underflows to zero for a swing of 1e-300 degrees.
        const bool crosses = (a.thetaDot_radps < 0 && b.thetaDot_radps > 0) ||
                             (a.thetaDot_radps > 0 && b.thetaDot_radps < 0);
        if (!crosses && !(b.thetaDot_radps == 0 && a.thetaDot_radps != 0)) continue;
        const double t_s = a.time + (b.time - a.time) * a.thetaDot_radps / (a.thetaDot_radps - b.thetaDot_radps);
        if (result.turningPoints++ == 0) first_s = t_s;
        last_s = t_s;
    }
    if (result.turningPoints >= 2) result.period_s = 2 * (last_s - first_s) / (result.turningPoints - 1);
    return result;
}

}  // namespace pendulum
