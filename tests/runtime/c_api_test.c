/*
 * The runtime's C API used from C: compiled as strict C99 (-std=c99 -pedantic-errors), which
 * also proves that wrc/runtime.h is valid C. Registered with ctest as runtime_c_api; exits
 * non-zero when a check fails.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tests/runtime/c_api_test_support.h"
#include "wrc/runtime.h"

static int g_failures = 0;

#define CHECK(condition)                                                            \
  do {                                                                              \
    if (!(condition)) {                                                             \
      fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #condition); \
      ++g_failures;                                                                 \
    }                                                                               \
  } while (0)

/* |a - b| <= tolerance */
#define CHECK_NEAR(a, b, tolerance) CHECK(fabs((a) - (b)) <= (tolerance))

static double fx(double y, double spin) { return 1.0 + 2.0 * y + 300.0 * spin + 50.0 * y * spin; }

int main(void) {
  char path[4096];
  wrc_table* table = NULL;
  double point[2];
  double out[2];
  double d_out[4];
  int flags;

  if (wrc_test_write_c_table(path, sizeof path) != 0) return 1;

  /* Missing file: an error code, a NULL handle and a message naming the file. */
  table = (wrc_table*)&flags; /* Any non-NULL value; must come back NULL. */
  CHECK(wrc_table_open("/nonexistent/wrc/table.h5", &table) == WRC_ERR_FILE);
  CHECK(table == NULL);
  CHECK(strstr(wrc_last_error(), "/nonexistent/wrc/table.h5") != NULL);

  CHECK(wrc_table_open(path, &table) == 0);
  if (table == NULL) {
    fprintf(stderr, "open failed: %s\n", wrc_last_error());
    wrc_test_remove(path);
    return 1;
  }
  CHECK(wrc_table_num_axes(table) == 2);
  CHECK(wrc_table_num_outputs(table) == 2);
  CHECK(strcmp(wrc_table_axis_name(table, 0), "y") == 0);
  CHECK(strcmp(wrc_table_axis_name(table, 1), "spin") == 0);
  CHECK(wrc_table_axis_size(table, 0) == 5);
  CHECK(wrc_table_axis_size(table, 1) == 3);
  CHECK(wrc_table_axis_values(table, 1)[2] == 0.01);
  CHECK(strcmp(wrc_table_output_name(table, 0), "fx") == 0);
  CHECK(strcmp(wrc_table_output_name(table, 1), "fy") == 0);
  CHECK(wrc_table_output_index(table, "fy") == 1);

  /* Multilinear: fx is bilinear, so exact (tolerance: rounding of |fx| <= 8). fy = y² is
   * interpolated linearly between the nodes 0 and 1: 0.5 at y = 0.5. */
  point[0] = 0.5;
  point[1] = 0.005;
  CHECK(wrc_table_eval(table, point, out) == WRC_OK);
  CHECK_NEAR(out[0], fx(0.5, 0.005), 1e-12);
  CHECK_NEAR(out[1], 0.5, 1e-12);
  CHECK(wrc_table_eval_deriv(table, point, out, d_out) == WRC_OK);
  CHECK_NEAR(d_out[0], 2.0 + 50.0 * 0.005, 1e-12); /* dfx/dy */
  CHECK_NEAR(d_out[1], 300.0 + 50.0 * 0.5, 1e-9);  /* dfx/dspin, ~1/h = 100 times larger */
  CHECK_NEAR(d_out[2], 1.0, 1e-12);                /* dfy/dy on [0, 1] */
  CHECK(d_out[3] == 0.0);                          /* fy does not depend on spin */

  /* Out of range: clamped and flagged. */
  point[0] = 3.0;
  point[1] = 0.0;
  CHECK(wrc_table_eval(table, point, out) == WRC_FLAG_CLAMPED);
  CHECK_NEAR(out[0], fx(2.0, 0.0), 1e-12);

  /* NaN and NULL: negative codes with a reason. */
  point[1] = NAN;
  out[0] = 0.0;
  CHECK(wrc_table_eval(table, point, out) == WRC_ERR_NAN_INPUT);
  CHECK(strstr(wrc_last_error(), "NaN") != NULL);
  CHECK(strstr(wrc_last_error(), "spin") != NULL);
  CHECK(out[0] == 0.0); /* out untouched */
  CHECK(wrc_table_eval(table, NULL, out) == WRC_ERR_NULL_POINTER);
  CHECK(wrc_table_eval(NULL, point, out) == WRC_ERR_NULL_POINTER);

  /* Cubic on [0, 1]: the data y² have an extremum at y = 0 (secants -1 and 1), where the
   * limiter sets the slope to 0, which is also the exact slope of y² there; at y = 1 the
   * estimate 2 is exact and within 3·min(1, 3). With exact end slopes the cubic Hermite cell
   * reproduces y² exactly. fx is bilinear and reproduced as well. */
  CHECK(wrc_table_set_interpolation(table, WRC_INTERP_CUBIC) == 0);
  CHECK(wrc_table_interpolation(table) == WRC_INTERP_CUBIC);
  point[0] = 0.5;
  point[1] = 0.005;
  CHECK(wrc_table_eval_deriv(table, point, out, d_out) == WRC_OK);
  CHECK_NEAR(out[0], fx(0.5, 0.005), 1e-12);
  CHECK_NEAR(out[1], 0.25, 1e-12);
  CHECK_NEAR(d_out[2], 1.0, 1e-12); /* d(y²)/dy at 0.5 */
  CHECK(wrc_table_set_interpolation(table, 5) == WRC_ERR_INVALID_ARGUMENT);

  CHECK(strcmp(wrc_table_attribute(table, "format"), "wrc-table") == 0);

  wrc_table_close(table);
  wrc_test_remove(path);
  if (g_failures == 0) printf("runtime C API: all checks passed\n");
  return g_failures == 0 ? 0 : 1;
}
