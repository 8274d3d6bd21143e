// The baby boot against references that share nothing with its Simbody model: the hand-derived equations of motion
// integrated with Boost.Odeint, and a published result (Drake's chaotic-babyboot benchmark, whose values at
// t = 10 s come from MotionGenesis' Kutta-Merson and MATLAB's ode45 runs and agree among themselves to 7
// significant digits in the angles).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "biosim/program/babyboot_reference.h"
#include "biosim/program/course.h"
#include "simlab/digits.h"

namespace {

using babyboot::reference::Parameters;
using babyboot::reference::State;
const double kDegree = M_PI / 180;

/// The published boot: released at qA = 90 deg, qB = 1 deg, at rest.
State publishedStart() { return {90 * kDegree, 1 * kDegree, 0, 0}; }

/// The Simbody model of the boot with its defaults (which are the published boot), at this accuracy.
biosim::Observed simbodyBoot(double accuracy, double finalTime, double dt) {
    const biosim::Declaration d = biosim::declare();
    simlab::RunSettings settings = d.run;
    settings.integrator = "RungeKuttaMerson";
    settings.accuracy = accuracy;
    settings.finalTime = finalTime;
    settings.dt = dt;
    return biosim::observe(d, biosim::resolve(d), settings);
}

}  // namespace

TEST_CASE("the hand-derived boot reproduces the published angles and rates at 10 s", "[babyboot][reference]") {
    // Drake, multibody/benchmarks/chaotic_babyboot (2017): qA = -61.312983340691 deg, qB = -929.47789677244 deg,
    // qA' = -6.7440081040646 rad/s, qB' = -2.7795690128833 rad/s; their own runs agree to 7, 7, 6 and 6 digits.
    const std::vector<State> states = babyboot::reference::integrate(Parameters{}, publishedStart(), {0.0, 10.0});
    const State& end = states.back();
    const double qA = end[0] / kDegree, qB = end[1] / kDegree;
    const double dA = simlab::accuracyDigits(qA, -61.312983340691), dB = simlab::accuracyDigits(qB, -929.47789677244);
    const double dAp = simlab::accuracyDigits(end[2], -6.7440081040646);
    const double dBp = simlab::accuracyDigits(end[3], -2.7795690128833);
    INFO("qA = " << qA << " deg (" << dA << " digits), qB = " << qB << " deg (" << dB << " digits), qA' = " << end[2]
                 << " (" << dAp << "), qB' = " << end[3] << " (" << dBp << ")");
    CHECK(dA >= 7);
    CHECK(dB >= 7);
    CHECK(dAp >= 6);
    CHECK(dBp >= 6);
}

TEST_CASE("the hand-derived boot conserves energy and converges as its tolerance tightens", "[babyboot][reference]") {
    const Parameters p;
    const std::vector<State> tight = babyboot::reference::integrate(p, publishedStart(), {0.0, 10.0}, 1e-14);
    const std::vector<State> looser = babyboot::reference::integrate(p, publishedStart(), {0.0, 10.0}, 1e-12);
    // Energy is zero at the start (the rod horizontal, at rest); its scale is the energy the swing exchanges,
    // g (mA LA + mB LB) = 0.2036 J.
    const double scale = p.g * (p.mA * p.LA + p.mB * p.LB);
    CHECK(std::abs(babyboot::reference::energy(p, tight.back())) / scale < 1e-12);
    // Chaos amplifies the looser run's error, but two digits of tolerance still buy digits at 10 s.
    CHECK(simlab::accuracyDigits(looser.back()[1], tight.back()[1]) >= 6);
}

TEST_CASE("the Simbody boot agrees with the hand-derived one to 10 digits while the chaos allows", "[babyboot]") {
    // Sampled every 0.1 s to 10 s. Digits of qA and qB, relative to a scale of one radian (the angles pass zero),
    // with Simbody's Runge-Kutta-Merson at accuracy 1e-13; the reference is at 1e-14.
    const double finalTime = 10, dt = 0.1;
    const biosim::Observed simbody = simbodyBoot(1e-13, finalTime, dt);
    std::vector<double> times;
    for (double t : simbody.time) times.push_back(t);
    const std::vector<State> reference = babyboot::reference::integrate(Parameters{}, publishedStart(), times);
    REQUIRE(reference.size() == simbody.time.size());
    double lastTenDigits = -1;  // the last sample time up to which every sample agrees to 10 digits
    bool holding = true;
    double digitsAtEnd = 0;
    for (std::size_t k = 0; k < times.size(); ++k) {
        double digits = simlab::kMaxDigits;
        for (int i = 0; i < 2; ++i) {
            digits = std::min(digits, simlab::accuracyDigits(simbody.q[k][i], reference[k][i], 1.0));
        }
        holding = holding && digits >= 10;
        if (holding) lastTenDigits = times[k];
        digitsAtEnd = digits;
    }
    std::printf("Simbody boot vs hand-derived: 10 digits or more up to t = %.1f s; %.1f digits at %.0f s\n",
                lastTenDigits, digitsAtEnd, finalTime);
    INFO("10 digits or more up to t = " << lastTenDigits << " s; " << digitsAtEnd << " digits at " << finalTime << " s");
    // Chaos amplifies every error about a hundredfold in these 10 s; ten digits hold for most of them.
    CHECK(lastTenDigits >= 8.0);
    CHECK(digitsAtEnd >= 9);
}

TEST_CASE("the Simbody boot reproduces the published angles at 10 s", "[babyboot]") {
    const biosim::Observed simbody = simbodyBoot(1e-13, 10, 0.01);
    const double qA = simbody.rows.back()[0], qB = simbody.rows.back()[1];
    const double dA = simlab::accuracyDigits(qA, -61.312983340691), dB = simlab::accuracyDigits(qB, -929.47789677244);
    std::printf("Simbody boot vs published at 10 s: qA %.1f digits, qB %.1f digits\n", dA, dB);
    INFO("qA = " << qA << " deg (" << dA << " digits), qB = " << qB << " deg (" << dB << " digits)");
    // The published values themselves agree among their four runs to 7 significant digits.
    CHECK(dA >= 7);
    CHECK(dB >= 7);
}
