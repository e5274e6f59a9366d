#pragma once
/// @file scene.h
/// A scene (docs/reference/case-files.md, scenes): a wheel-rail case plus a `[table]` section that
/// spans a grid of states. Each table axis varies one quantity; quantities not on an axis come from
/// the case.
///
/// Axis values are given in one of three forms:
///  - `{from = a, to = b, step = h}`: a, a + h, a + 2h, ... up to b. b itself is included when
///    it lies on that grid within 1e-9·h (and then appears exactly as written), so
///    `{from = 0.0, to = 1.0, step = 0.1}` gives 11 values despite rounding. Needs h > 0 and
///    a <= b.
///  - `{from = a, to = b, count = n}`: n equally spaced values from a to b inclusive (n >= 2 and
///    a < b, or n = 1 and a = b).
///  - `[v0, v1, ...]`: explicit values, strictly ascending.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "wrc/core/case.h"
#include "wrc/quantities.h"

namespace wrc {

/// One table axis: its name (a scene axis of wrc/quantities.h) and its values, strictly ascending.
struct SceneAxis {
  std::string name;
  std::vector<double> values;
};

/// `[table.refine]`: the generator places the nodes of every axis itself until the
/// interpolation error meets a target (docs/tables.md). The axis values of `[table]` are then
/// the starting nodes: they are kept, and nodes are added between them where the error is.
struct RefineSettings {
  /// Target for the force outputs (fx fy fz fx_ws fy_ws fz_ws), as a fraction of the local
  /// wheel load (the prescribed fz, or the solved vertical force where z is prescribed).
  double load_fraction = 0.005;
  /// Absolute targets of other outputs, in the output's unit (e.g. z in mm). By default z
  /// (when stored) gets 0.003 mm.
  std::map<std::string, double, std::less<>> absolute;
  /// The outputs whose error drives the refinement, in scene output order: the force outputs
  /// among the scene's outputs and those with an absolute target.
  std::vector<std::string> outputs;
  /// The interpolation the table will be read with (`interpolation`): its error is the one
  /// measured, so a table for cubic lookups gets the nodes cubic lookups need.
  enum class Interpolation { kLinear, kCubic };
  Interpolation interpolation = Interpolation::kLinear;
  /// When the target is met (`quantile`): once this share of uniformly random states has its
  /// error within the target (judged on a 90 % upper confidence bound from 1000 exact solves),
  /// as `wrc verify` measures a table. 1: only once every sampled interval midpoint is within
  /// the target, which an interval across a contact jump never is (the budget stops the run).
  double quantile = 0.95;
  /// Budget: the table never grows beyond this many grid points.
  std::size_t max_points = 1'000'000;
  /// Budget: at most this many refinement passes after the starting grid.
  int max_passes = 40;
  /// Exact solves per axis interval and pass that measure its interpolation error.
  int samples = 24;
  /// Seed of the sample draw: a refinement is repeatable to the bit.
  std::uint64_t seed = 1;
  /// Smallest interval per axis name: an interval shorter than twice this is never split.
  /// Axes not listed get (range) / 2048.
  std::map<std::string, double, std::less<>> min_step;
  /// `[table.refine.slope]`: a target on the table's slopes at one state (centred running):
  /// the linearised contact a stability analysis or a simulator's Jacobian takes from it.
  struct Slope {
    /// Error of the table's slope against the solver's, relative to the solver's (with a
    /// floor: the output's pointwise target over the axis range).
    double fraction = 0.01;
    /// The state, per axis in dimension order; a node of the starting grid.
    std::vector<double> at;
    /// Spacing of the slope's samples per axis in dimension order; 0: the axis' slope is not a
    /// target.
    std::vector<double> step;
    /// Half-width of the least-squares window per axis, a whole number of steps: the slope is
    /// fitted through the samples at ±step, ±2·step, … ±window (window = step: the central
    /// difference).
    std::vector<double> window;
    /// Samples on each side of the state on axis a: window / step.
    int SamplesPerSide(std::size_t a) const;
  };
  std::optional<Slope> slope;
};

/// A parsed and validated scene.
struct Scene {
  /// The case with every axis quantity set to the axis' first value, so that it is complete.
  /// base.source_text is the full scene text.
  Case base;
  std::vector<SceneAxis> axes;  ///< In dimension order (`table.axes`).
  /// Output names (docs/reference/case-files.md), in file order.
  std::vector<std::string> outputs;
  /// Present when the scene asks the generator to place the nodes (`[table.refine]`).
  std::optional<RefineSettings> refine;

  /// Number of grid points: the product of the axis lengths.
  std::size_t PointCount() const;
  /// Axis lengths in dimension order (the table's array shape).
  std::vector<std::size_t> Shape() const;
};

/// The outputs used when `table.outputs` is absent: fx fy fz mx my mz n_patches contact_y
/// contact_angle pmax, plus z when fz is prescribed (fz is in the list anyway).
std::vector<std::string> DefaultSceneOutputs(bool fz_prescribed);

/// Whether neighbouring table-axis values a < b are far enough apart for the runtime to
/// interpolate between them (the WRC_AXIS_* limits of wrc/runtime.h).
bool AxisStepIsResolvable(double a, double b);

/// The value a table of this scene fixes for the state quantity `name` (kStateQuantities of
/// wrc/quantities.h): its value in the scene's case; NaN where the table does not fix it (an axis
/// of the scene, y_wheel, z with a prescribed fz and fz with a prescribed z, friction that
/// varies with the contact angle). Throws std::logic_error for a name that is not a state
/// quantity. What the runtime's wheelset API reads (the table's fixed_* attributes).
double FixedStateValue(const Scene& scene, std::string_view name);

/// The case at one grid point: `axis_values` holds one value per axis, in axis order, and need
/// not be grid nodes (e.g. random samples). A spin value is converted to omega with the case's
/// velocity and nominal radius; a mu value makes friction constant. Throws
/// std::invalid_argument when the number of values does not match, InputError for values that
/// are not allowed (NaN, mu < 0, fz <= 0).
Case CaseAtPoint(const Scene& scene, const std::vector<double>& axis_values);

/// The case at a grid node, one index per axis. Throws std::out_of_range for a bad index.
Case CaseAtIndex(const Scene& scene, const std::vector<std::size_t>& indices);

/// Reads and validates a scene file. Also reads both profiles (as the solver will), so that a
/// malformed profile is reported at the scene key that names it, before any point is solved.
/// Throws InputError with a message "file:line: key = value: problem".
Scene LoadScene(const std::filesystem::path& path);

/// Parses and validates scene text; see ParseCase() for `base_dir` and `display_name`.
Scene ParseScene(std::string_view toml_text, const std::filesystem::path& base_dir,
                 std::string_view display_name);

}  // namespace wrc
