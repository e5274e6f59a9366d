/**
 * @file runtime.h
 * @brief wrc runtime: look up precomputed wheel–rail contact tables (C99 API).
 *
 * A table is an HDF5 file written by `wrc generate` (layout in SPEC §4.2): outputs such as
 * fx … mz sampled on a rectilinear grid of axes such as y, roll, yaw, spin. This library loads a
 * table into memory and interpolates it. It depends on HDF5 only.
 *
 * The functions of SPEC §6 are here with exactly those names; everything else is an extension,
 * listed in runtime/README.md.
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

/* ---------------------------------------------------------------------------------------------
 * SPEC §6
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

/** Index of the axis called name, or WRC_ERR_NOT_FOUND (or another negative code). */
WRC_API int wrc_table_axis_index(const wrc_table* t, const char* name);

/** Index of the output called name, or WRC_ERR_NOT_FOUND (or another negative code). */
WRC_API int wrc_table_output_index(const wrc_table* t, const char* name);

/** The `unit` attribute of /axes/<name>, "" when absent; NULL on error. */
WRC_API const char* wrc_table_axis_unit(const wrc_table* t, int i);

/** The `unit` attribute of /outputs/<name>, "" when absent; NULL on error. */
WRC_API const char* wrc_table_output_unit(const wrc_table* t, int i);

/** A string attribute of the file's root group (format, wrc_version, created, scene, …), or
 *  NULL when there is none of that name (wrc_last_error() then says so). */
WRC_API const char* wrc_table_attribute(const wrc_table* t, const char* name);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* WRC_RUNTIME_H_ */
