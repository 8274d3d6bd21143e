#include "simlab/model_info.h"

#include <sstream>
#include <stdexcept>

#include "Simbody.h"

namespace simlab {

std::string mobilizerKind(const SimTK::SimbodyMatterSubsystem& matter, int bodyIndex) {
    using M = SimTK::MobilizedBody;
    const M& b = matter.getMobilizedBody(SimTK::MobilizedBodyIndex(bodyIndex));
    // Translation is also spelled Cartesian; Pin, Revolute; Slider, Prismatic; Ball, Spherical.
    if (M::Ground::isInstanceOf(b)) return "Ground";
    if (M::Weld::isInstanceOf(b)) return "Weld";
    if (M::Pin::isInstanceOf(b)) return "Pin";
    if (M::Slider::isInstanceOf(b)) return "Slider";
    if (M::Screw::isInstanceOf(b)) return "Screw";
    if (M::Universal::isInstanceOf(b)) return "Universal";
    if (M::Cylinder::isInstanceOf(b)) return "Cylinder";
    if (M::BendStretch::isInstanceOf(b)) return "BendStretch";
    if (M::Planar::isInstanceOf(b)) return "Planar";
    if (M::SphericalCoords::isInstanceOf(b)) return "SphericalCoords";
    if (M::Gimbal::isInstanceOf(b)) return "Gimbal";
    if (M::Ball::isInstanceOf(b)) return "Ball";
    if (M::Ellipsoid::isInstanceOf(b)) return "Ellipsoid";
    if (M::Translation::isInstanceOf(b)) return "Translation";
    if (M::LineOrientation::isInstanceOf(b)) return "LineOrientation";
    if (M::FreeLine::isInstanceOf(b)) return "FreeLine";
    if (M::Free::isInstanceOf(b)) return "Free";
    if (M::Bushing::isInstanceOf(b)) return "Bushing";
    return "Custom";
}

ModelInfo describeModel(const SimTK::SimbodyMatterSubsystem& matter, const SimTK::State& state) {
    // Constraint equations are counted at Instance stage; realize a copy so the caller's state is untouched.
    SimTK::State s = state;
    matter.getSystem().realize(s, SimTK::Stage::Instance);
    ModelInfo info;
    info.bodies = matter.getNumBodies() - 1;
    info.mobilities = s.getNU();
    info.constraintEquations = s.getNUErr();
    if (info.constraintEquations > 0) {
        // The constraints' Jacobian G (one row per constraint equation, one column per mobility) in the initial
        // state: its rank is how many motions they really remove. Velocity-level constraints need that stage.
        matter.getSystem().realize(s, SimTK::Stage::Velocity);
        SimTK::Matrix G;
        matter.calcG(s, G);
        info.independentConstraints = G.nrow() > 0 ? SimTK::FactorQTZ(G).getRank() : 0;
    }
    for (int i = 1; i < matter.getNumBodies(); ++i) {
        const SimTK::MobilizedBody& b = matter.getMobilizedBody(SimTK::MobilizedBodyIndex(i));
        info.mobilizers.push_back({i, mobilizerKind(matter, i), b.getNumQ(s), b.getNumU(s), b.getBodyMass(s)});
    }
    return info;
}

std::string ModelInfo::summary() const {
    std::ostringstream out;
    out << bodies << (bodies == 1 ? " body" : " bodies");
    const char* separator = ": ";
    for (const MobilizerInfo& m : mobilizers) {
        out << separator << (m.mass > 0 ? "body " : "massless body ") << m.body << " on a " << m.kind
            << " mobilizer (" << m.nu << " dof)";
        separator = ", ";
    }
    if (constraintEquations > 0) {
        out << "; " << constraintEquations
            << (constraintEquations == 1 ? " constraint equation" : " constraint equations");
        if (independentConstraints != constraintEquations) out << " (" << independentConstraints << " independent)";
    }
    out << "; " << degreesOfFreedom() << (degreesOfFreedom() == 1 ? " degree" : " degrees") << " of freedom";
    return out.str();
}

int ModelInfo::massiveBodies() const {
    int count = 0;
    for (const MobilizerInfo& m : mobilizers) count += m.mass > 0;
    return count;
}

bool ModelInfo::uses(const std::string& kind) const {
    for (const MobilizerInfo& m : mobilizers) {
        if (m.kind == kind) return true;
    }
    return false;
}

void requireSimulatedMotion(const SimTK::SimbodyMatterSubsystem& matter) {
    for (int i = 1; i < matter.getNumBodies(); ++i) {
        if (matter.getMobilizedBody(SimTK::MobilizedBodyIndex(i)).hasMotion()) {
            throw std::runtime_error("the model gives body " + std::to_string(i) +
                                     " a Motion, which dictates how it moves: the lab asks for its motion to be "
                                     "simulated from forces, not written into the model");
        }
    }
    for (int i = 0; i < matter.getNumConstraints(); ++i) {
        const SimTK::Constraint& c = matter.getConstraint(SimTK::ConstraintIndex(i));
        if (SimTK::Constraint::PrescribedMotion::isInstanceOf(c) || SimTK::Constraint::Custom::isInstanceOf(c)) {
            throw std::runtime_error("the model has a constraint that can make a coordinate follow a function of "
                                     "time (constraint " + std::to_string(i) + ", " +
                                     (SimTK::Constraint::Custom::isInstanceOf(c) ? "Custom" : "PrescribedMotion") +
                                     "): the lab asks for the motion to be simulated from forces");
        }
    }
}

}  // namespace simlab
