#pragma once
/// @file profile.h
/// Wheel and rail profiles: readers for the file formats CONTACT accepts, the repairs CONTACT
/// applies to measured data, and a smooth arc-length spline of the result.
///
/// Conventions (as CONTACT's "Inputs regarding wheel and rail profiles",
/// docs/reference/conventions.md): lengths in mm; rail profiles in rail coordinates and wheel
/// profiles in wheel coordinates, y lateral and positive towards the field side, z positive
/// downwards. After ReadProfile the points run
///  - for a rail:  from the track centre to the field side, y ascending overall;
///  - for a wheel: from the field side to the flange side, y descending overall;
/// so that, walking along the points, the material is on the right-hand side (in the y–z
/// picture with z pointing down). The direction is judged from the two end points; when they
/// have the same y the order is kept and a warning says so.
///
/// Typical use:
/// @code
///   wrc::ProfileOptions options;
///   options.mirror_y = true;
///   wrc::Profile rail = wrc::ReadProfile("avg_HR.BAN", wrc::ProfileKind::kRail, options);
///   for (const std::string& w : rail.warnings) std::cerr << "warning: " << w << '\n';
///   wrc::ProfileSpline spline(rail);
///   wrc::ProfileHeight top = spline.ZAtY(0.0);
/// @endcode

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace wrc {

/// Which body a profile describes; fixes the expected orientation (see file comment).
enum class ProfileKind { kRail, kWheel };

/// How the file's contents were read.
enum class ProfileFormat {
  kSimpack,   ///< Simpack .prr/.prw: header.begin / spline.begin / point.begin blocks.
  kMiniProf,  ///< MiniProf .ban/.whl: header lines (mostly key=value), then numeric columns.
  kTable,     ///< Plain columns y, z: comma, semicolon or white space separated.
};

/// Whether z is mirrored (z → −z), as CONTACT's MIRRORZ.
enum class MirrorZ {
  kAuto,  ///< MIRRORZ = 0: mirror when the end faces point the wrong way (ProfileOptions).
  kYes,   ///< MIRRORZ = 1: always mirror.
  kNo,    ///< MIRRORZ = −1: use z as given.
};

/// What ReadProfile / MakeProfile do with the points beyond parsing them.
struct ProfileOptions {
  /// Mirror y (y → −y) before anything else, as CONTACT's MIRRORY = 1. MiniProf rail files
  /// usually need it (avg_HR.BAN does).
  bool mirror_y = false;
  /// Decide mirror_y from the profile's shape instead (mirror_y is then ignored), see
  /// LateralOrientation: y is mirrored when the shape says the profile is mirrored, kept when it
  /// says it is not or cannot tell (with a warning).
  bool detect_mirror_y = false;
  /// Add a warning saying what the automatic orientation (detect_mirror_y, MirrorZ::kAuto)
  /// decided and why, for callers whose user asked for it explicitly.
  bool report_orientation = false;
  /// Factor applied to y and z before anything else, as CONTACT's SCALE_YZ: 1000 for a file
  /// in metres, 25.4 for inches. Finite and > 0.
  double scale_yz = 1.0;
  /// Mirror z. Automatic detection looks at the two ends of the profile: over the last 2 mm of
  /// each end, a face steeper than 30° counts as a side face. Rail side faces must run towards
  /// +z (downwards) at the ends, wheel side faces (flange back, field-side chamfer) towards −z.
  /// z is mirrored when the side faces found point the wrong way in majority; with no side face
  /// (flat or grooved profiles) or a tie, z is kept and a warning says so. This follows the user
  /// guide's description of CONTACT's heuristic ("based on wheel and rail side faces"); its exact
  /// algorithm is not documented. It agrees with CONTACT on every measured profile file whose
  /// behaviour is known (Simpack files kept, MiniProf rails mirrored, grooves kept). With kYes
  /// or kNo the same test runs on the result, and a warning naming mirror_z is added (and kept
  /// in Profile::orientation_doubts) when the side faces say it is upside down.
  MirrorZ mirror_z = MirrorZ::kAuto;
  /// Smoothing wavelength L_filt in mm (CONTACT's SMOOTH with ISMOOTH = 1); 0 = no smoothing,
  /// otherwise finite and > 0. The points are replaced by a weighted cubic smoothing spline that
  /// halves fluctuations of wavelength L_filt along the profile, damps shorter ones more and
  /// keeps longer ones:
  /// minimises Σ w_i |x_i − f(s_i)|² + λ ∫|f''(s)|² ds with w_i = (s_{i+1} − s_{i−1})/2 and
  /// λ = (L_filt/2π)⁴, s the chord length of the repaired points.
  double smoothing = 0.0;
  /// Zig-zag threshold in degrees (CONTACT's ZIGTHRS = 5π/6): a turn of the polyline larger than
  /// this counts as turning back. Must lie in (45, 180]; 180 disables the check.
  double zigzag_threshold_deg = 150.0;
  /// Also delete single points where the polyline turns back by more than the threshold while
  /// its neighbours do not (spikes). CONTACT's documented zig-zag rule only handles pairs, so
  /// false gives that rule alone; true (default) additionally removes outliers such as the
  /// flange-tip point at line 222 of Car7216_0001r.whl.
  bool remove_spikes = true;
  /// Kink detection (CONTACT's KINKHIGH, KINKLOW, KINKWID). A kink is a point where the
  /// polyline of the repaired points turns by more than `kink_high_rad` (the inclination change
  /// δα_i between segments i−1→i and i→i+1) while no other point within `kink_width` mm of arc
  /// length (summed chords) on either side turns by more than `kink_low_rad`. Such an isolated
  /// corner is real geometry (a groove edge, a roller's side face) and is kept sharp: the spline
  /// and the smoothing are made piecewise between kinks. Clustered large turns are roughness and
  /// are left to the smoothing. kink_high_rad >= π disables the detection (the result is then
  /// the plain spline through all points); it must be > 0.
  double kink_high_rad = 0.52359877559829887;  // π/6
  /// Neighbour threshold in rad; a negative value (the default) means kink_high_rad / 5. NaN is
  /// refused.
  double kink_low_rad = -1.0;
  /// Half-width in mm of the neighbourhood that must be free of turns above kink_low_rad
  /// (finite, >= 0).
  double kink_width = 2.0;
};

/// A profile after reading and repair: points (y_i, z_i) in the profile's own coordinates.
struct Profile {
  ProfileKind kind = ProfileKind::kRail;
  ProfileFormat format = ProfileFormat::kTable;
  std::string source;       ///< The file name as given (or the name passed to MakeProfile).
  std::vector<double> y;    ///< Lateral coordinates, mm.
  std::vector<double> z;    ///< Vertical coordinates (positive down), mm.
  std::vector<int> lines;   ///< Line in the source file of each point (1-based); for points
                            ///< from MakeProfile, the 1-based index of the input point.
  bool mirrored_y = false;  ///< y was mirrored (option mirror_y or the Simpack file's mirror.y).
  bool mirrored_z = false;  ///< z was mirrored (option, auto-detection or the Simpack file).
  bool reversed = false;    ///< The point order was reversed to run as documented above.
  bool smoothed = false;    ///< The points are the values of the smoothing spline.
  /// Indices of the kinks (see ProfileOptions::kink_high_rad), ascending, interior points only.
  /// Kinks are geometry, not repairs, so they add no warning. ProfileSpline keeps the curve's
  /// direction discontinuous at each of them; clear the list to get one smooth spline.
  std::vector<std::size_t> kinks;
  /// Everything repaired or ignored, one sentence each, naming the file and its line numbers.
  std::vector<std::string> warnings;
  /// The warnings that say the profile looks upside down or mirrored, with the key to change
  /// (also in `warnings`): callers add them to errors that a wrong orientation can cause.
  std::vector<std::string> orientation_doubts;

  std::size_t size() const { return y.size(); }
  /// Length of the polyline through the points, mm.
  double PolylineLength() const;
};

/// Points as they stand in a file, before any of the repairs of ReadProfile. Simpack in-file
/// processing (units.len.f, shift, bounds, point.dist.min, mirror.y/z, inversion) is applied, as
/// CONTACT applies it before its own options.
struct ProfilePoints {
  ProfileFormat format = ProfileFormat::kTable;
  std::string source;
  std::vector<double> y;
  std::vector<double> z;
  std::vector<int> lines;  ///< 1-based line of each point.
  bool mirrored_y = false;
  bool mirrored_z = false;
  /// What the file says it is: Simpack's header "type" (0 rail, 1 wheel); empty otherwise.
  std::optional<ProfileKind> declared_kind;
  std::vector<std::string> warnings;
};

/// Rail or wheel as suggested by the extension: .prr/.ban rail, .prw/.whl wheel (any case).
std::optional<ProfileKind> ProfileKindFromExtension(const std::string& path);

/// The format used for `path`: by extension (.prr/.prw Simpack, .ban/.whl MiniProf, .csv
/// table); for other extensions by content (Simpack block keywords, MiniProf header keys),
/// defaulting to a table. Throws InputError if the file cannot be opened or is empty.
ProfileFormat DetectProfileFormat(const std::string& path);

/// Parses a profile file without repairing it. Throws wrc::InputError: "<file>: cannot open
/// profile file: ..." for a missing, unreadable file or a directory; "<file>:<line>: ..." for an
/// empty file, a value that is not a number or not finite (NaN, Inf, 1e999) in the data section,
/// a data section that cannot be found, and the Simpack errors below. The format comes from the
/// extension, or from the contents for other extensions (see DetectProfileFormat).
///
/// Format details:
///  - Simpack: comments start with '!' or '%' (outside quotes); points are the rows "y z
///    [weight]" (separated by spaces, tabs or commas) between point.begin and point.end; weights
///    are ignored (with a warning if not 1), further columns too (warning). Errors: point.end
///    without point.begin, header.end/spline.end inside the point block, a file ending inside
///    it, no point block at all, a non-finite number in a setting, a non-zero "rotate" and
///    units.len.f <= 0. A non-zero approx.smooth is ignored with a warning, a missing
///    units.len.f means mm (warning).
///  - MiniProf: the first two columns are y (MiniProf's X) and z (MiniProf's Y). The data
///    section starts at the first purely numeric line followed by two more numeric lines (blank,
///    comment and switched-off lines in between do not count), or at the first purely numeric
///    line when there is no such run; the lines before are the header. Numeric lines in the
///    header (the "Sd Sh qR" line of old wheel files, e.g. avg_wheel.whl line 7) are ignored with
///    a warning, and so are non-zero XOffset/YOffset (not applied). Lines starting with '%', '!'
///    or '#' are comments. In the data section, lines starting with a double quote are
///    switched-off points and skipped with a warning; after the numbers '%', '!' and '"' start
///    comments; other text after the numbers of a data line is ignored with a warning; any other
///    text is an error.
///  - Table: columns separated by commas, semicolons, tabs or spaces (with ';' as separator a
///    decimal comma is accepted); '#', '%' and '!' start comments; non-numeric lines are allowed
///    only before the first numeric line (a header). The first two columns are y and z.
ProfilePoints ReadProfilePoints(const std::string& path);

/// Reads `path` (ReadProfilePoints), then repairs it with RepairProfile. Adds a warning when the
/// file declares the other kind (Simpack header "type") or, without a declaration, its extension
/// suggests the other kind.
Profile ReadProfile(const std::string& path, ProfileKind kind, const ProfileOptions& options = {});

/// First checks the options, that every coordinate is finite and that there are at least 4
/// points. Then the repairs, in CONTACT's order:
///  1. mirror y (option), mirror z (option or auto-detection, see ProfileOptions::mirror_z);
///  2. drop repeats: points within 1 nm (1e-6 mm) of the previous point (warning); done again
///     after steps 4 and 5, whose replacement points can land on a neighbour;
///  3. reverse the order if needed (see file comment);
///  4. zig-zags: where two successive points both turn the polyline by more than the threshold,
///     the pair is replaced by its average (CONTACT's rule; avg_HR.BAN loses one point); a single
///     point turning by more than the threshold (a spike) is deleted unless remove_spikes is
///     false (a wrc extension); warnings;
///  5. loops: where the polyline crosses itself, a loop of at most 2 mm (a stitching artefact)
///     is cut out at the crossing (warning); a longer loop is an error, as in CONTACT;
///  6. checks: at least 4 points remain (checked after every step above); the length of the
///     polyline is between 5 and 500 mm as CONTACT requires (this catches profiles in m or
///     inches);
///  7. kinks (ProfileOptions::kink_high_rad), stored in Profile::kinks;
///  8. smoothing (ProfileOptions::smoothing), separately on each part between kinks, with the
///     kink points held fixed, so that smoothing never rounds a kink.
/// Throws InputError naming the file (and lines) when a check fails or an option is invalid.
Profile RepairProfile(ProfilePoints points, ProfileKind kind, const ProfileOptions& options = {});

/// Builds a profile from coordinates in memory and repairs it like a file (RepairProfile); `name`
/// stands in for the file name in messages, and "lines" are the 1-based indices of the input
/// points. Throws InputError for different sizes, non-finite values or a failed check.
Profile MakeProfile(const std::vector<double>& y, const std::vector<double>& z, ProfileKind kind,
                    const ProfileOptions& options = {}, const std::string& name = "<memory>");

/// What the shape of a profile says about its lateral (y) orientation.
enum class LateralVerdict {
  kAsExpected,  ///< The profile runs as the conventions require (see file comment).
  kMirrored,    ///< The profile looks mirrored in y: field side and track-centre side swapped.
  kUndecided,   ///< The shape does not tell (symmetric, flangeless, too short).
};

/// The verdict with the evidence, in words for messages.
struct LateralOrientation {
  LateralVerdict verdict = LateralVerdict::kUndecided;
  std::string reason;  ///< E.g. "the flange lies at the larger-y end".
};

/// Judges the lateral orientation of points in the profile's own coordinates (z already
/// downwards, any point order). Rail profiles have their gauge face on the track-centre side,
/// at smaller y: a profile that reaches at least 10 mm below its highest point on one side of
/// it and less than a third of that on the other is judged by which side is the deep one (a
/// MiniProf measures the gauge face far down, the field side only a few mm). Wheel profiles
/// have their flange, the lowest point, on the track-centre side: the flange tip must lie in
/// the third of the profile's width at smaller y and at least 5 mm below the profile's middle.
/// Everything else (full rail sections, rollers, circles, flat or grooved profiles) is
/// undecided.
LateralOrientation JudgeLateralOrientation(const std::vector<double>& y,
                                           const std::vector<double>& z, ProfileKind kind);

/// A point or direction in the profile plane.
struct ProfileVector {
  double y = 0.0;
  double z = 0.0;
};

/// Result of ProfileSpline::ZAtY.
struct ProfileHeight {
  enum class Status {
    kInside,       ///< Exactly one point of the profile has this y.
    kMultiValued,  ///< Several points have this y (vertical or overhanging parts); z and s are
                   ///< those of the surface facing the other body: smallest z on a rail,
                   ///< largest z on a wheel.
    kOutside,      ///< No point of the profile has this y; z and s are NaN.
  };
  Status status = Status::kOutside;
  double z = 0.0;      ///< Height at y, mm (NaN when outside).
  double s = 0.0;      ///< Arc length at that point, mm (NaN when outside).
  double dz_dy = 0.0;  ///< Slope dz/dy there (1e12 where the profile is vertical; NaN outside).
  /// True unless outside.
  bool found() const { return status != Status::kOutside; }
};

namespace profile_detail {
struct SplineAccess;  // Test access to the internals (core/geometry/profile_internal.h).
}  // namespace profile_detail

/// The profile as a parametric curve (y(s), z(s)), with s the arc length in mm from the first
/// point (0 ≤ s ≤ length()). The points are split at the profile's kinks (Profile::kinks) into
/// parts; a kink point ends one part and starts the next. Each part is interpolated by two
/// cubic splines y(s), z(s) run by GSL (a part of only two points by a straight line), so the
/// curve is continuous everywhere, smooth (C2) within a part and has a corner at each kink.
/// At the profile's ends the splines are natural (zero curvature); at a kink they are
/// not-a-knot, taking the curvature up to the corner from the data. Without kinks this is one
/// pair of GSL natural cubic splines through all points. The knots s_i start as the
/// chord lengths of the polyline and are refined, part by part, until each knot interval's
/// spline arc length (5-point Gauss–Legendre) equals its parameter length: the refinement stops
/// when no knot moves by more than 1e-10 of the arc length at the part's end (at most the
/// profile length), so s is the arc length of the curve itself. A part that has not settled
/// after 50 passes, or whose knots stop increasing or become non-finite, is refused (see the
/// constructor). The curve passes through every point of the profile
/// (smoothing, if any, was applied to the points by RepairProfile). At a kink's s, the
/// derivative-based queries (TangentAt, NormalAt, InclinationAt, CurvatureAt) use the part
/// after the kink, the one with larger s. Thread-safe for concurrent const use. Copyable.
class ProfileSpline {
 public:
  /// Throws InputError for fewer than 4 points, coincident successive points ("<file>:<line>:
  /// point coincides with the previous one"), kinks that are not interior points in ascending
  /// order, and a part whose knot refinement does not settle ("<file>:<line>: no arc-length
  /// spline through the points of lines A to B ...": points that turn back sharply).
  explicit ProfileSpline(const Profile& profile);
  /// What was repaired or ignored while reading the profile (Profile::warnings), kept so that
  /// results can report it.
  const std::vector<std::string>& warnings() const;
  /// Profile::orientation_doubts of the profile.
  const std::vector<std::string>& orientation_doubts() const;
  ~ProfileSpline();
  ProfileSpline(const ProfileSpline& other);
  ProfileSpline& operator=(const ProfileSpline& other);
  ProfileSpline(ProfileSpline&& other) noexcept;
  ProfileSpline& operator=(ProfileSpline&& other) noexcept;

  ProfileKind kind() const;
  /// The source file name of the profile (for messages).
  const std::string& source() const;
  /// Total arc length, mm.
  double length() const;
  /// Arc length s_i of each profile point.
  const std::vector<double>& knots() const;
  /// Smallest and largest y over the whole curve (not only the points), mm.
  double YMin() const;
  double YMax() const;

  /// Position (y(s), z(s)). Here and in the four queries below, an s within 1e-12·length() of
  /// [0, length()] is clamped into it; one further outside (or NaN) throws std::out_of_range.
  ProfileVector PositionAt(double s) const;
  /// PositionAt for each of `s`, which must ascend: the same values, found by walking the knot
  /// intervals instead of searching them for each point (scans along the profile).
  std::vector<ProfileVector> PositionsAt(const std::vector<double>& s) const;
  /// Unit tangent in the direction of increasing s. At a kink: the tangent leaving it.
  ProfileVector TangentAt(double s) const;
  /// Unit normal pointing out of the body's material (towards the other body): upwards (−z) on a
  /// rail's running surface, downwards (+z) on a wheel's tread.
  ProfileVector NormalAt(double s) const;
  /// Surface inclination in rad, as CONTACT's: the angle from the +y axis to the surface, with
  /// the surface followed in the direction of increasing y for a rail; for a wheel the same
  /// formula applied to the reversed tangent, so both use atan(dz/dy) where single-valued.
  /// On a rail: negative on the gauge face, about 0 on top, up to +90° on the field side.
  double InclinationAt(double s) const;
  /// Signed curvature in 1/mm: positive where the body is convex (rail head, wheel tread of a
  /// circular roller), negative where concave (a groove).
  double CurvatureAt(double s) const;

  /// Every s in [0, length()] with y(s) = y, ascending, roots less than 1e-9 mm apart counted
  /// once; empty outside the profile. A table of the knot intervals by y (built once) limits the
  /// search to the intervals that can reach y.
  std::vector<double> SAtY(double y) const;
  /// z at lateral position y (see ProfileHeight for the statuses).
  ProfileHeight ZAtY(double y) const;

 private:
  friend struct profile_detail::SplineAccess;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Where the flange back of a wheel profile lies: the smallest y of the points on the
/// track-centre side of the flange tip, in the profile's coordinates (the value that
/// Wheelset::flange_back_position should have, to within the millimetre or two that a
/// measurement may leave out where the flange back meets the inner rim face). Empty for a rail
/// and for a wheel without a flange on the track-centre side (JudgeLateralOrientation of its
/// points is not kAsExpected).
std::optional<double> FlangeBackY(const ProfileSpline& wheel);

}  // namespace wrc
