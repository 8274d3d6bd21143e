// The end of the lab's precompiled header (cmake/Simlab.cmake, after simlab/pch.h): the contract, and the
// templates every file of the lab instantiates with its types, compiled once per build instead of once per file.
//
// CHANGE: nothing, as long as your contract keeps the names Model and Sample.
#pragma once

#include "mylab/MyLab.h"

namespace mylab::precompiled {
inline void uses() { (void)&simlab::precompiled::labUses<Model, Sample>; }
}  // namespace mylab::precompiled
