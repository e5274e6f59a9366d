// A C++ simulator linking the installed runtime through runtime.hpp: opens the table given on
// the command line and checks one interpolated value.
#include <cmath>
#include <cstdio>
#include <exception>

#include "expected.h"
#include "wrc/runtime.hpp"

int main(int argc, char** argv) {
  if (argc != 2) return 1;
  try {
    const wrc::Table table(argv[1]);
    int flags = -1;
    const double fx = table.eval({SIM_Y, SIM_SPIN}, &flags)[0];
    if (flags != WRC_OK || std::fabs(fx - SIM_FX) > SIM_TOLERANCE) {
      std::fprintf(stderr, "sim.cpp: fx = %.17g (flags %d), expected %.17g\n", fx, flags, SIM_FX);
      return 1;
    }
    std::printf("sim.cpp: fx = %.17g\n", fx);
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "sim.cpp: %s\n", error.what());
    return 1;
  }
}
