#pragma once
/// @file case.h
/// One contact problem as described by a case file (docs/reference/case-files.md): one wheel on one
/// rail, or a quadratic half-space problem (docs/reference/case-files.md, half-space cases). Plain
/// data; LoadCase() / ParseCase() fill it from TOML and validate every value, so code that receives
/// a Case can rely on it.
///
/// Member defaults are the documented defaults of the keys (docs/reference/case-files.md).

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "wrc/core/material.h"
#include "wrc/core/profile.h"

namespace wrc {

/// `problem.type`.
enum class CaseType {
  kWheelRail,  ///< "wheel-rail": profiles, track and wheelset (docs/reference/case-files.md).
  kHalfspace,  ///< "halfspace": h(x,y) = a1·x² + b1·y² − approach (docs/reference/case-files.md,
               ///< half-space cases).
};

/// `wheelset.side`: which wheel of the wheelset is in contact.
enum class WheelSide { kRight, kLeft };

/// `method.reference`: the contact reference surface.
enum class ReferenceSurface {
  kCurved,  ///< "curved": the paper's curved reference surface.
  kPlanar,  ///< "planar": CONTACT's planar contact approach.
};

/// `method.position`: where the contact reference is placed.
enum class ReferencePosition {
  kInitial,   ///< "initial": the point of maximum interpenetration.
  kWeighted,  ///< "weighted": weighted centre of the interpenetration region.
};

/// `method.angle`: how the reference contact angle is chosen.
enum class ReferenceAngle {
  kSampled,   ///< "sampled": the angle at the reference position.
  kWeighted,  ///< "weighted": weighted mean over the interpenetration region.
};

/// `method.weights`: weight function for the weighted position and angle.
enum class ReferenceWeights {
  kLinear,     ///< "linear" (paper Eq. 13).
  kQuadratic,  ///< "quadratic" (paper Eq. 14).
};

/// `[rail]` or `[wheel]`: a profile file.
struct ProfileSource {
  /// Profile file. Relative paths in the file are resolved against the case file's directory,
  /// so this path is ready to open (absolute when the base directory was absolute).
  std::filesystem::path path;
  /// As written in the case file, for messages and for storing the profile under its name.
  std::string path_as_written;
  bool mirror_y = false;  ///< Mirror the profile in y before use.
  /// `mirror_y = "auto"`: decide mirror_y from the profile's shape (mirror_y is then unused).
  bool mirror_y_auto = false;
  /// `mirror_z`: true, false or "auto" (the default: decided from the side faces).
  MirrorZ mirror_z = MirrorZ::kAuto;
  /// Whether mirror_y or mirror_z was written as "auto", so that the decision is reported.
  bool report_orientation = false;
  /// `smooth`: smoothing wavelength in mm (ProfileOptions::smoothing); 0 = none.
  double smooth = 0.0;
  /// `scale_yz`: factor from the file's length unit to mm (1000 for metres).
  double scale_yz = 1.0;
  /// The profile as LoadCase / LoadScene read it (mirrored when asked), shared by every solve of
  /// the case or scene so that it is read and splined once; null when not read (a Case built
  /// in code), and the solver then reads `path` itself.
  std::shared_ptr<const ProfileSpline> spline;
};

/// The reading options that a `[rail]` or `[wheel]` section asks for.
ProfileOptions ProfileOptionsOf(const ProfileSource& source);

/// The source's spline: the one LoadCase / LoadScene read, or else the file read now with the
/// section's options. Throws InputError for a profile that cannot be read.
std::shared_ptr<const ProfileSpline> SplineOf(const ProfileSource& source, ProfileKind kind);

/// `[track]`: placement of the rail.
struct Track {
  /// mm below the track plane where the gauge is measured; <= 0 selects the absolute
  /// placement by rail_y / rail_z.
  double gauge_height = 14.0;
  double gauge_width = 1435.0;  ///< mm, used when gauge_height > 0.
  double cant = 0.025;          ///< rad.
  double rail_y = 0.0;          ///< mm, rail origin, used when gauge_height <= 0.
  double rail_z = 0.0;          ///< mm, rail origin, used when gauge_height <= 0.

  /// True when the rail is placed by rail_y / rail_z instead of by gauge.
  bool absolute_placement() const { return gauge_height <= 0.0; }
};

/// `[wheelset]`: geometry of the wheelset.
struct Wheelset {
  WheelSide side = WheelSide::kRight;
  double flange_back_distance = 1360.0;  ///< mm.
  double flange_back_position = -70.0;   ///< mm, w.r.t. the wheel profile origin.
  double nominal_radius = 460.0;         ///< mm, > 0.
};

/// `[friction]`: Coulomb friction, constant or varying with the surface inclination alpha:
/// linear in between the given angles, constant outside them.
struct Friction {
  /// Inclination angles in degrees, strictly ascending. Empty for constant friction.
  std::vector<double> alpha_deg;
  /// Friction coefficients, >= 0: one value for constant friction, else one per alpha_deg.
  std::vector<double> mu{0.3};

