// The end of apple's precompiled header (cmake/Simlab.cmake, after simlab/pch.h): the contract, and the templates
// every apple file instantiates with its types, instantiated once per build rather than at each compile.
#pragma once

#include "apple/NewtonsApple.h"

namespace apple::precompiled {
inline void uses() { (void)&simlab::precompiled::labUses<Model, Sample>; }
}  // namespace apple::precompiled
