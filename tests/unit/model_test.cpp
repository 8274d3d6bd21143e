// describeModel: counting bodies, mobilities and constraints, and naming mobilizers.
#include <catch2/catch.hpp>

#include "Simbody.h"
#include "simlab/model_info.h"

namespace model_test {

using namespace SimTK;

namespace {
const Body::Rigid kBall(MassProperties(1.0, Vec3(0), UnitInertia::sphere(0.1)));
}

TEST_CASE("a Slider is one body with one degree of freedom", "[model]") {
    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    MobilizedBody::Slider(matter.Ground(), Transform(), kBall, Transform());
    const simlab::ModelInfo info = simlab::describeModel(matter, system.realizeTopology());
    CHECK(info.bodies == 1);
    CHECK(info.mobilities == 1);
    CHECK(info.degreesOfFreedom() == 1);
    REQUIRE(info.mobilizers.size() == 1);
    CHECK(info.mobilizers[0].kind == "Slider");
    CHECK(info.summary() == "1 body: body 1 on a Slider mobilizer (1 dof); 1 degree of freedom");
}

TEST_CASE("a Free mobilizer has six mobilities and seven coordinates", "[model]") {
    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    MobilizedBody::Free(matter.Ground(), Transform(), kBall, Transform());
    const simlab::ModelInfo info = simlab::describeModel(matter, system.realizeTopology());
    CHECK(info.degreesOfFreedom() == 6);
    CHECK(info.mobilizers.at(0).nq == 7);  // a quaternion for orientation
    CHECK(info.uses("Free"));
    CHECK_FALSE(info.uses("Slider"));
}

TEST_CASE("constraint equations take away degrees of freedom", "[model]") {
    // Two free-floating points held a fixed distance apart: 3 + 3 mobilities, 1 constraint equation.
    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    MobilizedBody::Translation a(matter.Ground(), Transform(), kBall, Transform());
    MobilizedBody::Translation b(matter.Ground(), Transform(), kBall, Transform());
    Constraint::Rod(a, b, 1.0);
    const simlab::ModelInfo info = simlab::describeModel(matter, system.realizeTopology());
    CHECK(info.bodies == 2);
    CHECK(info.mobilities == 6);
    CHECK(info.constraintEquations == 1);
    CHECK(info.degreesOfFreedom() == 5);
    CHECK(info.mobilizers.at(1).kind == "Translation");
}

TEST_CASE("mobilizers are named as Simbody spells them", "[model]") {
    MultibodySystem system;
    SimbodyMatterSubsystem matter(system);
    MobilizedBody::Pin pin(matter.Ground(), Transform(), kBall, Transform());
    MobilizedBody::Ball ball(pin, Transform(), kBall, Transform());
    MobilizedBody::Planar(ball, Transform(), kBall, Transform());
    MobilizedBody::Weld(matter.Ground(), Transform(), kBall, Transform());
    const simlab::ModelInfo info = simlab::describeModel(matter, system.realizeTopology());
    REQUIRE(info.mobilizers.size() == 4);
    CHECK(info.mobilizers[0].kind == "Pin");
    CHECK(info.mobilizers[1].kind == "Ball");
    CHECK(info.mobilizers[2].kind == "Planar");
    CHECK(info.mobilizers[3].kind == "Weld");
    CHECK(info.degreesOfFreedom() == 1 + 3 + 3 + 0);
}

}  // namespace model_test
