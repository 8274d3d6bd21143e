// The end of the pendulum's precompiled header (cmake/Simlab.cmake, after simlab/pch.h): the contract, and the
// templates every pendulum file instantiates with its types, instantiated once per build.
#pragma once

#include "pendulum/Pendulum.h"

namespace pendulum::precompiled {
inline void uses() { (void)&simlab::precompiled::labUses<Model, Sample>; }
}  // namespace pendulum::precompiled
