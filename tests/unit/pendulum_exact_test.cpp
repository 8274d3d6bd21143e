// The pendulum's exact swing (examples/pendulum: Jacobi elliptic functions and the complete elliptic integral)
// against an independent integration of theta'' = -(g/L) sin theta (Boost.Odeint's Runge-Kutta-Fehlberg 7(8) at a
// tolerance of 1e-14), and against the physics: the small-swing series of the period, the energy, the half swing.
#include <catch2/catch.hpp>
#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <vector>

#include "pendulum/program/exact.h"
#include "pendulum/program/period.h"

namespace pendulum_exact_test {

namespace {

using State = std::array<double, 2>;  // theta, theta'

State integrateSwing(const pendulum::Scene& scene, double t) {
    State x = {pendulum::exact::releaseAngle_rad(scene), 0};
    const double w2 = scene.gravity_mps2 / scene.length_m;
    auto swing = [&](const State& s, State& dsdt, double) {
        dsdt[0] = s[1];
        dsdt[1] = -w2 * std::sin(s[0]);
    };
    using namespace boost::numeric::odeint;
    integrate_adaptive(make_controlled(1e-14, 1e-14, runge_kutta_fehlberg78<State>()), swing, x, 0.0, t, 1e-4);
    return x;
}

pendulum::Scene released(double angle_deg, double length_m = 1.0, double gravity_mps2 = 9.81) {
    pendulum::Scene s;
    s.releaseAngle_deg = angle_deg;
    s.length_m = length_m;
    s.gravity_mps2 = gravity_mps2;
    return s;
}

}  // namespace

TEST_CASE("the exact swing is the integrated swing, from 10 to 179 degrees", "[pendulum][exact]") {
    for (const double angle : {10.0, 90.0, 150.0, 179.0}) {
        for (const double t : {0.37, 1.9, 6.1}) {
            const pendulum::Scene scene = released(angle, 0.8, 9.81);
            const pendulum::exact::Angle exact = pendulum::exact::at(scene, t);
            const State integrated = integrateSwing(scene, t);
            const double theta0 = pendulum::exact::releaseAngle_rad(scene);
            INFO("released at " << angle << " deg, t = " << t << " s");
            // Errors against the release angle and its natural rate: theta passes zero twice a swing.
            CHECK(std::abs(exact.theta_rad - integrated[0]) < 1e-9 * theta0);
            CHECK(std::abs(exact.thetaDot_radps - integrated[1]) <
                  1e-9 * theta0 * pendulum::exact::naturalFrequency_radps(scene));
        }
    }
}

TEST_CASE("the exact period tends to the small swing's, as its series says", "[pendulum][exact]") {
    // T = 2 pi sqrt(L/g) (1 + theta0^2/16 + 11 theta0^4/3072 + ...): at 1 degree the next term is below 1e-12.
    const pendulum::Scene scene = released(1.0, 2.0, 9.81);
    const double theta0 = pendulum::exact::releaseAngle_rad(scene);
    const double series = 2 * SimTK::Pi * std::sqrt(2.0 / 9.81) *
                          (1 + theta0 * theta0 / 16 + 11 * std::pow(theta0, 4) / 3072);
    CHECK(std::abs(pendulum::exact::period_s(scene) / series - 1) < 1e-12);
    // Near the top the period grows without bound, like log(1 / (pi - theta0)).
    CHECK(pendulum::exact::period_s(released(179.9)) > pendulum::exact::period_s(released(179)) + 1.0);
}

TEST_CASE("the exact swing keeps its energy and turns at -theta0 after half a period", "[pendulum][exact]") {
    const pendulum::Scene scene = released(150);
    const double scale_J = scene.mass_kg * scene.gravity_mps2 * scene.length_m;
    for (const double t : {0.0, 0.5, 1.3, 2.9}) {
        const pendulum::exact::Angle a = pendulum::exact::at(scene, t);
        CHECK(std::abs(pendulum::exact::energyOf_J(scene, a.theta_rad, a.thetaDot_radps) -
                       pendulum::exact::mechanicalEnergy_J(scene)) < 1e-12 * scale_J);
    }
    const pendulum::exact::Angle half = pendulum::exact::at(scene, pendulum::exact::period_s(scene) / 2);
    CHECK(std::abs(half.theta_rad + pendulum::exact::releaseAngle_rad(scene)) < 1e-12);
    CHECK(std::abs(half.thetaDot_radps) < 1e-9);
}

TEST_CASE("a release to the other side swings as the mirror image, at 50-digit truths", "[pendulum][exact]") {
    // theta(t) and theta'(t) from sin(theta / 2) = k sn(K - w0 t, k) evaluated by mpmath at 50 digits (mp.dps = 50;
    // at -170 degrees its odefun, a Taylor integration of theta'' = -(g/L) sin theta, agrees to 20 digits), with
    // L = 1 m and g = 9.81 m/s^2. Boost's elliptic functions in double are good to a few units in the 15th digit,
    // except where theta0 is near 180 degrees: there sn is near 1 and asin magnifies its rounding.
    struct Truth {
        double angle_deg, t_s, theta_rad, thetaDot_radps, tolerance;  // tolerance: against theta0, and w0 theta0
    };
    const Truth truths[] = {
        {-10, 1.0, 0.1745120868176276168, 0.0084256570952214649433, 1e-13},
        {-10, 0.37, -0.070268091275212006234, 0.49965379173014914051, 1e-13},
        {-170, 1.0, -1.292380313506464094, 4.9713329844346886121, 1e-12},
        {-170, 0.37, -2.8370928029665742126, 0.77750015396228180535, 1e-12},
        {-179.9, 1.0, -3.1215516460376768448, 0.062530736638431634687, 1e-9},
        {-179.9, 0.37, -3.1385381687741565784, 0.0078513098086060463517, 1e-9},
    };
    for (const Truth& truth : truths) {
        const pendulum::Scene scene = released(truth.angle_deg);
        const double theta0 = std::abs(pendulum::exact::releaseAngle_rad(scene));
        const double w0 = pendulum::exact::naturalFrequency_radps(scene);
        const pendulum::exact::Angle a = pendulum::exact::at(scene, truth.t_s);
        const pendulum::exact::Angle mirror = pendulum::exact::at(released(-truth.angle_deg), truth.t_s);
        INFO("released at " << truth.angle_deg << " deg, t = " << truth.t_s << " s");
        CHECK(std::abs(a.theta_rad - truth.theta_rad) < truth.tolerance * theta0);
        CHECK(std::abs(a.thetaDot_radps - truth.thetaDot_radps) < truth.tolerance * w0 * theta0);
        CHECK(a.theta_rad == -mirror.theta_rad);
        CHECK(a.thetaDot_radps == -mirror.thetaDot_radps);
    }
    // The period does not depend on the side.
    CHECK(pendulum::exact::period_s(released(-150)) == pendulum::exact::period_s(released(150)));
}

TEST_CASE("the period the samples show is the exact one, at any amplitude down to 1e-300 degrees", "[pendulum][period]") {
    // The exact swing sampled every 0.01 s for 10 s, from rest as a run starts: its turning points, placed by linear interpolation of theta',
    // give the period 4 K(k) / w0 to the interpolation's third order (about 1e-7 s here). At 1e-300 degrees theta' is
    // about 1e-302 rad/s, and the product of two samples' rates, 1e-604, is no double: the crossings are found by sign.
    for (const double angle_deg : {150.0, 10.0, -10.0, 1e-6, 1e-300, -1e-300}) {
        const pendulum::Scene scene = released(angle_deg);
        std::vector<pendulum::Sample> samples;
        for (int i = 0; i <= 1000; ++i) {
            const double t_s = 0.01 * i;
            const pendulum::exact::Angle a = pendulum::exact::at(scene, t_s);
            samples.push_back({t_s, a.theta_rad, i == 0 ? 0.0 : a.thetaDot_radps, 0});  // released at rest
        }
        const pendulum::MeasuredPeriod measured = pendulum::measuredPeriod(samples);
        const double exact_s = pendulum::exact::period_s(scene);
        INFO("released at " << angle_deg << " deg: " << measured.turningPoints << " turning points");
        CHECK(measured.turningPoints == static_cast<int>(std::floor(2 * 10 / exact_s)));
        CHECK(std::abs(measured.period_s - exact_s) < 1e-6 * exact_s);
    }
}

}  // namespace pendulum_exact_test
