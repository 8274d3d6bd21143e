// The book's exact solution (Jacobi elliptic functions) against an independent integration of Euler's
// equations (Boost.Odeint's Runge-Kutta-Fehlberg 7(8) at a tolerance of 1e-15), and against the physics.
#include <catch2/catch.hpp>
#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <string>

#include "book/program/exact.h"

namespace book_exact_test {

namespace {

using State = std::array<double, 3>;

// w(t) from Euler's torque-free equations, integrated to a tolerance of 1e-15.
SimTK::Vec3 integrateEuler(const book::Scene& scene, double t) {
    const SimTK::Vec3 I = book::exact::principalMoments(scene);
    State w = {scene.w_B0[0], scene.w_B0[1], scene.w_B0[2]};
    auto euler = [&](const State& x, State& dxdt, double) {
        dxdt[0] = (I[1] - I[2]) * x[1] * x[2] / I[0];
        dxdt[1] = (I[2] - I[0]) * x[2] * x[0] / I[1];
        dxdt[2] = (I[0] - I[1]) * x[0] * x[1] / I[2];
    };
    using namespace boost::numeric::odeint;
    integrate_adaptive(make_controlled(1e-15, 1e-15, runge_kutta_fehlberg78<State>()), euler, w, 0.0, t, 1e-4);
    return SimTK::Vec3(w[0], w[1], w[2]);
}

book::Scene scene(double mass, SimTK::Vec3 dimensions, SimTK::Vec3 w0) {
    book::Scene s;
    s.mass = mass;
    s.dimensions = dimensions;
    s.w_B0 = w0;
    return s;
}

}  // namespace

TEST_CASE("the lab book's moments rank y, x, z from smallest to largest", "[book]") {
    const book::Scene lab;
    const SimTK::Vec3 I = book::exact::principalMoments(lab);
    CHECK(I[0] == Approx(0.4 * (0.09 + 0.0025) / 12));  // Ixx = m (Ly^2 + Lz^2) / 12
    CHECK(I[1] == Approx(0.4 * (0.04 + 0.0025) / 12));
    CHECK(I[2] == Approx(0.4 * (0.04 + 0.09) / 12));
    CHECK(book::exact::axesByMoment(lab) == std::array<int, 3>{1, 0, 2});
    CHECK(book::exact::spin(lab, "min") == SimTK::Vec3(0.2, 7.0, 0.2));
    CHECK(book::exact::spin(lab, "intermediate") == SimTK::Vec3(7.0, 0.2, 0.2));
    CHECK(book::exact::spin(lab, "max") == SimTK::Vec3(0.2, 0.2, 7.0));
}

TEST_CASE("the elliptic solution agrees with Euler's equations integrated independently, to 12 digits", "[book]") {
    const book::Scene lab;
    std::vector<book::Scene> scenes;
    for (const char* axis : {"min", "intermediate", "max"}) scenes.push_back(scene(0.4, lab.dimensions, book::exact::spin(lab, axis)));
    // Spins about no axis in particular, and a book whose axes rank differently.
    scenes.push_back(scene(0.4, lab.dimensions, SimTK::Vec3(-1.3, 2.1, -0.7)));
    scenes.push_back(scene(1.9, SimTK::Vec3(0.35, 0.26, 0.04), SimTK::Vec3(3, -0.5, 1)));
    scenes.push_back(scene(0.25, SimTK::Vec3(0.18, 0.11, 0.025), SimTK::Vec3(0.2, 0.2, -15)));
    for (const book::Scene& s : scenes) {
        const SimTK::Vec3 exact = book::exact::angularVelocity(s, 4.0), integrated = integrateEuler(s, 4.0);
        INFO("w0 = (" << s.w_B0 << "): elliptic (" << exact << "), integrated (" << integrated << ")");
        CHECK(book::exact::angularVelocityDigits(s, 4.0, integrated) >= 12);
        CHECK((book::exact::angularVelocity(s, 0.0) - s.w_B0).norm() < 1e-13);  // and it starts where it should
    }
}

TEST_CASE("along the elliptic solution K and |H| stay constant", "[book]") {
    const book::Scene lab = scene(0.4, book::Scene{}.dimensions, SimTK::Vec3(7.0, 0.2, 0.2));
    const SimTK::Vec3 I = book::exact::principalMoments(lab);
    for (double t = 0; t <= 4; t += 0.37) {
        const SimTK::Vec3 w = book::exact::angularVelocity(lab, t);
        double K = 0, H2 = 0;
        for (int i = 0; i < 3; ++i) {
            K += 0.5 * I[i] * w[i] * w[i];
            H2 += I[i] * I[i] * w[i] * w[i];
        }
        CHECK(K == Approx(book::exact::kineticEnergy(lab)).epsilon(1e-13));
        CHECK(std::sqrt(H2) == Approx(book::exact::angularMomentum(lab)).epsilon(1e-13));
    }
}

TEST_CASE("a spin about the intermediate axis reverses within 4 s; the others do not", "[book]") {
    const book::Scene lab;
    auto reverses = [&](const std::string& axis) {
        book::Scene s = lab;
        s.w_B0 = book::exact::spin(lab, axis);
        const int spin = book::exact::axesByMoment(lab)[axis == "min" ? 0 : axis == "intermediate" ? 1 : 2];
        for (double t = 0; t <= 4; t += 0.01) {
            if (book::exact::angularVelocity(s, t)[spin] < 0) return true;
        }
        return false;
    };
    CHECK(reverses("intermediate"));
    CHECK_FALSE(reverses("min"));
    CHECK_FALSE(reverses("max"));
}

TEST_CASE("the linear growth rate about the intermediate axis is about 4.08 rad/s for the lab book", "[book]") {
    // lambda = w0 sqrt((Ib - Ia)(Ic - Ib) / (Ia Ic)) with Ia = Iyy, Ib = Ixx, Ic = Izz and w0 = 7 rad/s.
    CHECK(book::exact::linearGrowthRate(book::Scene{}, 7.0) == Approx(4.078).epsilon(1e-3));
}

}  // namespace book_exact_test
