/*
 * Opens a wrc table, lists its axes and outputs, and evaluates it at one point, multilinear and
 * cubic, with derivatives.
 *
 *   wrc_lookup_example TABLE.h5 [x0 x1 ...]
 *
 * Without coordinates the point is the middle of every axis range.
 */
#include <stdio.h>
#include <stdlib.h>

#include "wrc/runtime.h"

static void print_result(const wrc_table* table, const char* mode, int flags, const double* out,
                         const double* d_out) {
  const int n_axes = wrc_table_num_axes(table);
  const int n_outputs = wrc_table_num_outputs(table);
  int k;
  int a;
  printf("%s%s%s:\n", mode, (flags & WRC_FLAG_CLAMPED) ? " [clamped]" : "",
         (flags & WRC_FLAG_STATUS) ? " [near a failed node]" : "");
  for (k = 0; k < n_outputs; ++k) {
    printf("  %-14s = % .6e %s   d/d(", wrc_table_output_name(table, k), out[k],
           wrc_table_output_unit(table, k));
    for (a = 0; a < n_axes; ++a) {
      printf("%s%s", a ? ", " : "", wrc_table_axis_name(table, a));
    }
    printf(") = (");
    for (a = 0; a < n_axes; ++a) printf("%s% .4e", a ? ", " : "", d_out[k * n_axes + a]);
    printf(")\n");
  }
}

int main(int argc, char** argv) {
  wrc_table* table = NULL;
  double point[WRC_MAX_AXES];
  double* out;
  double* d_out;
  int n_axes;
  int n_outputs;
  int a;
  int flags;
  int status = EXIT_SUCCESS;

  if (argc < 2) {
    fprintf(stderr, "usage: %s TABLE.h5 [coordinate per axis ...]\n", argv[0]);
    return 2;
  }
  if (wrc_table_open(argv[1], &table) != 0) {
    fprintf(stderr, "%s\n", wrc_last_error());
    return 1;
  }
  n_axes = wrc_table_num_axes(table);
  n_outputs = wrc_table_num_outputs(table);
  if (argc != 2 && argc != 2 + n_axes) {
    fprintf(stderr, "the table has %d axes: give %d coordinates or none\n", n_axes, n_axes);
    wrc_table_close(table);
    return 2;
  }
  printf("%s: %d axes, %d outputs\n", argv[1], n_axes, n_outputs);
  for (a = 0; a < n_axes; ++a) {
    const double* values = wrc_table_axis_values(table, a);
    const int size = wrc_table_axis_size(table, a);
    point[a] = argc > 2 ? atof(argv[2 + a]) : 0.5 * (values[0] + values[size - 1]);
    printf("  axis %-6s %3d nodes in [%g, %g] %s, point %g\n", wrc_table_axis_name(table, a), size,
           values[0], values[size - 1], wrc_table_axis_unit(table, a), point[a]);
  }

  out = malloc(sizeof(double) * (size_t)n_outputs);
  d_out = malloc(sizeof(double) * (size_t)(n_outputs * n_axes));
  if (out == NULL || d_out == NULL) {
    fprintf(stderr, "out of memory\n");
    status = EXIT_FAILURE;
  } else {
    flags = wrc_table_eval_deriv(table, point, out, d_out);
    if (flags < 0) {
      fprintf(stderr, "%s\n", wrc_last_error());
      status = EXIT_FAILURE;
    } else {
      print_result(table, "multilinear", flags, out, d_out);
      if (wrc_table_set_interpolation(table, WRC_INTERP_CUBIC) != 0 ||
          (flags = wrc_table_eval_deriv(table, point, out, d_out)) < 0) {
        fprintf(stderr, "%s\n", wrc_last_error());
        status = EXIT_FAILURE;
      } else {
        print_result(table, "cubic", flags, out, d_out);
      }
    }
  }
  free(out);
  free(d_out);
  wrc_table_close(table);
  return status;
}
