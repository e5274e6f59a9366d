/*
 * A wheelset simulated on table lookups alone: the smallest template of a simulator that takes
 * its wheel-rail forces from a wrc table through the wheelset API.
 *
 *   wrc_wheelset_dynamics_example TABLE.h5 [SPEED_M_S [WHEEL_LOAD_N [RAIL_ORIGIN_Y_MM]]]
 *
 * The model is the one of `wrc study dynamics` (docs/dynamics.md): one wheelset on straight
 * track, held by primary springs to a frame moving at constant speed V; lateral displacement y
 * and yaw ψ integrated by classical fourth-order Runge–Kutta at 1 kHz over 2 s from y = 1 mm.
 * The wheel loads are constant; the roll follows y quasi-statically (the roll at which both
 * wheels carry their load at the same height, from the table's z output when it has one, else
 * 0). Parameters as in tables/wheelset_dynamics.toml. Prints y and ψ every 50 ms, the hunting
 * growth (last against first peak), and the CPU time per step.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "wrc/runtime.h"

/* The wheelset and its suspension (tables/wheelset_dynamics.toml). */
static const double kMass = 1813.0;                 /* kg */
static const double kYawInertia = 1120.0;           /* kg m^2 */
static const double kLateralStiffness = 100.0;      /* N/mm per axlebox */
static const double kLongitudinalStiffness = 100.0; /* N/mm per axlebox */
static const double kSemiSpacing = 1000.0;          /* mm, axleboxes from the centre */
static const double kNominalRadius = 460.0;         /* mm */
static const double kTimeStep = 1e-3;               /* s */
static const double kDuration = 2.0;                /* s */

typedef struct {
  double y, yaw, vy, vyaw; /* mm, rad, mm/s, rad/s */
} State;

typedef struct {
  const wrc_table* table;
  wrc_wheelset* wheelset;
  double velocity;             /* mm/s */
  double load;                 /* N per rail */
  double origin_y[2];          /* rail origins, mm */
  int z_output;                /* index of z, -1 if none */
  double roll_y[41], roll[41]; /* roll curve, y = 0 ... 10 mm */
  int flags;
} Model;

/* The wheelset height at which one wheel carries its load; the left wheel is the mirror image
 * of the right one the table was made for (y, roll change sign). */
static double height(const Model* m, int side, double y, double roll) {
  double point[WRC_MAX_AXES], out[64];
  const double mirror = side == WRC_RIGHT ? 1.0 : -1.0;
  int a;
  for (a = 0; a < wrc_table_num_axes(m->table); ++a) {
    const char* name = wrc_table_axis_name(m->table, a);
    point[a] = 0.0;
    if (strcmp(name, "y") == 0) point[a] = mirror * y;
    if (strcmp(name, "y_wheel") == 0) point[a] = mirror * (y - kNominalRadius * roll);
    if (strcmp(name, "roll") == 0) point[a] = mirror * roll;
    if (strcmp(name, "fz") == 0) point[a] = m->load;
  }
  if (wrc_table_eval(m->table, point, out) < 0) return NAN;
  return out[m->z_output];
}

/* Roll with equal heights of both wheels, by bisection over the table's roll axis. */
static void build_roll_curve(Model* m) {
  const int roll_axis = wrc_table_axis_index(m->table, "roll");
  double lo0 = 0.0, hi0 = 0.0;
  int i, k;
  if (roll_axis >= 0) {
    lo0 = wrc_table_axis_values(m->table, roll_axis)[0];
    hi0 = wrc_table_axis_values(m->table, roll_axis)[wrc_table_axis_size(m->table, roll_axis) - 1];
  }
  for (i = 0; i < 41; ++i) {
    double lo = lo0, hi = hi0;
    const double y = 0.25 * i;
    m->roll_y[i] = y;
    m->roll[i] = 0.0;
    if (m->z_output < 0 || roll_axis < 0 || i == 0) continue;
    for (k = 0; k < 40; ++k) {
      const double mid = 0.5 * (lo + hi);
      const double g_lo = height(m, WRC_RIGHT, y, lo) - height(m, WRC_LEFT, y, lo);
      const double g_mid = height(m, WRC_RIGHT, y, mid) - height(m, WRC_LEFT, y, mid);
      if (g_lo * g_mid <= 0.0)
        hi = mid;
      else
        lo = mid;
    }
    m->roll[i] = 0.5 * (lo + hi); /* an end of the axis when no root lies on it */
  }
}

