# How the course's own code compiles: simlab here, and a lab built out of the tree against simlab's CMake package
# (simlab_add_lab), whose objects are linked with simlab's and must agree with them.
if(NOT CMAKE_BUILD_TYPE AND NOT CMAKE_CONFIGURATION_TYPES)
  set(CMAKE_BUILD_TYPE Release CACHE STRING "Build type" FORCE)
endif()
# No build type defines NDEBUG. Debian builds Simbody without it, and Simbody's headers lay out a State's cache
# entries differently with it (SimTKcommon/internal/StateImpl.h): code of ours that inlines them, compiled with
# NDEBUG, would read a State the library wrote with the wrong layout (a State copied and changed in course code
# crashed in ListOfDependents::notePrerequisiteChange). Student files are compiled without it too.
foreach(config RELEASE RELWITHDEBINFO MINSIZEREL)
  string(REGEX REPLACE "(^| )-DNDEBUG( |$)" " " CMAKE_CXX_FLAGS_${config} "${CMAKE_CXX_FLAGS_${config}}")
endforeach()
# A release build of simlab's own code is -O1: the simulations' hot loops run in Simbody's optimized libraries, so
# a self-check runs within 5 % of -O3 while the project builds in two thirds of the time. Optimization levels change
# no figure: x86-64 has no fused multiply-add without -march, and ISO C++ mode does not contract expressions.
string(REGEX REPLACE "(^| )-O3( |$)" " -O1 " CMAKE_CXX_FLAGS_RELEASE "${CMAKE_CXX_FLAGS_RELEASE}")
# Position-independent code everywhere: the probes' objects must be, and one precompiled header then serves all of
# the course's libraries.
set(CMAKE_POSITION_INDEPENDENT_CODE ON)
set(CMAKE_CXX_STANDARD 17)
set(CMAKE_CXX_STANDARD_REQUIRED ON)
set(CMAKE_CXX_EXTENSIONS OFF)
# Boost.Math computes in double, not in long double: glibc's long double exp, log and pow run x87 instructions that
# Intel's and AMD's processors round differently, and the figures we print must be the same on every machine
# (simlab/reproducible_math.h says why, and tests/cli/reproducible_math.sh checks every program for them).
add_compile_definitions(BOOST_MATH_PROMOTE_DOUBLE_POLICY=false)
