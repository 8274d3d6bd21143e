// Simbody's integrators, chosen by name.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace SimTK {
class Integrator;
class System;
}  // namespace SimTK

namespace simlab {

/// Every integrator Simbody 3.7 ships, by the name the lab programs accept:
/// RungeKuttaMerson, RungeKutta3, RungeKutta2, RungeKuttaFeldberg, ExplicitEuler,
/// SemiExplicitEuler, SemiExplicitEuler2, Verlet, CPodes.
const std::vector<std::string>& integratorNames();

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
