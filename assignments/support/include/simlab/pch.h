// Precompiled for every student file: Simbody and the standard headers the labs use.
// Built once per build (see cmake/Simlab.cmake); a student compile then takes about a second.
#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "Simbody.h"
