// A work-precision curve read as a user reads one: the cheapest cost at which a method keeps a given number of
// digits. Points are (digits kept, cost); the front keeps, in order of cost, each point that keeps more digits
// than every cheaper one, since no one pays more for fewer digits. The cost of D digits is read along the front:
// between the last point short of D and the first that keeps D, log(cost) is taken as linear in digits (work
// grows by a steady factor per digit between neighbouring settings of one method). Below the front's first
// point the cost is that point's: the loosest setting measured already keeps D, and what a looser one would cost
// was not measured.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace simlab::work_precision {

struct Point {
    double digits = 0;   ///< kept over the whole run
    double cost = 0;     ///< evaluations, say (> 0)
    double seconds = 0;  ///< a second cost, read at the same place (0 where not measured)
};

/// The points that no cheaper point matches in digits, in order of cost. Points with a figure that is not
/// finite, or a cost that is not positive, are left out.
inline std::vector<Point> frontOf(std::vector<Point> points) {
    points.erase(std::remove_if(points.begin(), points.end(),
                                [](const Point& p) {
                                    return !std::isfinite(p.digits) || !std::isfinite(p.cost) || !(p.cost > 0);
                                }),
                 points.end());
    std::sort(points.begin(), points.end(), [](const Point& a, const Point& b) {
        return a.cost < b.cost || (a.cost == b.cost && a.digits > b.digits);
    });
    std::vector<Point> front;
    for (const Point& p : points) {
        if (front.empty() || p.digits > front.back().digits) front.push_back(p);
    }
    return front;
}

/// Where a front keeps `digits`, and at what cost.
struct Reading {
    double cost = 0;
    double seconds = 0;
    bool interpolated = false;  ///< false: the front's first point already keeps `digits`
};

/// The cost of `digits` read along `front` (from frontOf); none if no point keeps that many.
inline std::optional<Reading> costAt(const std::vector<Point>& front, double digits) {
    for (std::size_t i = 0; i < front.size(); ++i) {
        if (front[i].digits < digits) continue;
        if (i == 0) return Reading{front[0].cost, front[0].seconds, false};
        if (front[i].digits == digits) return Reading{front[i].cost, front[i].seconds, true};  // on a point
        const Point& lo = front[i - 1];
        const Point& hi = front[i];
        const double t = (digits - lo.digits) / (hi.digits - lo.digits);
        auto along = [t](double a, double b) {
            return a > 0 && b > 0 ? std::exp(std::log(a) + t * (std::log(b) - std::log(a))) : 0.0;
        };
        return Reading{along(lo.cost, hi.cost), along(lo.seconds, hi.seconds), true};
    }
    return std::nullopt;
}

}  // namespace simlab::work_precision
