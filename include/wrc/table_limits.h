/**
 * @file table_limits.h
 * @brief The numbers every wrc table obeys (C99, included by wrc/runtime.h).
 *
 * One home for the bounds shared by the scene parser and generator, which refuse to make a table
 * outside them, and the runtime, which refuses to load one.
 */
#ifndef WRC_TABLE_LIMITS_H_
#define WRC_TABLE_LIMITS_H_

/** @name Axis values a table may hold
 *  Every node lies within ±WRC_AXIS_MAX_MAGNITUDE; neighbouring nodes are at least
 *  WRC_AXIS_MIN_STEP apart and at least WRC_AXIS_MIN_RELATIVE_STEP of the larger magnitude of
 *  the two. Axes are physical quantities in mm, N, mrad, ‰ or mm/s, far inside these bounds;
 *  the bounds keep every reciprocal and product the interpolation forms finite, and the
 *  position within a cell resolved to better than 1e-6 of the cell.
 *  @{ */
#define WRC_AXIS_MAX_MAGNITUDE 1e30
#define WRC_AXIS_MIN_STEP 1e-30
#define WRC_AXIS_MIN_RELATIVE_STEP 1e-9
/** Every finite output value at a node lies within ±WRC_VALUE_MAX_MAGNITUDE (forces in N and
 *  moments in N·mm are below 1e12): cubic lookups divide differences of values by steps down to
 *  WRC_AXIS_MIN_STEP, which stays finite (below 1e61) only for values so bounded. */
#define WRC_VALUE_MAX_MAGNITUDE 1e30
/** The wheelset's forward velocity, mm/s, wherever it enters (case files, scenes, the
 *  wheelset state of wrc_wheelset_eval()): at most WRC_VELOCITY_MAX (1 km/s, six times the
 *  rail speed record) and at least WRC_VELOCITY_MIN (1 µm/s; a case file may also give 0,
 *  standing). Creepages are rates divided by it; the solver's arithmetic stays exact down to
 *  about 1e-100 mm/s and is wrong at 1e-200, so the bound is far inside what is honest. */
#define WRC_VELOCITY_MIN 1e-3
#define WRC_VELOCITY_MAX 1e6
/** @} */

#endif /* WRC_TABLE_LIMITS_H_ */