  bool is_constant() const { return alpha_deg.empty(); }
  /// Constant friction mu.
  static Friction Constant(double mu) { return Friction{{}, {mu}}; }
  /// The coefficient at inclination alpha (radians), interpolated as described above.
  double MuAt(double alpha_rad) const;
};

/// Closed interval [min, max] with min < max.
struct Interval {
  double min = 0.0;
  double max = 0.0;
};

/// `[grid]`: element sizes and, for half-space problems, the potential contact area.
struct GridSettings {
  double dx = 0.2;  ///< mm, rolling direction.
  double ds = 0.2;  ///< mm, along the (curved) lateral direction; wheel-rail only.
  double dy = 0.2;  ///< mm, lateral; half-space only.
  /// Half-space only: the rectangle covered by cells (docs/reference/case-files.md, half-space
  /// cases); when absent, the solver chooses it around the Hertz ellipse.
  std::optional<Interval> x;
  std::optional<Interval> y;
};

/// `[method]`: the contact reference and the combination of interpenetration regions.
struct Method {
  ReferenceSurface reference = ReferenceSurface::kCurved;
  ReferencePosition position = ReferencePosition::kWeighted;
  ReferenceAngle angle = ReferenceAngle::kWeighted;
  ReferenceWeights weights = ReferenceWeights::kQuadratic;
  double combine_distance = 6.0;  ///< mm, >= 0.
};

/// `[effects]`: what is computed.
struct Effects {
  bool tangential = true;           ///< false: frictionless, normal problem only.
  bool midplane_correction = true;  ///< Eq. 20, curved reference only.
};

/// `[geometry]` of a half-space problem: h(x,y) = a1·x² + b1·y² − approach.
struct HalfspaceGeometry {
  double a1 = 0.0;  ///< 1/mm, > 0.
  double b1 = 0.0;  ///< 1/mm, > 0.
};

/// `[state]` of a wheel-rail problem. Exactly one of z and fz holds a value. In a file, velocity
/// must be given; its member value (and the omega of free rolling on a 460 mm wheel that goes
/// with it) only serves cases built in code.
struct WheelsetState {
  double y = 0.0;             ///< mm, lateral wheelset position.
  std::optional<double> z;    ///< mm, prescribed vertical position (z = 0 nominal).
  std::optional<double> fz;   ///< N, prescribed vertical force on the rail, > 0.
  double roll = 0.0;          ///< rad.
  double yaw = 0.0;           ///< rad.
  double velocity = 2000.0;   ///< mm/s, forward.
  double omega = -4.3481124;  ///< rad/s, pitch velocity (negative for forward rolling).
  /// -, rotation relative to free rolling, when given instead of omega (0 when neither is
  /// given); omega holds its value.
  std::optional<double> spin;
  double vy = 0.0;     ///< mm/s.
  double vroll = 0.0;  ///< rad/s.
  double vyaw = 0.0;   ///< rad/s.

  /// True when fz is prescribed and z is solved for.
  bool force_prescribed() const { return fz.has_value(); }
};

/// `[state]` of a half-space problem. Exactly one of fn and approach holds a value.
struct HalfspaceState {
  std::optional<double> fn;        ///< N, prescribed normal force, > 0.
  std::optional<double> approach;  ///< mm, prescribed approach.
  double cksi = 0.001;             ///< -, longitudinal creepage.
  double ceta = 0.0;               ///< -, lateral creepage.
  double cphi = 0.0;               ///< 1/mm, spin creepage.

  /// True when fn is prescribed and the approach is solved for.
  bool force_prescribed() const { return fn.has_value(); }
};

/// A whole case. Sections that do not belong to the case's type keep their defaults.
struct Case {
  CaseType type = CaseType::kWheelRail;

  // Wheel-rail problems.
  ProfileSource rail;
  ProfileSource wheel;
  Track track;
  Wheelset wheelset;
  WheelsetState state;

  // Half-space problems.
  HalfspaceGeometry geometry;
  HalfspaceState halfspace_state;

  // Both.
  ElasticMaterial rail_material;   ///< Body 1.
  ElasticMaterial wheel_material;  ///< Body 2.
  Friction friction;
  GridSettings grid;
  Method method;
  Effects effects;

  std::string source_name;         ///< File name used in messages.
  std::filesystem::path base_dir;  ///< Directory that relative paths are resolved against.
  std::string source_text;         ///< The original TOML text (tables store it verbatim).
};

/// Pitch velocity for a spin value (docs/reference/case-files.md, scenes): omega = −(velocity /
/// nominal_radius)·(1 + spin). spin is the rotation relative to free rolling at the nominal radius;
/// 0.01 turns the wheel 1 % faster than free rolling.
inline double OmegaFromSpin(double spin, double velocity, double nominal_radius) {
  return -(velocity / nominal_radius) * (1.0 + spin);
}

/// Reads and validates a case file. Also checks that the profile files exist and read as
/// profiles (ReadProfile with the section's ProfileOptionsOf, then ProfileSpline), so that a
/// broken profile is reported with the key that names it. Throws InputError with a message
/// "file:line: key = value: problem", for a profile "case.toml:4: rail.profile = "rail.csv":
/// /.../rail.csv:5: <problem>".
Case LoadCase(const std::filesystem::path& path);

/// Parses and validates case text. `base_dir` resolves relative profile paths (the files need
/// not exist: a table carries its profiles along); `display_name` names the source in
/// messages. Throws InputError.
Case ParseCase(std::string_view toml_text, const std::filesystem::path& base_dir,
               std::string_view display_name);

}  // namespace wrc
