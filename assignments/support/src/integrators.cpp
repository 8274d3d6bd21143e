#include "simlab/integrators.h"

#include <cstdio>
#include <stdexcept>

#include "Simbody.h"

namespace simlab {

const std::vector<std::string>& integratorNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> out;
        for (const IntegratorKind& kind : kIntegrators) out.emplace_back(kind.name);
        return out;
    }();
    return names;
}

std::string integratorTable() {
    std::string out = "integrator          error control  what the accuracy means\n";
    char line[320];
    for (const IntegratorKind& kind : kIntegrators) {
        std::snprintf(line, sizeof line, "%-19s %-13s  %s\n", kind.name, kind.errorControl ? "yes" : "no (fixed)",
                      kind.accuracy);
        out += line;
    }
    return out;
}

void requireIntegratorName(const std::string& name) {
    std::string list;
    for (const std::string& known : integratorNames()) {
        if (known == name) return;
        list += (list.empty() ? "" : ", ") + known;
    }
    throw std::invalid_argument("unknown integrator '" + name + "'; choose one of: " + list);
}

bool hasErrorControl(const std::string& name) {
    requireIntegratorName(name);
    for (const IntegratorKind& kind : kIntegrators) {
        if (name == kind.name) return kind.errorControl;
    }
    return false;
}

bool fixedStepUsesAccuracy(const std::string& name) {
    requireIntegratorName(name);
    return name == "Verlet";
}

std::unique_ptr<SimTK::Integrator> integratorNamed(const std::string& name, const SimTK::System& system,
                                                   double fixedStep) {
    using namespace SimTK;
    requireIntegratorName(name);
    if (name == "RungeKuttaMerson") return std::make_unique<RungeKuttaMersonIntegrator>(system);
    if (name == "RungeKutta3") return std::make_unique<RungeKutta3Integrator>(system);
    if (name == "RungeKutta2") return std::make_unique<RungeKutta2Integrator>(system);
    if (name == "RungeKuttaFeldberg") return std::make_unique<RungeKuttaFeldbergIntegrator>(system);
    if (name == "ExplicitEuler") return std::make_unique<ExplicitEulerIntegrator>(system);
    if (name == "SemiExplicitEuler") {
        if (!(fixedStep > 0)) throw std::invalid_argument("SemiExplicitEuler needs a positive fixed step");
        return std::make_unique<SemiExplicitEulerIntegrator>(system, fixedStep);
    }
    if (name == "SemiExplicitEuler2") return std::make_unique<SemiExplicitEuler2Integrator>(system);
    if (name == "Verlet") return std::make_unique<VerletIntegrator>(system);
    return std::make_unique<CPodesIntegrator>(system);  // the list's last name
}

}  // namespace simlab
