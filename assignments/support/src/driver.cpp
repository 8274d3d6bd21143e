#include "simlab/driver.h"

namespace simlab {

IntegratorStats statsOf(const SimTK::Integrator& integrator) {
    IntegratorStats stats;
    stats.method = integrator.getMethodName();
    stats.stepsTaken = integrator.getNumStepsTaken();
    stats.stepsAttempted = integrator.getNumStepsAttempted();
    stats.realizations = integrator.getNumRealizations();
    stats.accuracyInUse = integrator.getAccuracyInUse();
    stats.errorControl = integrator.methodHasErrorControl();
    return stats;
}

}  // namespace simlab
