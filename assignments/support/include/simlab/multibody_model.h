// The part of every lab's Model the course makes: a Simbody system with its matter and force subsystems.
#pragma once

#include "Simbody.h"

namespace simlab {

/// The system and its two subsystems. Each assignment's Model adds the mobilized bodies a student builds.
/// Not copyable: the subsystems refer to this object's system.
struct MultibodyModel {
    SimTK::MultibodySystem system;
    SimTK::SimbodyMatterSubsystem matter{system};  ///< bodies and the mobilizers that connect them
    SimTK::GeneralForceSubsystem forces{system};   ///< forces such as gravity

    MultibodyModel() = default;
    MultibodyModel(const MultibodyModel&) = delete;
    MultibodyModel& operator=(const MultibodyModel&) = delete;
};

}  // namespace simlab
