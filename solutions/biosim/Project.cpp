// The swinging baby boot: a thin uniform rod A hangs from a fixed support N by a revolute joint, and a uniform
// plate B (the boot) turns on a second revolute joint about A's axis. The two axes are perpendicular, and for
// most starts the motion is chaotic (T. R. Kane, "Mechanical demonstration of mathematical stability and
// instability", 1974).
//
// Frames. G (= N) is Ground: x is the swing axis, y up. A's origin is the support's pivot; A's x is the swing axis
// and the rod hangs along -y of A. B's origin is the plate's centre, LB below the pivot on the rod; B's x is the
// plate's normal, B's z lies along the rod and B's y lies in the plate, across the rod. qA = 0 hangs A straight
// down; qB = 0 puts the plate's normal along the swing axis.
//
// The defaults are the boot of Drake's chaotic-babyboot benchmark (MotionGenesis): a uniform rod of 10 g whose
// centre hangs 7.5 cm below the pivot, and a uniform 100 g plate whose centre hangs 20 cm below it, released at
// qA = 90 deg, qB = 1 deg.
#include "biosim/Project.h"

#include <algorithm>
#include <cmath>

namespace biosim {

using namespace SimTK;

namespace {
const double kDegree = Pi / 180;  // rad
}

Declaration declare() {
    Declaration d;
    d.program = "babyboot";
    d.title = "A swinging baby boot: a rod on a pin, a plate on a perpendicular pin at its end";
    // Each moment may take any value a plate could have: the rule below holds the three together, since a rigid
    // body's central moments obey the triangle inequality (each at most the sum of the other two).
    d.parameters = {
        {"mA", "kg", 0.010, 1e-4, 10, "mass of the rod A"},
        {"LA", "m", 0.075, 0, 2, "distance from the pivot to A's mass centre"},
        {"IAx", "kg m^2", 5e-6, 1e-9, 1, "A's central moment of inertia about the swing axis"},
        {"mB", "kg", 0.100, 1e-4, 10, "mass of the plate B"},
        {"LB", "m", 0.20, 1e-3, 2, "distance from the pivot to B's centre, along the rod"},
        {"IBx", "kg m^2", 2.5e-4, 1e-6, 1e-2, "B's central moment about its normal"},
        {"IBy", "kg m^2", 5e-5, 1e-6, 1e-2, "B's central moment about its in-plane axis across the rod"},
        {"IBz", "kg m^2", 2e-4, 1e-6, 1e-2, "B's central moment about the rod's axis"},
        {"g", "m/s^2", 9.81, 0, 20, "gravity, along -y of Ground"},
        {"qA", "deg", 90, -180, 180, "initial angle of the rod from straight down"},
        {"qB", "deg", 1, -180, 180, "initial angle of the plate's normal from the swing axis"},
        {"uA", "rad/s", 0, -20, 20, "initial rate of qA"},
        {"uB", "rad/s", 0, -20, 20, "initial rate of qB"},
    };
    d.rules = {
        {"B's central moments obey the triangle inequality: each is at most the sum of the other two",
         [](const Parameters& p) {
             // A thin plate sits on the boundary (its moment about the normal is the sum of the other two), and
             // moments rounded to six digits may miss it a little: the rule allows what Simbody itself allows, a
             // moment per unit mass past the sum by under 1.5e-8 m^2 (sqrt of double's epsilon).
             const double x = p["IBx"], y = p["IBy"], z = p["IBz"], slack = 1e-8 * p["mB"];
             return x <= y + z + slack && y <= x + z + slack && z <= x + y + slack;
         }},
    };
    d.columns = {
        {"qA", "deg", "the rod's angle from straight down"},
        {"qB", "deg", "the plate's angle about the rod"},
        {"uA", "rad/s", "the rate of qA"},
        {"uB", "rad/s", "the rate of qB"},
        {"energy", "J", "kinetic plus gravitational potential energy (zero potential at the pivot)"},
    };
    d.claims.degreesOfFreedom = 2;  // the two joint angles
    d.claims.energyConserved = true;  // frictionless pins, no air: nothing dissipates
    d.claims.atRest = {{"g", 0}, {"uA", 0}, {"uB", 0}};
    d.run.finalTime = 10;
    d.run.dt = 0.01;
    d.run.accuracy = 1e-7;
    return d;
}

void buildModel(const Parameters& p, Model& model) {
    // A: a thin rod along its y axis, its mass centre LA below the pivot; no moment about its own axis.
    const Vec3 p_AAcm(0, -p["LA"], 0);
    const Inertia I_AAcm(p["IAx"], 0, p["IAx"]);
    Body::Rigid rodA(MassProperties(p["mA"], p_AAcm, I_AAcm.shiftFromMassCenter(p_AAcm, p["mA"])));
    // How --animate and --replay draw it (nothing here changes the motion): a thin cylinder from the pivot to the
    // plate's pin (Simbody's cylinders lie along their y axis).
    rodA.addDecoration(Vec3(0, -p["LB"] / 2, 0),
                       DecorativeCylinder(0.01, p["LB"] / 2).setColor(Vec3(0.45, 0.3, 0.15)));

    // B: the plate, with its origin at its centre and the moments named by the axes above.
    Body::Rigid plateB(MassProperties(p["mB"], Vec3(0), Inertia(p["IBx"], p["IBy"], p["IBz"])));
    // Drawn as the uniform brick with these moments: its half-lengths h satisfy I_x = m (h_y^2 + h_z^2) / 3, ...
    const Vec3 I_B(p["IBx"], p["IBy"], p["IBz"]);
    Vec3 half;
    for (int i = 0; i < 3; ++i) {
        half[i] = std::sqrt(std::max(1.5 * (I_B[(i + 1) % 3] + I_B[(i + 2) % 3] - I_B[i]) / p["mB"], 1e-6));
    }
    plateB.addDecoration(Transform(), DecorativeBrick(half).setColor(Vec3(0.2, 0.45, 0.8)));

    // A Pin turns about the z axis of its frames. The first pin's z is Ground's x (the swing axis) ...
    const Rotation R_GF(Pi / 2, YAxis);
    model.bodies["A"] = MobilizedBody::Pin(model.matter.Ground(), Transform(R_GF, Vec3(0)), rodA,
                                           Transform(R_GF, Vec3(0)));
    // ... the second pin's z is the rod's axis (A's y), at B's centre, LB below the pivot.
    const Rotation R_AF(-Pi / 2, XAxis);
    model.bodies["B"] = MobilizedBody::Pin(model.bodies["A"], Transform(R_AF, Vec3(0, -p["LB"], 0)), plateB,
                                           Transform());

    Force::UniformGravity(model.forces, model.matter, Vec3(0, -p["g"], 0));
}

State initialState(const Parameters& p, const Model& model) {
    State state = model.system.realizeTopology();
    model.body("A").setOneQ(state, 0, p["qA"] * kDegree);
    model.body("B").setOneQ(state, 0, p["qB"] * kDegree);
    model.body("A").setOneU(state, 0, p["uA"]);
    model.body("B").setOneU(state, 0, p["uB"]);
    return state;
}

std::vector<double> sample(const Parameters&, const Model& model, const State& state) {
    const double qA = model.body("A").getOneQ(state, 0);
    const double qB = model.body("B").getOneQ(state, 0);
    return {qA / kDegree, qB / kDegree, model.body("A").getOneU(state, 0), model.body("B").getOneU(state, 0),
            model.system.calcEnergy(state)};
}

std::vector<Experiment> experiments() {
    const Parameters defaults = [] {
        std::map<std::string, double> values;
        for (const Parameter& parameter : declare().parameters) values[parameter.name] = parameter.value;
        return Parameters(values);
    }();
    // With the plate edge-on (qB = 0, uB = 0) the plate never turns and the boot is a compound pendulum:
    // qA'' = -(m g L / I) sin qA, with m L = mA LA + mB LB and I the moment about the swing axis at the pivot.
    auto omega = [](const Parameters& p) {
        const double mL = p["mA"] * p["LA"] + p["mB"] * p["LB"];
        const double I = p["IAx"] + p["IBx"] + p["mA"] * p["LA"] * p["LA"] + p["mB"] * p["LB"] * p["LB"];
        return std::sqrt(p["g"] * mL / I);
    };
    // Its exact period from an amplitude of 60 deg: T = (4 / omega) K(sin(30 deg)), K the complete elliptic
    // integral of the first kind.
    const double period = 4 / omega(defaults) * std::comp_ellint_1(std::sin(30 * kDegree));

    return {
        conserved("the plate spins at a constant rate while the rod hangs still", "uB")
            .with({{"qA", 0}, {"uA", 0}, {"uB", 3}})
            .within(1e-9),
        conserved("the energy keeps its value through the chaos", "energy").with({{"qA", 60}}).within(1e-6),
        periodic("an edge-on plate swings with the compound pendulum's exact period", "qA", period)
            .with({{"qA", 60}, {"qB", 0}, {"uB", 0}})
            .within(1e-6),
        matches("small edge-on swings follow qA = qA0 cos(omega t)", "qA",
                [omega](const Parameters& p, double t) { return p["qA"] * std::cos(omega(p) * t); })
            .with({{"qA", 0.5}, {"qB", 0}, {"uB", 0}})
            .until(2)
            .within(1e-3),
        symmetric("a mirrored start swings as the mirror image", "qA", {{"qA", -90}, {"qB", -1}}).within(1e-9),
    };
}

double answer(const Parameters& p) {
    // How long can a run at the default accuracy be trusted? Run it beside one 10^4 times more accurate and find
    // when their plate angles first differ by more than one degree, looking over the first 15 s (they part near
    // 9.5 s; a model whose runs agree longer answers 15: "15 s at least").
    simlab::RunSettings settings = declare().run;
    settings.finalTime = 15;
    const Run run = simulate(p, settings);
    settings.accuracy /= 1e4;
    const Run reference = simulate(p, settings);
    const std::vector<double> qB = run.column("qB");
    const std::vector<double> qBref = reference.column("qB");
    for (std::size_t k = 0; k < qB.size(); ++k) {
        if (std::abs(qB[k] - qBref[k]) > 1.0) return run.time[k];
    }
    return settings.finalTime;
}

}  // namespace biosim
