// The book's three spins in the work-precision study: w_B against Euler's equations integrated in long double
// (19 significant digits) by Boost.Odeint, whose own accuracy is measured by a second run at a looser tolerance and
// a third in 113-bit floats (book/reference.h).
// (The elliptic solution in exact.h loses digits to its own evaluation, most for the intermediate spin.)
#include "book/contract/BookSpin.h"
#include "book/program/exact.h"
#include "book/grading/observations.h"
#include "book/program/reference.h"
#include "simlab/digits.h"
#include "simlab/long_run.h"
#include "simlab/study.h"

namespace {

using Reference = simlab::OdeReference<3>;

class Spin : public simlab::study::Instance {
public:
    Spin(const book::Scene& scene, bool free) : scene_(scene), reference_(book::exact::eulerReference(scene)) {
        if (!free) {
            book::buildModel(scene_, model_);
            initial_ = book::initialState(scene_, model_);
            return;
        }
        // Over-modelled: the book on a Free mobilizer, six motions where the spin about a fixed centre needs three.
        using namespace SimTK;
        const Body::Rigid body(MassProperties(scene_.mass, Vec3(0), UnitInertia::brick(scene_.dimensions / 2)));
        model_.book = MobilizedBody::Free(model_.matter.Ground(), Transform(), body, Transform());
        initial_ = model_.system.realizeTopology();
        model_.book.setUToFitAngularVelocity(initial_, scene_.w_B0);
    }
    const SimTK::MultibodySystem& system() const override { return model_.system; }
    const SimTK::State& initial() const override { return initial_; }
    double digits(const SimTK::State& state) override {
        const book::Sample s = book::readState(model_, state);
        return book::exact::spinDigits(scene_, s.w_B, reference_.at(s.time));
    }
    double conserved(const SimTK::State& state) override { return book::readState(model_, state).kineticEnergy; }

private:
    book::Scene scene_;
    book::Model model_;
    SimTK::State initial_;
    Reference reference_;
};

/// The spin of `scene` (its w_B0 says about which axis) to `finalTime`, as a scene of the study named `name`.
simlab::study::Subject spinOf(const book::Scene& scene, double finalTime, const std::string& name,
                              const std::string& axis) {
    simlab::study::Subject s;
    s.name = name;
    s.finalTime = finalTime;
    s.figure = "w_B of a spin about the " + axis + " axis (scale: |w_B(0)|)";
    s.conservedName = "kinetic energy (relative to its value)";
    s.conservedScale = book::exact::kineticEnergy(scene);
    s.reference = "Euler's equations in long double, Boost.Odeint RKF78 at tolerance 1e-18, checked at 1e-16 and in "
                  "113-bit floats";
    // Its digits: the first rung of the precision ladder, on the figure's own scale.
    s.referenceDigits = [scene, T = s.finalTime] {
        const book::exact::CertifiedSpin c = book::exact::certifiedAngularVelocity(scene, T, true);
        return simlab::accuracyDigits(c.error, 0.0, book::exact::magnitude(scene.w_B0));
    };
    s.make = [scene] { return std::make_unique<Spin>(scene, false); };
    s.makeOverModelled = [scene] { return std::make_unique<Spin>(scene, true); };
    s.minimal = "Ball (3 dof)";
    s.overModelled = "Free (6 dof)";
    return s;
}

simlab::study::Subject spinAbout(const std::string& axis) {
    book::Scene scene;
    scene.w_B0 = book::exact::spin(scene, axis);
    return spinOf(scene, book::defaultRunSettings().finalTime, "book-" + axis, axis);
}

/// The axis the largest component of w_B0 is about, by its moment: min, intermediate or max.
std::string axisOf(const book::Scene& scene) {
    int largest = 0;
    for (int i = 1; i < 3; ++i) {
        if (std::abs(scene.w_B0[i]) > std::abs(scene.w_B0[largest])) largest = i;
    }
    const std::array<int, 3> axes = book::exact::axesByMoment(scene);
    return largest == axes[0] ? "min" : largest == axes[1] ? "intermediate" : "max";
}

}  // namespace

int main(int argc, char** argv) {
    if (simlab::study::asksForLongRun(argc, argv)) {
        // The lab's default scene for a long time: w_B against Euler's equations in long double, which keep their
        // digits over the whole run; the kinetic energy, conserved with no torque.
        book::Scene scene;
        scene.w_B0 = book::exact::spin(scene, "intermediate");
        simlab::study::LongRunView view;
        view.scene = "the spin about the intermediate axis";
        view.subject = [scene](double finalTime) { return spinOf(scene, finalTime, "book", axisOf(scene)); };
        view.trajectory = simlab::study::TrajectoryCheck::reference;
        view.fixedStep = 1e-3;  // s: a seventh of a degree of the 7 rad/s spin a step
        view.quickFinalTime = 20;
        return simlab::study::longRunMain(argc, argv, "book", view);
    }
    return simlab::study::studyMain(argc, argv, "book",
                                    {spinAbout("min"), spinAbout("intermediate"), spinAbout("max")},
                                    [](const nlohmann::json& given, double finalTime) {
                                        const book::Scene scene = simlab::wire::readOver(book::Scene{}, given, "scene");
                                        return spinOf(scene, finalTime, "book", axisOf(scene));
                                    });
}
