// The baby boot in the work-precision study: qA, qB, uA and uB against the hand-derived equations of motion
// (babyboot_reference.h) integrated in long double by Boost.Odeint. The boot is chaotic, so the study runs to 5 s,
// where the reference's own accuracy (measured by a second run at a looser tolerance) still exceeds double's.
#include "biosim/program/babyboot_reference.h"
#include "biosim/program/course.h"
#include "simlab/digits.h"
#include "simlab/long_run.h"
#include "simlab/precision_ladder.h"
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

/// The boot minimal (its two Pins, as the project builds it) or over-modelled: the rod on a Free mobilizer held to
/// the pivot by a Ball constraint and to the swing axis by two constant angles, six motions and five constraint
/// equations where one Pin does, with the plate's Pin on it as before.
class Boot : public simlab::study::Instance {
public:
    explicit Boot(bool over) : parameters_(biosim::resolve(biosim::declare())), reference_(bootReference(parameters_, 1e-18L)) {
        if (!over) {
            biosim::buildModel(parameters_, model_);
            initial_ = biosim::initialState(parameters_, model_);
            return;
        }
        using namespace SimTK;
        const biosim::Parameters& p = parameters_;
        const Vec3 p_AAcm(0, -p["LA"], 0);
        // A thin rod has no moment about its own axis, but on a Free mobilizer that would leave the mass matrix
        // singular (the rod's turn about its axis and the plate's Pin move the plate alike). The constraints allow
        // no turn but the swing about x, so any moment about the rod's axis leaves the motion as it is: IAx.
        const Inertia I_AAcm(p["IAx"], p["IAx"], p["IAx"]);
        const Body::Rigid rodA(MassProperties(p["mA"], p_AAcm, I_AAcm.shiftFromMassCenter(p_AAcm, p["mA"])));
        const Body::Rigid plateB(MassProperties(p["mB"], Vec3(0), Inertia(p["IBx"], p["IBy"], p["IBz"])));
        rod_ = MobilizedBody::Free(model_.matter.Ground(), Transform(), rodA, Transform());
        Constraint::Ball(model_.matter.Ground(), Vec3(0), rod_, Vec3(0));
        // The rod's x axis stays along Ground's x, the swing axis: square to Ground's y and z.
        Constraint::ConstantAngle(model_.matter.Ground(), UnitVec3(YAxis), rod_, UnitVec3(XAxis));
        Constraint::ConstantAngle(model_.matter.Ground(), UnitVec3(ZAxis), rod_, UnitVec3(XAxis));
        plate_ = MobilizedBody::Pin(rod_, Transform(Rotation(-Pi / 2, XAxis), Vec3(0, -p["LB"], 0)), plateB, Transform());
        Force::UniformGravity(model_.forces, model_.matter, Vec3(0, -p["g"], 0));
        initial_ = model_.system.realizeTopology();
        rod_.setQToFitRotation(initial_, Rotation(p["qA"] * kDegree, XAxis));
        rod_.setUToFitAngularVelocity(initial_, Vec3(p["uA"], 0, 0));
        plate_.setOneQ(initial_, 0, p["qB"] * kDegree);
        plate_.setOneU(initial_, 0, p["uB"]);
        over_ = true;
    }
    const SimTK::MultibodySystem& system() const override { return model_.system; }
    const SimTK::State& initial() const override { return initial_; }
    double digits(const SimTK::State& state) override {
        const Reference::Y& x = reference_.at(state.getTime());
        // The angles and rates pass through zero: angles against one radian, rates against one radian per second.
        double simulated[4] = {0, 0, 0, 0};
        if (over_) {
            // qA is the rod's turn about Ground's x (within +-180 degrees, as the swing stays), uA its rate.
            model_.system.realize(state, SimTK::Stage::Velocity);
            const SimTK::Rotation& R_GA = rod_.getBodyRotation(state);
            simulated[0] = std::atan2(R_GA.asMat33()(2, 1), R_GA.asMat33()(1, 1));
            simulated[1] = plate_.getOneQ(state, 0);
            simulated[2] = rod_.getBodyAngularVelocity(state)[0];
            simulated[3] = plate_.getOneU(state, 0);
        } else {
            simulated[0] = state.getQ()[0], simulated[1] = state.getQ()[1];
            simulated[2] = state.getU()[0], simulated[3] = state.getU()[1];
        }
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
    SimTK::MobilizedBody rod_, plate_;  ///< the over-modelled boot's
    bool over_ = false;
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
    boot.reference = "the hand-derived equations of motion in long double, Boost.Odeint RKF78 at tolerance 1e-18, "
                     "checked at 1e-16 and in 113-bit floats";
    // Its digits: the first rung of the precision ladder (a chaotic motion magnifies rounding as much as truncation),
    // against the figure's scales of 1 rad and 1 rad/s.
    boot.referenceDigits = [p, T = boot.finalTime] {
        const babyboot::reference::Parameters r = referenceParameters(p);
        auto f = [r](const auto& x, auto& dxdt) { babyboot::reference::derivative(r, x, dxdt); };
        const std::array<double, 4> x0 = {p["qA"] * kDegree, p["qB"] * kDegree, p["uA"], p["uB"]};
        return simlab::accuracyDigits(simlab::precision::certifyLongDouble<4>(f, x0, T, 1e-3).error, 0.0, 1.0);
    };
    boot.make = [] { return std::make_unique<Boot>(false); };
    boot.makeOverModelled = [] { return std::make_unique<Boot>(true); };
    boot.minimal = "two Pins (2 dof)";
    boot.overModelled = "Free + 5 constraints";
    if (simlab::study::asksForLongRun(argc, argv)) {
        // The chaotic boot for a long time: no reference keeps digits past a few seconds, so each run is judged
        // against the same method run tighter, in the study's norm (qA, qB against 1 rad; uA, uB against 1 rad/s).
        simlab::study::LongRunView view;
        view.scene = "the baby boot from the project's default start";
        view.subject = [boot](double finalTime) {
            simlab::study::Subject s = boot;
            s.finalTime = finalTime;
            return s;
        };
        view.trajectory = simlab::study::TrajectoryCheck::tighterRun;
        view.fixedStep = 1e-3;  // s
        view.quickFinalTime = 20;
        return simlab::study::longRunMain(argc, argv, "biosim", view);
    }
    return simlab::study::studyMain(argc, argv, "biosim", {boot});
}
