// The apple's scene in the work-precision study: y and vy against the exact fall y = h - g t^2 / 2, which
// double precision evaluates to its last digit.
#include "apple/contract/NewtonsApple.h"
#include "apple/program/exact.h"
#include "apple/grading/observations.h"
#include "simlab/digits.h"
#include "simlab/study.h"

namespace {

class Fall : public simlab::study::Instance {
public:
    Fall(const apple::Scene& scene, double finalTime, bool free) : scene_(scene), finalTime_(finalTime) {
        if (!free) {
            apple::buildModel(scene_, model_);
            initial_ = apple::initialState(scene_, model_);
            return;
        }
        // Over-modelled: the apple on a Free mobilizer, six motions where the fall needs one.
        using namespace SimTK;
        const Body::Rigid body(MassProperties(scene_.mass, Vec3(0), UnitInertia::sphere(scene_.radius)));
        model_.apple = MobilizedBody::Free(model_.matter.Ground(), Transform(), body, Transform());
        Force::UniformGravity(model_.forces, model_.matter, Vec3(0, -scene_.gravity, 0));
        initial_ = model_.system.realizeTopology();
        model_.apple.setQToFitTranslation(initial_, Vec3(0, scene_.dropHeight, 0));
    }
    const SimTK::MultibodySystem& system() const override { return model_.system; }
    const SimTK::State& initial() const override { return initial_; }
    double digits(const SimTK::State& state) override {
        return apple::exact::sampleDigits(scene_, apple::readState(model_, state), finalTime_);
    }
    /// The lab program's figure at the end: y's digits (apple::exact::finalDigits).
    double finalDigits(const SimTK::State& state) override {
        return apple::exact::finalDigits(scene_, apple::readState(model_, state));
    }
    double conserved(const SimTK::State& state) override { return apple::readState(model_, state).mechanicalEnergy; }

private:
    apple::Scene scene_;
    apple::Model model_;
    SimTK::State initial_;
    double finalTime_;
};

simlab::study::Subject fallOf(const apple::Scene& scene, double finalTime) {
    simlab::study::Subject fall;
    fall.name = "apple";
    fall.finalTime = finalTime;
    fall.figure = "y and vy of the falling apple (scales: the height the fall spans, g T)";
    fall.conservedName = "mechanical energy (relative to the energy the fall exchanges)";
    fall.conservedScale = 0.5 * scene.mass * SimTK::square(scene.gravity * finalTime);
    fall.reference = "the exact fall, y = h - g t^2/2, vy = -g t";
    fall.referenceDigits = [] { return simlab::kMaxDigits; };
    fall.make = [scene, finalTime] { return std::make_unique<Fall>(scene, finalTime, false); };
    fall.makeOverModelled = [scene, finalTime] { return std::make_unique<Fall>(scene, finalTime, true); };
    fall.minimal = "Slider (1 dof)";
    fall.overModelled = "Free (6 dof)";
    return fall;
}

}  // namespace

int main(int argc, char** argv) {
    return simlab::study::studyMain(argc, argv, "apple", {fallOf(apple::Scene{}, apple::defaultRunSettings().finalTime)},
                                    [](const nlohmann::json& scene, double finalTime) {
                                        return fallOf(simlab::wire::readOver(apple::Scene{}, scene, "scene"), finalTime);
                                    });
}
