// What a student's model contains: bodies, the mobilizer of each, and its degrees of freedom.
#pragma once

#include <string>
#include <vector>

namespace SimTK {
class SimbodyMatterSubsystem;
class State;
}  // namespace SimTK

namespace simlab {

struct MobilizerInfo {
    int body = 0;      ///< mobilized body index (Ground is 0)
    std::string kind;  ///< "Slider", "Free", "Planar", ...
    int nq = 0;        ///< generalized coordinates
    int nu = 0;        ///< generalized speeds (mobilities)
    double mass = 0;   ///< kg; 0 for a massless body (an intermediate frame between mobilizers)
};

struct ModelInfo {
    int bodies = 0;                  ///< bodies other than Ground
    int mobilities = 0;              ///< sum of nu over the mobilizers
    int constraintEquations = 0;     ///< velocity-level constraint equations
    int independentConstraints = 0;  ///< of those, how many constrain independently: the rank of their Jacobian
                                     ///< (a constraint written twice removes one motion, not two)
    std::vector<MobilizerInfo> mobilizers;

    /// Independent motions the model allows: mobilities minus independent constraints.
    int degreesOfFreedom() const { return mobilities - independentConstraints; }
    /// Bodies with mass (massless ones only join mobilizers together).
    int massiveBodies() const;
    /// One line, e.g. "1 body: body 1 on a Free mobilizer (6 dof)".
    std::string summary() const;
    /// True if some body is on a mobilizer of this kind.
    bool uses(const std::string& kind) const;
};

/// Describe the model in `matter`. `state` must come from the model's system (topology realized).
ModelInfo describeModel(const SimTK::SimbodyMatterSubsystem& matter, const SimTK::State& state);

/// Throws std::runtime_error, in one line, if `matter` is told how to move rather than left to be simulated: a body
/// with a Motion, or a constraint that can make a coordinate follow a function of time (PrescribedMotion, or a
/// Custom constraint). A lab's answer would then be written into the model, not computed by the integrator.
void requireSimulatedMotion(const SimTK::SimbodyMatterSubsystem& matter);

/// Name of a mobilizer kind as Simbody spells it ("Slider", "Free", ...), or "Custom".
std::string mobilizerKind(const SimTK::SimbodyMatterSubsystem& matter, int bodyIndex);

}  // namespace simlab
