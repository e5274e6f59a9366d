/* Changes each byte of a table in turn (XOR 0x5a) and opens every damaged copy with the C
 * runtime in this one process, so that the heap carries what earlier opens left in it (run it
 * under MALLOC_PERTURB_ as tools/flip_scan/flip_scan.sh does). Each copy must either be refused
 * or give exactly the intact table's numbers at every node and cell centre of its diagonal; a
 * crash ends the scan. Prints the counts: offsets, refused, identical, warned, different.
 *
 *   wrc_flip_scan TABLE SCRATCH [STRIDE]
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "wrc/runtime.h"

enum { kMaxPoints = 64 };

typedef struct {
  int n_points, n_outputs;
  double points[kMaxPoints][WRC_MAX_AXES];
  double* values; /* n_points × n_outputs */
  int flags[kMaxPoints];
} Probe;

static unsigned char* ReadAll(const char* path, long* size) {
  FILE* f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  *size = ftell(f);
  fseek(f, 0, SEEK_SET);
  unsigned char* data = malloc((size_t)*size);
  if (data && fread(data, 1, (size_t)*size, f) != (size_t)*size) {
    free(data);
    data = NULL;
  }
  fclose(f);
  return data;
}

static int WriteAll(const char* path, const unsigned char* data, long size) {
  FILE* f = fopen(path, "wb");
  if (!f) return 0;
  const int ok = fwrite(data, 1, (size_t)size, f) == (size_t)size;
  return fclose(f) == 0 && ok;
}

/* Points along the diagonal of the grid: node k of every axis and the middle of cell k. */
static void ChoosePoints(const wrc_table* t, Probe* p) {
  const int n_axes = wrc_table_num_axes(t);
  p->n_points = 0;
  for (int k = 0; p->n_points + 1 < kMaxPoints; ++k) {
    int any = 0;
    for (int half = 0; half < 2; ++half) {
      double* point = p->points[p->n_points];
      for (int a = 0; a < n_axes; ++a) {
        const int n = wrc_table_axis_size(t, a);
        const double* v = wrc_table_axis_values(t, a);
        const int i = k < n ? k : n - 1;
        point[a] = half && i + 1 < n ? 0.5 * (v[i] + v[i + 1]) : v[i];
        any |= k < n;
      }
      if (any) ++p->n_points;
    }
    if (!any) break;
  }
}

static void Evaluate(const wrc_table* t, Probe* p) {
  for (int i = 0; i < p->n_points; ++i)
    p->flags[i] = wrc_table_eval(t, p->points[i], p->values + (size_t)i * p->n_outputs);
}

int main(int argc, char** argv) {
  if (argc < 3) {
    fprintf(stderr, "usage: wrc_flip_scan TABLE SCRATCH [STRIDE]\n");
    return 2;
  }
  const long stride = argc > 3 ? atol(argv[3]) : 1;
  long size = 0;
  unsigned char* data = ReadAll(argv[1], &size);
  wrc_table* t = NULL;
  if (!data || stride < 1 || wrc_table_open(argv[1], &t) != 0) {
    fprintf(stderr, "wrc_flip_scan: cannot read the intact table %s\n", argv[1]);
    return 2;
  }
  Probe intact, damaged;
  intact.n_outputs = damaged.n_outputs = wrc_table_num_outputs(t);
  ChoosePoints(t, &intact);
  intact.values = malloc(sizeof(double) * kMaxPoints * (size_t)intact.n_outputs);
  damaged.values = malloc(sizeof(double) * kMaxPoints * (size_t)intact.n_outputs);
  Evaluate(t, &intact);
  wrc_table_close(t);
  long offsets = 0, refused = 0, identical = 0, warned = 0, different = 0;
  for (long off = 0; off < size; off += stride) {
    data[off] ^= 0x5a;
    if (!WriteAll(argv[2], data, size)) {
      fprintf(stderr, "wrc_flip_scan: cannot write %s\n", argv[2]);
      return 2;
    }
    data[off] ^= 0x5a;
    ++offsets;
    wrc_table* d = NULL;
    if (wrc_table_open(argv[2], &d) != 0) {
      ++refused;
      continue;
    }
    memcpy(damaged.points, intact.points, sizeof intact.points);
    damaged.n_points = intact.n_points;
    const int same_shape = wrc_table_num_outputs(d) == intact.n_outputs;
    if (same_shape) Evaluate(d, &damaged);
    const int same =
        same_shape &&
        memcmp(damaged.flags, intact.flags, sizeof(int) * (size_t)intact.n_points) == 0 &&
        memcmp(damaged.values, intact.values,
               sizeof(double) * (size_t)intact.n_points * (size_t)intact.n_outputs) == 0;
    if (wrc_table_warning(d) != NULL && wrc_table_warning(d)[0] != '\0') ++warned;
    if (same) {
      ++identical;
    } else {
      ++different;
      fprintf(stderr, "wrc_flip_scan: offset %ld opens with other numbers\n", off);
    }
    wrc_table_close(d);
  }
  printf("offsets %ld refused %ld identical %ld warned %ld different %ld\n", offsets, refused,
         identical, warned, different);
  free(intact.values);
  free(damaged.values);
  free(data);
  return different == 0 ? 0 : 1;
}
