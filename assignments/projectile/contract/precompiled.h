// The end of projectile's precompiled header (cmake/Simlab.cmake, after simlab/pch.h): the contract, and the templates
// every projectile file instantiates with its types, instantiated once per build rather than at each compile.
#pragma once

#include "projectile/ProjectileMotion.h"

namespace projectile::precompiled {
inline void uses() { (void)&simlab::precompiled::labUses<Model, Sample>; }
}  // namespace projectile::precompiled
