/**
 * @file runtime.h
 * @brief wrc runtime: look up precomputed wheel–rail contact tables (C99 API).
 *
 * A table is an HDF5 file written by `wrc generate`: outputs such as
 * fx … mz sampled on a rectilinear grid of axes such as y, roll, yaw, spin. This library loads a
 * table into memory and interpolates it. It depends on HDF5 only.
 *
 * Reference: docs/reference/runtime.md (an overview) and runtime/README.md (every function,
 * flag and error code, wheelsets, Python, linking).
 *
 * Error handling: functions returning int give 0 (or non-negative flags) on success and a
 * negative WRC_ERR_* code on failure; functions returning pointers give NULL on failure. The
 * reason is then in wrc_last_error(), a per-thread message naming the file, the dataset or
 * argument and the problem.
 *
 * Threads: a table handle may be evaluated from any number of threads at once. Opening, closing
 * and wrc_table_set_interpolation() must not run concurrently with other calls on the same
 * handle.
 */
#ifndef WRC_RUNTIME_H_
#define WRC_RUNTIME_H_

#ifdef __cplusplus
extern "C" {
#endif

/** Marks the API of a shared-library build as exported; everything else stays hidden. */
#if defined(__GNUC__)
#define WRC_API __attribute__((visibility("default")))
#else
#define WRC_API
#endif

/** An open, fully loaded table. Opaque. */
typedef struct wrc_table wrc_table;

/** @name Evaluation result flags (non-negative return values of the eval functions)
 *  @{ */
#define WRC_OK 0
/** The point lay outside the table on some axis and was clamped to the table's range. */
#define WRC_FLAG_CLAMPED 1
/** Some grid node whose data enters the result has a non-zero /status (no contact, not
 *  converged, error). Multilinear: the corners of the cell; cubic: also the nodes its slopes
 *  are computed from (up to 2–3 nodes away along each axis). */
#define WRC_FLAG_STATUS 2
/** @} */

/** @name Error codes (negative return values)
 *  @{ */
/** A required pointer argument was NULL. */
#define WRC_ERR_NULL_POINTER (-1)
/** A coordinate of the point was NaN. */
#define WRC_ERR_NAN_INPUT (-2)
/** The table holds no value there: every node of the cell failed (NaN) for some output. That
 *  output's entries of out are NaN; wrc_last_error() names it. A cell with only some failed
 *  nodes is interpolated from its valid corners instead (see wrc_table_eval()). */
#define WRC_ERR_NO_DATA (-3)
/** An argument was out of range (index, interpolation mode). */
#define WRC_ERR_INVALID_ARGUMENT (-4)
/** Memory could not be allocated. */
#define WRC_ERR_OUT_OF_MEMORY (-5)
/** No axis, output or attribute of that name. */
#define WRC_ERR_NOT_FOUND (-6)
/** The file does not exist or is not an HDF5 file. */
#define WRC_ERR_FILE (-10)
/** The file is HDF5 but not a valid wrc table (format, version, shapes, values). */
#define WRC_ERR_FORMAT (-11)
/** Unexpected internal failure (a bug). */
#define WRC_ERR_INTERNAL (-99)
/** @} */

/** @name Interpolation modes
 *  @{ */
/** Multilinear: C⁰, exact for multilinear functions. The default. */
#define WRC_INTERP_LINEAR 0
/** Tensor-product cubic Hermite with monotonicity-preserving slopes: C¹, exact for functions
 *  that are cubic along each axis where the data is monotone-consistent, no overshoot across
 *  jumps along an axis. See runtime/README.md. */
#define WRC_INTERP_CUBIC 1
/** @} */

/** Largest number of axes a table may have. */
#define WRC_MAX_AXES 8

/* The limits on a table's axes and values and on the velocity (WRC_AXIS_*, WRC_VALUE_*,
 * WRC_VELOCITY_*): the generator checks them when it writes a table, the runtime when it
 * reads one. */
#include "wrc/table_limits.h"

/* ---------------------------------------------------------------------------------------------
 * The table API
 * ------------------------------------------------------------------------------------------- */

/** Opens and loads a table, validating its format, version, shapes and values.
 *  @param path HDF5 file.
 *  @param out  Receives the handle (NULL on failure). Free it with wrc_table_close().
 *  @return 0, or WRC_ERR_FILE / WRC_ERR_FORMAT / WRC_ERR_OUT_OF_MEMORY / WRC_ERR_NULL_POINTER. */
WRC_API int wrc_table_open(const char* path, wrc_table** out);

/** Frees a table; NULL is allowed. */
WRC_API void wrc_table_close(wrc_table* t);

/** Number of axes (array dimensions), or a negative code for a NULL table. */
WRC_API int wrc_table_num_axes(const wrc_table* t);

/** Number of outputs, or a negative code for a NULL table. */
WRC_API int wrc_table_num_outputs(const wrc_table* t);

/** Name of axis i (0-based, in dimension order), or NULL. Valid until the table is closed. */
WRC_API const char* wrc_table_axis_name(const wrc_table* t, int i);

/** Number of grid nodes on axis i, or a negative code. */
WRC_API int wrc_table_axis_size(const wrc_table* t, int i);

/** The strictly ascending node coordinates of axis i (wrc_table_axis_size(t, i) values), or
 *  NULL. Valid until the table is closed. */
WRC_API const double* wrc_table_axis_values(const wrc_table* t, int i);

/** Name of output i, or NULL. Outputs are in the order of the /outputs attribute `order` when
 *  present, otherwise in creation order, otherwise in name order. */
WRC_API const char* wrc_table_output_name(const wrc_table* t, int i);

/** Interpolates all outputs at a point.
 *
 *  Next to a failed node (/status != 0, outputs NaN) the result comes from the valid corners of
 *  the cell: per output, the multilinear weights renormalised over the corners with a finite
 *  value (a convex combination of them, continuous inside the cell), in both interpolation
 *  modes, with WRC_FLAG_STATUS set; only a cell whose every node failed gives WRC_ERR_NO_DATA.
 *  A finite point inside the table therefore never gets NaN otherwise. runtime/README.md
 *  describes the fallback and where it is not continuous.
 *  @param point One coordinate per axis, in axis order.
 *  @param out   Receives one value per output.
 *  @return WRC_OK (0), or a combination of WRC_FLAG_CLAMPED and WRC_FLAG_STATUS, or a negative
 *          WRC_ERR_* code (NaN input, NULL pointer, no data) with the reason in
 *          wrc_last_error(). Thread-safe; does not allocate. */
WRC_API int wrc_table_eval(const wrc_table* t, const double* point, double* out);

/** Message describing the last failure in the calling thread ("" if none). Not cleared by
 *  successful calls. Valid until the next failing call in this thread. */
WRC_API const char* wrc_last_error(void);

/* ---------------------------------------------------------------------------------------------
 * Extensions
 * ------------------------------------------------------------------------------------------- */

/** Like wrc_table_eval(), and also the derivatives of every output with respect to every axis.
 *  @param d_out n_outputs × n_axes values, row-major: d_out[k * n_axes + a] = ∂out[k]/∂point[a].
 *               May be NULL (then this is wrc_table_eval()). The derivatives are those of the
 *               function actually returned: zero along an axis on which the point was clamped
 *               and along axes with a single node. Multilinear: the derivative of the cell's
 *               multilinear form (one-sided at nodes: the cell above is used, except at the
 *               last node). Thread-safe; does not allocate. */
WRC_API int wrc_table_eval_deriv(const wrc_table* t, const double* point, double* out,
                                 double* d_out);

/** Selects WRC_INTERP_LINEAR or WRC_INTERP_CUBIC for this handle. The first switch to cubic
 *  computes and stores node slopes (2^(number of axes with more than one node) values per node
 *  and output), so it allocates and may fail with WRC_ERR_OUT_OF_MEMORY; evaluation stays
 *  allocation-free. Not to be called while other threads evaluate this handle.
 *  @return 0 or a negative code. */
WRC_API int wrc_table_set_interpolation(wrc_table* t, int mode);

/** The handle's interpolation mode, or a negative code. */
WRC_API int wrc_table_interpolation(const wrc_table* t);

/** @name Storage of the node data a lookup reads
 *  @{ */
/** Doubles, as the table holds them. The default. */
#define WRC_STORAGE_FLOAT64 0
/** A float copy of the node data (and of the cubic data): half the memory a lookup reads, the
 *  sums still in double. Values change by the float rounding of the node data, at most 6e-8
 *  of a value (runtime/README.md says what it does on the shipped table). */
#define WRC_STORAGE_FLOAT32 1
/** @} */

/** Selects what this handle's lookups read: WRC_STORAGE_FLOAT64 or WRC_STORAGE_FLOAT32. The
 *  switch to float32 allocates the copy (the doubles stay, for wrc_table_node_values and for
 *  cells next to failed nodes, which are interpolated from them); it may fail with
 *  WRC_ERR_OUT_OF_MEMORY. Not to be called while other threads evaluate this handle.
 *  @return 0 or a negative code. */
WRC_API int wrc_table_set_storage(wrc_table* t, int storage);

/** The handle's storage, or a negative code. */
WRC_API int wrc_table_storage(const wrc_table* t);

/** Index of the axis called name, or WRC_ERR_NOT_FOUND (or another negative code). */
WRC_API int wrc_table_axis_index(const wrc_table* t, const char* name);

/** Index of the output called name, or WRC_ERR_NOT_FOUND (or another negative code). */
WRC_API int wrc_table_output_index(const wrc_table* t, const char* name);

/** The `unit` attribute of /axes/<name>, "" when absent; NULL on error. */
WRC_API const char* wrc_table_axis_unit(const wrc_table* t, int i);

/** The `unit` attribute of /outputs/<name>, "" when absent; NULL on error. */
WRC_API const char* wrc_table_output_unit(const wrc_table* t, int i);

/** The table's data as loaded: for each grid node (row-major over the axes, the last axis
 *  fastest) one value per output, in output order; the product of the axis sizes times
 *  wrc_table_num_outputs(t) values. NULL for a NULL table. Valid until the table is closed. */
WRC_API const double* wrc_table_node_values(const wrc_table* t);

/** The /status of each grid node (0 ok, 1 no contact, 2 not converged, 3 error), in the order
 *  of wrc_table_node_values(). NULL for a NULL table. Valid until the table is closed. */
WRC_API const signed char* wrc_table_node_status(const wrc_table* t);

/** A string attribute of the file's root group (format, wrc_version, created, scene, …), or
 *  NULL when there is none of that name (wrc_last_error() then says so). */
WRC_API const char* wrc_table_attribute(const wrc_table* t, const char* name);

/** A float64 attribute of the file's root group (the fixed state a table was made at:
 *  wheelset_velocity, wheelset_nominal_radius, fixed_y, …; docs/reference/table-layout.md) into
 *  *value. WRC_OK, or WRC_ERR_NOT_FOUND when there is none of that name (tables written before
 *  these attributes hold the same values in their scene text only), WRC_ERR_NULL_POINTER. */
WRC_API int wrc_table_number_attribute(const wrc_table* t, const char* name, double* value);

/** Why the table should be replaced although it loaded, or NULL: a table written before tables
 *  were sealed (a SHA-256 of its bytes checked before HDF5 reads them) loads, but damage to it
 *  is found only as HDF5 reads it; `wrc upgrade OLD.h5 -o NEW.h5` seals it. */
WRC_API const char* wrc_table_warning(const wrc_table* t);

/* ---------------------------------------------------------------------------------------------
 * Wheelsets
 *
 * A wheelset is two wheels on two rails; each wheel is read from a table made for one wheel
 * (one case = one wheel on one rail). Either side may be served by a table made for the other
 * side, read as its mirror image in the track's x–z plane: the pose quantities that change sign
 * under that mirror (y, roll, yaw, vy, vroll, vyaw) are negated on the way in, and the outputs
 * that do (fy, mx, mz, contact_y, contact_angle) on the way out; z, fz, omega, spin, velocity,
 * mu, fx, my and fz stay. This is how the solver itself solves a `side = "left"` case.
 * ------------------------------------------------------------------------------------------- */

/** Index of the left and the right wheel in the arrays below. */
#define WRC_LEFT 0
#define WRC_RIGHT 1

/** Wheelset result flag (besides WRC_FLAG_CLAMPED and WRC_FLAG_STATUS, per wheel): the state
 *  gives a quantity the table has no axis for, at a value other than the one the table was made
 *  with; the table's value was used. */
#define WRC_FLAG_FIXED 4

/** Two wheels, each with its table. Opaque; the tables are borrowed and must outlive it. */
typedef struct wrc_wheelset wrc_wheelset;

/** A wheelset's state as a multibody simulator has it: track frame (x along the track, y
 *  lateral, z down), mm, rad, s, N. */
typedef struct wrc_wheelset_state {
  double y;        /**< mm, lateral displacement of the wheelset. */
  double z;        /**< mm, vertical displacement (down), 0 at the nominal position. */
  double roll;     /**< rad, about x. */
  double yaw;      /**< rad, about z. */
  double vy;       /**< mm/s, lateral velocity. */
  double vroll;    /**< rad/s. */
  double vyaw;     /**< rad/s. */
  double omega;    /**< rad/s, rotation about the axle; negative when rolling forward. */
  double velocity; /**< mm/s, forward speed V > 0. */
  /** N, vertical force on each rail ([WRC_LEFT], [WRC_RIGHT]): read on tables with an fz
   *  axis (made with z solved for); NaN when not known. */
  double fz[2];
  /** Friction coefficient at each wheel, read on tables with a mu axis; NaN when not known. */
  double mu[2];
} wrc_wheelset_state;

/** One wheel's contact: forces and moments on the rail, in track coordinates. */
typedef struct wrc_wheel_contact {
  double force[3];      /**< N, (fx, fy, fz) on the rail. */
  double moment[3];     /**< N·mm, (mx, my, mz) on the rail, about the rail's origin. */
  double contact_y;     /**< mm, lateral position of the force resultant on the rail profile. */
  double contact_angle; /**< rad, surface inclination there (track frame). */
  /** N, frictional power per distance rolled, Tγ = −(ξ·Fx + η·Fy + φ·Mz) summed over the
   *  patches: the wear number of the table's t_gamma output. */
  double t_gamma;
  int flags; /**< WRC_FLAG_CLAMPED | WRC_FLAG_STATUS | WRC_FLAG_FIXED. */
} wrc_wheel_contact;

/** Both wheels and the total. Outputs a table does not hold are NaN. */
typedef struct wrc_wheelset_result {
  wrc_wheel_contact wheel[2]; /**< [WRC_LEFT], [WRC_RIGHT] */
  double force[3];            /**< N, on the wheelset: −(sum of the forces on the rails). */
  /** N·mm, on the wheelset about the track origin: −Σ (moment + origin × force) over the
   *  rails, with the rail origins of wrc_wheelset_set_rail_origin(); NaN until both are set. */
  double moment[3];
} wrc_wheelset_result;

/** Fills a state with zeros, and NaN for fz and mu (not known). The caller then sets at least
 *  velocity and omega. NULL is allowed. */
WRC_API void wrc_wheelset_state_init(wrc_wheelset_state* state);

/** Makes a wheelset from a table for each side. Either may be NULL: that side is then served by
 *  the other table, mirrored. A table made for the opposite side (its scene's wheelset.side) is
 *  read mirrored too. Each table's scene must give state.velocity; its axes may be any of y, z,
 *  fz, roll, yaw, spin, omega, vy, vyaw, mu.
 *  @return 0, or WRC_ERR_NULL_POINTER (both tables or out NULL), WRC_ERR_FORMAT (scene without
 *          a velocity, unknown axis), WRC_ERR_OUT_OF_MEMORY. */
WRC_API int wrc_wheelset_create(const wrc_table* left, const wrc_table* right, wrc_wheelset** out);

/** Frees a wheelset (not its tables); NULL is allowed. */
WRC_API void wrc_wheelset_destroy(wrc_wheelset* wheelset);

/** Sets the origin of a rail (side WRC_LEFT or WRC_RIGHT) in the track frame, (y, z) in mm, as
 *  `wrc solve` reports it; needed for the wheelset's total moment only. Not to be called while
 *  other threads evaluate this wheelset. @return 0 or a negative code. */
WRC_API int wrc_wheelset_set_rail_origin(wrc_wheelset* wheelset, int side, double y, double z);

/** Evaluates both wheels. Velocities enter relative to the forward speed: a table made at speed
 *  V0 is read at vy·V0/V, vyaw·V0/V (and vroll, omega likewise; spin = −omega·r0/V − 1 with the
 *  table's nominal radius r0), so one table serves every speed. On a table without vy and vroll
 *  axes the lateral velocities are read on the yaw axis at yaw − vy/V + vroll·r0/V, without a vyaw
 *  axis the yaw rate on the spin axis at spin + vyaw·y_c/V (y_c = ±(flange_back_distance/2 −
 *  flange_back_position), + right): the poses of equal creepage (runtime/README.md).
 *  @return the flags of both wheels or'ed (each wheel's in result->wheel[i].flags), or a
 *          negative WRC_ERR_* code (NULL pointer, NaN input, velocity ≤ 0, no data) with the
 *          reason in wrc_last_error(). Thread-safe; does not allocate. */
WRC_API int wrc_wheelset_eval(const wrc_wheelset* wheelset, const wrc_wheelset_state* state,
                              wrc_wheelset_result* result);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* WRC_RUNTIME_H_ */
