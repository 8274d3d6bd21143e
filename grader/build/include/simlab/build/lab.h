// A lab of one's own: an assignment's folder outside simlab's tree, built against this simlab on first use.
#pragma once

#include <string>
#include <vector>

#include "simlab/build/manifest.h"

namespace simlab::engine {

/// Whether an assignment named on the command line is a lab's folder whatever the course's ids are: a path
/// ("./pendulum", "labs/pendulum", "/srv/labs/pendulum", "."). A bare name the course has not is a folder too, where
/// one of that name holds a CMakeLists.txt (Manifest::find).
bool isLabFolder(const std::string& name);

/// The assignment the folder `dir` declares (its CMakeLists.txt calls simlab_add_assignment), built against this
/// simlab's CMake package (find_package(simlab)) in the user's cache: configured on first use, brought up to date
/// incrementally after (an edited test or rubric is built again). Its build log is kept beside the build; a
/// failure is one line naming the log. Throws UsageError.
Assignment buildLab(const Manifest& manifest, const std::string& dir);

/// The folders of the labs built in this simlab's cache so far: simlab's places from then on, named or not.
std::vector<std::string> labsBuilt(const Manifest& manifest);

/// Where buildLab builds the lab in `dir` (its canonical path).
std::string labBuildFolder(const Manifest& manifest, const std::string& dir);

}  // namespace simlab::engine
