/* Evaluates a table at N random points (a fixed-seed generator, reaching 10 % beyond each
 * axis), multilinear and cubic, with derivatives, and prints one FNV-1a digest of every bit of
 * every result and flag: two runtimes, or two files of one table, agree to the bit exactly when
 * their digests do. Usage: table_digest TABLE [N] */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "wrc/runtime.h"

static uint64_t Fold(uint64_t hash, const void* data, size_t size) {
  const unsigned char* bytes = (const unsigned char*)data;
  size_t i;
  for (i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 1099511628211ull;
  return hash;
}

/* xorshift64*: uniform in [0, 1). */
static double Uniform(uint64_t* state) {
  *state ^= *state >> 12;
  *state ^= *state << 25;
  *state ^= *state >> 27;
  return (double)((*state * 2685821657736338717ull) >> 11) / 9007199254740992.0;
}

int main(int argc, char** argv) {
  wrc_table* table = NULL;
  long n = argc > 2 ? atol(argv[2]) : 1000000;
  int modes[2] = {WRC_INTERP_LINEAR, WRC_INTERP_CUBIC};
  uint64_t hash = 14695981039346656037ull, state = 20261206;
  int m, a, n_axes, n_out;
  long i, failed = 0;
  double point[WRC_MAX_AXES], *out, *d_out;
  if (argc < 2 || wrc_table_open(argv[1], &table) != 0) {
    fprintf(stderr, "table_digest: %s\n",
            argc < 2 ? "usage: table_digest TABLE [N]" : wrc_last_error());
    return 2;
  }
  n_axes = wrc_table_num_axes(table);
  n_out = wrc_table_num_outputs(table);
  out = malloc(sizeof(double) * (size_t)n_out);
  d_out = malloc(sizeof(double) * (size_t)(n_out * n_axes));
  for (m = 0; m < 2; ++m) {
    if (wrc_table_set_interpolation(table, modes[m]) != 0) return 3;
    for (i = 0; i < n; ++i) {
      int flags;
      for (a = 0; a < n_axes; ++a) {
        const double* v = wrc_table_axis_values(table, a);
        const double lo = v[0], hi = v[wrc_table_axis_size(table, a) - 1];
        point[a] = lo + (1.2 * Uniform(&state) - 0.1) * (hi - lo);
      }
      flags = wrc_table_eval_deriv(table, point, out, d_out);
      hash = Fold(hash, &flags, sizeof flags);
      if (flags < 0) {
        ++failed;
        continue;
      }
      hash = Fold(hash, out, sizeof(double) * (size_t)n_out);
      hash = Fold(hash, d_out, sizeof(double) * (size_t)(n_out * n_axes));
    }
  }
  printf("digest %016llx over %ld points in 2 modes (%ld without data)\n", (unsigned long long)hash,
         n, failed);
  free(out);
  free(d_out);
  wrc_table_close(table);
  return 0;
}
