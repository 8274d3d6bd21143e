// The baby boot in the work-precision study: qA, qB, uA and uB against the hand-derived equations of motion
// (babyboot_reference.h) integrated in long double by Boost.Odeint. The boot is chaotic, so the study runs to 5 s,
// where the reference's own accuracy (measured by a second run at a looser tolerance) still exceeds double's.
#include "babyboot_reference.h"
#include "biosim/course.h"
#include "simlab/digits.h"
#include "simlab/study.h"

namespace {

using Reference = simlab::OdeReference<4>;
const double kDegree = SimTK::Pi / 180;

babyboot::reference::Parameters referenceParameters(const biosim::Parameters& p) {
    babyboot::reference::Parameters r;
    r.mA = p["mA"], r.LA = p["LA"], r.IAx = p["IAx"];
    r.mB = p["mB"], r.LB = p["LB"], r.IBx = p["IBx"], r.IBy = p["IBy"], r.IBz = p["IBz"];
    r.g = p["g"];
    return r;
}

Reference bootReference(const biosim::Parameters& p, long double tolerance) {
    const babyboot::reference::Parameters r = referenceParameters(p);
    auto f = [r](const Reference::Y& x, Reference::Y& dxdt) { babyboot::reference::derivative(r, x, dxdt); };
    return Reference(f, {p["qA"] * kDegree, p["qB"] * kDegree, p["uA"], p["uB"]}, tolerance);
}

class Boot : public simlab::study::Instance {
public:
    Boot() : parameters_(biosim::resolve(biosim::declare())), reference_(bootReference(parameters_, 1e-18L)) {
        biosim::buildModel(parameters_, model_);
        initial_ = biosim::initialState(parameters_, model_);
    }
    const SimTK::MultibodySystem& system() const override { return model_.system; }
    const SimTK::State& initial() const override { return initial_; }
    double digits(const SimTK::State& state) override {
        const Reference::Y& x = reference_.at(state.getTime());
        // The angles and rates pass through zero: angles against one radian, rates against one radian per second.
        const double simulated[4] = {state.getQ()[0], state.getQ()[1], state.getU()[0], state.getU()[1]};
        double worst = simlab::kMaxDigits;
        for (std::size_t i = 0; i < 4; ++i) {
            worst = std::min(worst, simlab::accuracyDigits(simulated[i], static_cast<double>(x[i]), 1.0));
        }
        return worst;
    }
    double conserved(const SimTK::State& state) override {
        model_.system.realize(state, SimTK::Stage::Dynamics);
        return model_.system.calcEnergy(state);
    }

private:
    biosim::Parameters parameters_;
    biosim::Model model_;
    SimTK::State initial_;
    Reference reference_;
};

}  // namespace

int main(int argc, char** argv) {
    const biosim::Parameters p = biosim::resolve(biosim::declare());
    simlab::study::Subject boot;
    boot.name = "babyboot";
    boot.finalTime = 5;
    boot.figure = "qA, qB (scale 1 rad) and uA, uB (scale 1 rad/s) of the chaotic boot";
    boot.conservedName = "energy (relative to g (mA LA + mB LB), the energy a swing exchanges)";
    boot.conservedScale = p["g"] * (p["mA"] * p["LA"] + p["mB"] * p["LB"]);
    boot.reference = "the hand-derived equations of motion in long double, Boost.Odeint RKF78 at tolerance 1e-18";
    boot.referenceDigits = [p, T = boot.finalTime] {
        return simlab::agreement<4>(bootReference(p, 1e-18L), bootReference(p, 1e-17L), T, {1, 1, 1, 1});
    };
    boot.make = [] { return std::make_unique<Boot>(); };
    return simlab::study::studyMain(argc, argv, "biosim", {boot});
}