static double roll_at(const Model* m, double y) {
  const double a = fabs(y) > 10.0 ? 10.0 : fabs(y);
  const int i = a >= 10.0 ? 39 : (int)(a / 0.25);
  const double t = (a - m->roll_y[i]) / 0.25;
  const double r = (1.0 - t) * m->roll[i] + t * m->roll[i + 1];
  return y < 0.0 ? -r : r;
}

/* Contact forces on the wheelset, both wheels in one call: the runtime reads vy and the yaw rate
 * on the yaw and spin axes (the poses of equal creepage) where the table has no vy and vyaw
 * axes. */
static int contact(Model* m, const State* s, double* fy, double* mz) {
  double fx = 0.0, mz_origin = 0.0;
  wrc_wheelset_state w;
  wrc_wheelset_result r;
  int side, flags;
  wrc_wheelset_state_init(&w);
  w.y = s->y;
  w.roll = roll_at(m, s->y);
  w.yaw = s->yaw;
  w.vy = s->vy;
  w.vyaw = s->vyaw;
  w.velocity = m->velocity;
  w.omega = -m->velocity / kNominalRadius;
  w.fz[0] = w.fz[1] = m->load;
  flags = wrc_wheelset_eval(m->wheelset, &w, &r);
  if (flags < 0) return flags;
  m->flags |= flags;
  *fy = 0.0;
  for (side = 0; side < 2; ++side) {
    fx -= r.wheel[side].force[0];
    *fy -= r.wheel[side].force[1];
    mz_origin -= r.wheel[side].moment[2] - m->origin_y[side] * r.wheel[side].force[0];
  }
  *mz = mz_origin + s->y * fx; /* about the wheelset centre */
  return 0;
}

static int derivative(Model* m, const State* s, State* d) {
  double fy, mz;
  const int code = contact(m, s, &fy, &mz);
  if (code < 0) return code;
  d->y = s->vy;
  d->yaw = s->vyaw;
  d->vy = 1000.0 * (fy - 2.0 * kLateralStiffness * s->y) / kMass;
  d->vyaw = (mz - 2.0 * kLongitudinalStiffness * kSemiSpacing * kSemiSpacing * s->yaw) /
            (1000.0 * kYawInertia);
  return 0;
}

static State advance(const State* s, const State* d, double h) {
  State r;
  r.y = s->y + h * d->y;
  r.yaw = s->yaw + h * d->yaw;
  r.vy = s->vy + h * d->vy;
  r.vyaw = s->vyaw + h * d->vyaw;
  return r;
}

static int rk4_step(Model* m, State* s, double h) {
  State k1, k2, k3, k4, t;
  if (derivative(m, s, &k1) < 0) return -1;
  t = advance(s, &k1, 0.5 * h);
  if (derivative(m, &t, &k2) < 0) return -1;
  t = advance(s, &k2, 0.5 * h);
  if (derivative(m, &t, &k3) < 0) return -1;
  t = advance(s, &k3, h);
  if (derivative(m, &t, &k4) < 0) return -1;
  s->y += h / 6.0 * (k1.y + 2.0 * k2.y + 2.0 * k3.y + k4.y);
  s->yaw += h / 6.0 * (k1.yaw + 2.0 * k2.yaw + 2.0 * k3.yaw + k4.yaw);
  s->vy += h / 6.0 * (k1.vy + 2.0 * k2.vy + 2.0 * k3.vy + k4.vy);
  s->vyaw += h / 6.0 * (k1.vyaw + 2.0 * k2.vyaw + 2.0 * k3.vyaw + k4.vyaw);
  return 0;
}

