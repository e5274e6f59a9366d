/* A C simulator linking the installed runtime: opens the table given on the command line and
   checks one interpolated value. */
#include <math.h>
#include <stdio.h>

#include "expected.h"
#include "wrc/runtime.h"

int main(int argc, char** argv) {
  wrc_table* table = NULL;
  double point[2] = {SIM_Y, SIM_SPIN};
  double fx = 0.0;
  int flags;
  if (argc != 2 || wrc_table_open(argv[1], &table) != 0) {
    fprintf(stderr, "sim.c: cannot open the table: %s\n", wrc_last_error());
    return 1;
  }
  flags = wrc_table_eval(table, point, &fx);
  wrc_table_close(table);
  if (flags != WRC_OK || fabs(fx - SIM_FX) > SIM_TOLERANCE) {
    fprintf(stderr, "sim.c: fx = %.17g (flags %d), expected %.17g\n", fx, flags, SIM_FX);
    return 1;
  }
  printf("sim.c: fx = %.17g\n", fx);
  return 0;
}
