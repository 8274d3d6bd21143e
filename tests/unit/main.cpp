// The unit tests' main: Catch2's, after the reproducible libm (simlab/reproducible_math.h), so that the figures
// the tests compute are those of every other machine.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "simlab/reproducible_math.h"

int main(int argc, char** argv) {
    simlab::useReproducibleMath(argv);
    return Catch::Session().run(argc, argv);
}
