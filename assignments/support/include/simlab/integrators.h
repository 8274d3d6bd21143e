// Simbody's integrators, chosen by name.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace SimTK {
class Integrator;
class System;
}  // namespace SimTK

namespace simlab {

/// One of Simbody 3.7's integrators, as the lab programs, the studies, the harness and the docs know it: the one
/// table of them (kIntegrators), in the order a study runs them.
struct IntegratorKind {
    const char* name;       ///< what --integrator takes
    bool errorControl;      ///< estimates its error and adapts its step to the accuracy
    const char* accuracy;   ///< what the accuracy means for it, at adaptive steps and at fixed steps
};

inline constexpr IntegratorKind kIntegrators[] = {
    {"RungeKuttaMerson", true, "local error per step; at fixed steps, where events are found"},
    {"RungeKutta3", true, "local error per step; at fixed steps, where events are found"},
    {"RungeKutta2", true, "local error per step; at fixed steps, where events are found"},
    {"RungeKuttaFeldberg", true, "local error per step; at fixed steps, where events are found"},
    {"ExplicitEuler", true, "local error per step; at fixed steps, where events are found"},
    {"SemiExplicitEuler", false, "none for its steps, always fixed; where events are found"},
    {"SemiExplicitEuler2", true, "local error per step; at fixed steps, where events are found"},
    {"Verlet", true, "local error per step; at fixed steps, where events are found and its implicit step's "
                     "tolerance, min(1e-4, accuracy/10)"},
    {"CPodes", true, "local error per step; at fixed steps, where events are found"},
};

/// True if `name` is one of kIntegrators'.
inline bool isIntegratorName(std::string_view name) {
    for (const IntegratorKind& kind : kIntegrators) {
        if (name == kind.name) return true;
    }
    return false;
}

/// The names of kIntegrators, in its order.
const std::vector<std::string>& integratorNames();

/// kIntegrators as a table a person reads: name, error control, what the accuracy means.
std::string integratorTable();

/// Throws std::invalid_argument("unknown integrator 'X'; choose one of: ...") unless `name` is one of
/// integratorNames().
void requireIntegratorName(const std::string& name);

/// True for the integrators that estimate their error and adapt their step to an accuracy
/// (all but SemiExplicitEuler, which always takes fixed steps).
bool hasErrorControl(const std::string& name);

/// True for an integrator whose fixed step itself reads the accuracy: Verlet. Its step is explicit in the positions
/// and implicit in the velocities (the trapezoid rule), which Simbody solves by iteration, up to ten times, to a
/// relative change of min(1e-4, accuracy / 10); at a fixed step the accuracy decides how well that is solved, and
/// with it the digits the step keeps. (Any method's fixed step reads it where the model has events, whose times it
/// localizes, and constraints, which it projects to it: the latter moves results by rounding only.)
bool fixedStepUsesAccuracy(const std::string& name);

/// A new integrator of the named kind for `system`. `fixedStep` (s) is the step size of SemiExplicitEuler,
/// which takes it on construction; the others ignore it. Throws std::invalid_argument naming the valid
/// choices if `name` is not one of integratorNames().
std::unique_ptr<SimTK::Integrator> integratorNamed(const std::string& name, const SimTK::System& system,
                                                   double fixedStep);

}  // namespace simlab