int main(int argc, char** argv) {
  wrc_table* table;
  Model m;
  State s = {1.0, 0.0, 0.0, 0.0};
  const int steps = (int)(kDuration / kTimeStep + 0.5);
  double first_peak = 0.0, last_peak = 0.0, previous = 0.0, before = 0.0;
  clock_t start;
  double cpu;
  int i;
  if (argc < 2) {
    fprintf(stderr, "usage: %s TABLE.h5 [SPEED_M_S [WHEEL_LOAD_N [RAIL_ORIGIN_Y_MM]]]\n", argv[0]);
    return 2;
  }
  memset(&m, 0, sizeof m);
  m.velocity = 1000.0 * (argc > 2 ? atof(argv[2]) : 30.0);
  m.load = argc > 3 ? atof(argv[3]) : 12500.0;
  /* Lateral position of the right rail's origin as the solver places it for the Manchester
   * pair (gauge 1435 mm measured 14 mm below the top, cant 1/40); the left one mirrored. */
  m.origin_y[WRC_RIGHT] = argc > 4 ? atof(argv[4]) : 752.25;
  m.origin_y[WRC_LEFT] = -m.origin_y[WRC_RIGHT];
  if (!(m.velocity > 0.0) || !(m.load > 0.0)) {
    fprintf(stderr, "%s: speed and wheel load must be positive\n", argv[0]);
    return 2;
  }
  if (wrc_table_open(argv[1], &table) != 0 || wrc_wheelset_create(NULL, table, &m.wheelset) != 0) {
    fprintf(stderr, "%s: %s\n", argv[0], wrc_last_error());
    return 1;
  }
  m.table = table;
  m.z_output = wrc_table_output_index(table, "z");
  wrc_wheelset_set_rail_origin(m.wheelset, WRC_RIGHT, m.origin_y[WRC_RIGHT], 0.0);
  wrc_wheelset_set_rail_origin(m.wheelset, WRC_LEFT, m.origin_y[WRC_LEFT], 0.0);
  build_roll_curve(&m);
  printf("# V = %g m/s, wheel load %g N, roll at y = 5 mm: %.3e rad\n# t_s y_mm yaw_rad\n",
         m.velocity / 1000.0, m.load, roll_at(&m, 5.0));
  start = clock();
  for (i = 1; i <= steps; ++i) {
    before = previous;
    previous = s.y;
    if (rk4_step(&m, &s, kTimeStep) != 0) {
      fprintf(stderr, "%s: step %d: %s\n", argv[0], i, wrc_last_error());
      return 1;
    }
    /* A peak of |y|: y turned around at the previous step. */
    if ((previous - before) * (s.y - previous) < 0.0) {
      if (first_peak == 0.0) first_peak = fabs(previous);
      last_peak = fabs(previous);
    }
    if (i % 50 == 0) printf("%.3f %.6f %.6e\n", i * kTimeStep, s.y, s.yaw);
  }
  cpu = (double)(clock() - start) / CLOCKS_PER_SEC;
  printf("# peaks of |y|: first %.4f mm, last %.4f mm (%s)%s\n", first_peak, last_peak,
         last_peak > first_peak ? "growing: hunting" : "decaying: stable",
         (m.flags & WRC_FLAG_CLAMPED) ? "; some states were outside the table (clamped)" : "");
  printf("# %.3f us per step, %.0f times real time (CPU)\n", 1e6 * cpu / steps,
         cpu > 0.0 ? kDuration / cpu : INFINITY);
  wrc_wheelset_destroy(m.wheelset);
  wrc_table_close(table);
  return 0;
}
