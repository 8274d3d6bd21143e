// The start of every lab's precompiled header (cmake/Simlab.cmake): Simbody, the standard headers and the support
// headers the labs use, and the templates every lab file instantiates. Each lab's header adds its contract and
// its own uses (assignments/<id>/precompiled.h), built once per build with the student files' own flags, so that
// a student's compile after an edit starts after all of it: about 0.25 s for a lab's file with clang, most of it
// loading the header.
#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "Simbody.h"
#include "simlab/integrators.h"
#include "simlab/multibody_model.h"
#include "simlab/recorder.h"
#include "simlab/run_settings.h"

namespace simlab::precompiled {

// What a lab's file makes of Simbody's templates as it builds a model, sets its state and samples it. Never
// called: naming them here has the precompiled header instantiate them once (-fpch-instantiate-templates).
inline void simbodyUses(SimTK::MultibodySystem& system, SimTK::SimbodyMatterSubsystem& matter,
                        SimTK::GeneralForceSubsystem& forces, SimTK::State& state) {
    using namespace SimTK;
    const Body::Rigid body(MassProperties(1, Vec3(0), UnitInertia::sphere(1)));
    const Body::Rigid brick(MassProperties(1, Vec3(0), UnitInertia::brick(1, 2, 3)));
    const Body::Rigid rod(MassProperties(1, Vec3(0), UnitInertia::cylinderAlongY(1, 2).shiftFromCentroid(Vec3(1))));
    const Rotation R(Pi / 2, ZAxis);
    const Transform X(R, Vec3(1, 2, 3));
    MobilizedBody::Slider slider(matter.Ground(), X, body, Transform(R, Vec3(0)));
    MobilizedBody::Pin pin(slider, Vec3(0, 1, 0), rod, Vec3(0));
    MobilizedBody::Free free(matter.Ground(), brick);
    Force::UniformGravity(forces, matter, Vec3(0, -9.8, 0));
    system.realize(state, Stage::Acceleration);
    const Vec3 p = pin.getBodyOriginLocation(state) + free.getBodyOriginVelocity(state) % Vec3(1);
    const Vec3 w = free.getBodyAngularVelocity(state) * dot(p, p);
    const Rotation R_GB = free.getBodyRotation(state) * ~R;
    const Vec3 angles = R_GB.convertRotationToBodyFixedXYZ();
    free.setQToFitRotation(state, Rotation(BodyRotationSequence, angles[0], XAxis, angles[1], YAxis, angles[2], ZAxis));
    free.setUToFitAngularVelocity(state, w + free.expressVectorInGroundFrame(state, Vec3(0, 0, 1)).normalize());
    slider.setOneQ(state, 0, system.calcEnergy(state) + system.calcKineticEnergy(state) + matter.calcSystemMassCenterLocationInGround(state).norm());
    (void)(matter.calcSystemCentralMomentum(state) + matter.calcSystemMomentumAboutGroundOrigin(state));
}

// What a lab's file makes of its contract's templates: its integrator, its recorder of samples. A lab's header
// names labUses<Model, Sample> (the contract's own types); its functions are found by their arguments' namespace.
template <class Model, class Sample>
void labUses(const Model& model, const SimTK::State& state, const RunSettings& run, Recorder<Sample>& recorder) {
    std::unique_ptr<SimTK::Integrator> integrator = makeIntegrator(model, run);
    integrator = integratorNamed(run.integrator, model.system, run.dt);
    SimTK::TimeStepper stepper(model.system, *integrator);
    recorder.record(sample(model, state));
    std::vector<Sample> samples(recorder.rows());
    samples.push_back(sample(model, state));
}

}  // namespace simlab::precompiled
