// The end of book's precompiled header (cmake/Simlab.cmake, after simlab/pch.h): the contract, and the templates
// every book file instantiates with its types, instantiated once per build rather than at each compile.
#pragma once

#include "book/BookSpin.h"

namespace book::precompiled {
inline void uses() { (void)&simlab::precompiled::labUses<Model, Sample>; }
}  // namespace book::precompiled
