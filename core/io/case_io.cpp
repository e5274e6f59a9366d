// Case files (docs/reference/case-files.md): TOML to wrc::Case, with every name, type and value
// checked so that a typo or an impossible value is reported with file, line and key instead of
// being ignored.

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>
#include <tuple>

#include "core/io/case_parser.h"
#include "wrc/core/case.h"
#include "wrc/core/errors.h"
#include "wrc/core/grid.h"
#include "wrc/core/profile.h"
#include "wrc/table_limits.h"

namespace wrc {
namespace io {
namespace {

/// Which problem types a section or key belongs to.
enum class Applies { kBoth, kWheelRail, kHalfspace };

struct KeySchema {
  std::string_view key;
  Applies applies;
};

struct SectionSchema {
  std::string_view name;
  Applies applies;
  std::vector<KeySchema> keys;
};

/// Every section and key of a case file (docs/reference/case-files.md). Anything else in a
/// file is a mistake.
const std::vector<SectionSchema>& CaseSchema() {
  constexpr Applies kBoth = Applies::kBoth;
  constexpr Applies kWR = Applies::kWheelRail;
  constexpr Applies kHS = Applies::kHalfspace;
  // [rail] and [wheel] take the same keys.
  const std::vector<KeySchema> profile_keys = {
      {"profile", kWR}, {"mirror_y", kWR}, {"mirror_z", kWR}, {"smooth", kWR}, {"scale_yz", kWR}};
  static const std::vector<SectionSchema> schema = {
      {"problem", kBoth, {{"type", kBoth}}},
      {"rail", kWR, profile_keys},
      {"wheel", kWR, profile_keys},
      {"track",
       kWR,
       {{"gauge_height", kWR},
        {"gauge_width", kWR},
        {"cant", kWR},
        {"rail_y", kWR},
        {"rail_z", kWR}}},
      {"wheelset",
       kWR,
       {{"side", kWR},
        {"flange_back_distance", kWR},
        {"flange_back_position", kWR},
        {"nominal_radius", kWR}}},
      {"material", kBoth, {{"poisson", kBoth}, {"shear_modulus", kBoth}, {"shear_yield", kWR}}},
      {"friction", kBoth, {{"mu", kBoth}, {"alpha_deg", kBoth}}},
      {"grid", kBoth, {{"dx", kBoth}, {"ds", kWR}, {"dy", kHS}, {"x", kHS}, {"y", kHS}}},
      {"method",
       kWR,
       {{"reference", kWR},
        {"position", kWR},
        {"angle", kWR},
        {"weights", kWR},
        {"combine_distance", kWR}}},
      {"effects", kBoth, {{"tangential", kBoth}, {"midplane_correction", kWR}}},
      {"geometry", kHS, {{"a1", kHS}, {"b1", kHS}}},
      {"state",
       kBoth,
       {{"y", kWR},
        {"z", kWR},
        {"fz", kWR},
        {"roll", kWR},
        {"yaw", kWR},
        {"velocity", kWR},
        {"omega", kWR},
        {"spin", kWR},
        {"vy", kWR},
        {"vroll", kWR},
        {"vyaw", kWR},
        {"fn", kHS},
        {"approach", kHS},
        {"cksi", kHS},
        {"ceta", kHS},
        {"cphi", kHS}}},
  };
  return schema;
}

bool AppliesTo(Applies applies, CaseType type) {
  return applies == Applies::kBoth ||
         (applies == Applies::kWheelRail) == (type == CaseType::kWheelRail);
}

std::string TypeName(CaseType type) {
  return type == CaseType::kWheelRail ? "wheel-rail" : "halfspace";
}

std::string NotUsedBy(CaseType type) {
  return "not used by problem.type = \"" + TypeName(type) + "\"";
}

std::string JoinNames(const std::vector<std::string_view>& names) {
  std::string joined;
  for (std::string_view name : names) {
    if (!joined.empty()) joined += ", ";
    joined += name;
  }
  return joined;
}

/// Rejects unknown sections and keys, and those of the other problem type, before anything is
/// read: a misspelt key would otherwise silently fall back to its default.
void CheckNames(const toml::table& root, const SourceFile& file, CaseType type,
                bool allow_table_section) {
  std::vector<std::string_view> section_names;
  for (const SectionSchema& section : CaseSchema()) {
    if (AppliesTo(section.applies, type)) section_names.push_back(section.name);
  }
  if (allow_table_section) section_names.push_back("table");

  for (const auto& [key, node] : root) {
    const std::string_view name = key.str();
    if (name == "table") {
      if (allow_table_section) continue;
      file.FailAt(node.source().begin, "[table]",
                  "only scene files (wrc generate) have a [table] section, not case files");
    }
    const auto schema = std::find_if(CaseSchema().begin(), CaseSchema().end(),
                                     [name](const SectionSchema& s) { return s.name == name; });
    if (schema == CaseSchema().end()) {
      if (!node.is_table()) {
        // A key outside any section: say which section it belongs in, if any.
        for (const SectionSchema& section : CaseSchema()) {
          for (const KeySchema& known : section.keys) {
            if (known.key == name && AppliesTo(known.applies, type)) {
              file.Fail(
                  &node, name,
                  "keys belong in a section: put it under [" + std::string(section.name) + "]");
            }
          }
        }
        file.Fail(&node, name, "unknown key outside any section");
      }
      const std::string suggestion = SuggestName(name, section_names);
      std::string problem = "unknown section";
      if (!suggestion.empty()) problem += " (did you mean [" + suggestion + "]?)";
      problem += "; allowed sections: " + JoinNames(section_names);
      file.FailAt(node.source().begin, "[" + std::string(name) + "]", problem);
    }
    if (!AppliesTo(schema->applies, type)) {
      file.FailAt(node.source().begin, "[" + std::string(name) + "]", NotUsedBy(type));
    }
    const toml::table* section = node.as_table();
    if (section == nullptr) {
      file.Fail(&node, name, "must be a section [" + std::string(name) + "]");
    }

    std::vector<std::string_view> key_names;
    for (const KeySchema& known : schema->keys) {
      if (AppliesTo(known.applies, type)) key_names.push_back(known.key);
    }
    for (const auto& [inner_key, inner_node] : *section) {
      const std::string_view inner_name = inner_key.str();
      const std::string path = std::string(name) + "." + std::string(inner_name);
      const auto known =
          std::find_if(schema->keys.begin(), schema->keys.end(),
                       [inner_name](const KeySchema& k) { return k.key == inner_name; });
      if (known == schema->keys.end()) {
        const std::string suggestion = SuggestName(inner_name, key_names);
        std::string problem = "unknown key";
        if (!suggestion.empty()) {
          problem += " (did you mean " + std::string(name) + "." + suggestion + "?)";
        }
        problem += "; allowed keys in [" + std::string(name) + "]: " + JoinNames(key_names);
        file.Fail(&inner_node, path, problem);
      }
      if (!AppliesTo(known->applies, type)) {
        std::string problem = NotUsedBy(type);
        if (name == "grid" && inner_name == "ds") problem += " (half-space grids use grid.dy)";
        if (name == "grid" && inner_name == "dy") problem += " (wheel-rail grids use grid.ds)";
        file.Fail(&inner_node, path, problem);
      }
    }
  }
}

// Small checks that report the offending key with its value.
void RequirePositive(const Section& section, std::string_view key, double value) {
  if (!(value > 0.0)) section.Fail(key, "must be positive");
}
void RequireNonNegative(const Section& section, std::string_view key, double value) {
  if (value < 0.0) section.Fail(key, "must not be negative");
}
// |value| <= limit; `why` says where the limit comes from, in the user's terms.
void RequireMagnitudeAtMost(const Section& section, std::string_view key, double value,
                            double limit, const std::string& why) {
  if (!(std::fabs(value) <= limit)) {
    section.Fail(key, "must be within ±" + FormatNumber(limit) + " (" + why + ")");
  }
}

// Plausible ranges of the inputs. Each is far outside any real wheel–rail or test contact, so
// only a mistake (a unit slip, a typo in an exponent) reaches it, and the message then names
// the key rather than letting the solver fail somewhere else or return absurd numbers.
// Element sizes: 0.1 µm to 100 mm. Finer cannot be meant for contact mechanics; coarser than
// 100 mm is wider than any contact patch (a wheel–rail patch is at most ~40 mm long).
constexpr double kMinElementSize = 1e-4;
constexpr double kMaxElementSize = 100.0;
// Creepages and spin (relative slip): 1, i.e. 100 % of the rolling speed.
constexpr double kMaxCreepage = 1.0;
// Spin creepage of the half-space case, 1/mm: 1, a full turn of slip direction per ~6 mm.
constexpr double kMaxSpinCreepage = 1.0;
// Friction coefficient: 0 (frictionless) or 1e-6 to 10. Dry steel is about 0.6; a positive
// value below 1e-6 makes traction bounds that vanish against round-off.
constexpr double kMinFriction = 1e-6;
constexpr double kMaxFriction = 10.0;
// Prescribed forces: at least 1e-6 N; below that the patch is far smaller than any element.
constexpr double kMinForce = 1e-6;
// Track and wheelset dimensions, mm: gauges and flange-back distances from 300 mm (the
// smallest ride-on railways) to 3000 mm (twice the broadest gauge), wheel radii from 10 mm
// (scaled test rigs) to 2000 mm (four times a locomotive's).
constexpr double kMinTrackDimension = 300.0, kMaxTrackDimension = 3000.0;
constexpr double kMinWheelRadius = 10.0, kMaxWheelRadius = 2000.0;
// The wheelset's vertical position, mm: contact happens within a few mm of the first touch;
// 1000 mm is farther than any profile is tall.
constexpr double kMaxVerticalPosition = 1000.0;
// The lever that turns the yaw rate into longitudinal creepage: half a wide gauge, mm.
constexpr double kYawRateLever = 1000.0;

// lo <= value <= hi; `why` says in the user's terms what is meant.
void RequireWithin(const Section& section, std::string_view key, double value, double lo, double hi,
                   const std::string& why) {
  if (!(value >= lo && value <= hi)) {
    section.Fail(
        key, "must be between " + FormatNumber(lo) + " and " + FormatNumber(hi) + " (" + why + ")");
  }
}

void RequireElementSize(const Section& section, std::string_view key, double value) {
  RequirePositive(section, key, value);
  if (value < kMinElementSize || value > kMaxElementSize) {
    section.Fail(key, "must be between " + FormatNumber(kMinElementSize) + " and " +
                          FormatNumber(kMaxElementSize) + " mm (the size of one element)");
  }
}
void RequireFriction(const Section& section, std::string_view key, double mu) {
  RequireNonNegative(section, key, mu);
  if (mu != 0.0 && (mu < kMinFriction || mu > kMaxFriction)) {
    section.Fail(key, "must be 0 or between " + FormatNumber(kMinFriction) + " and " +
                          FormatNumber(kMaxFriction));
  }
}
void RequireForce(const Section& section, std::string_view key, double force) {
  RequirePositive(section, key, force);
  if (force < kMinForce) section.Fail(key, "must be at least " + FormatNumber(kMinForce) + " N");
}

// Smoothing wavelengths beyond the longest profile accepted (500 mm) would flatten it whole.
constexpr double kMaxSmoothingWavelength = 500.0;

/// `true`, `false` or "auto" (nullopt).
std::optional<bool> ReadMirror(const Section& section, std::string_view key, bool fallback) {
  const toml::node* node = section.Find(key);
  if (node == nullptr) return fallback;
  if (const auto* text = node->as_string(); text != nullptr && text->get() == "auto") {
    return std::nullopt;
  }
  if (node->as_boolean() == nullptr) section.Fail(key, "must be true, false or \"auto\"");
  return node->as_boolean()->get();
}

/// mirror_y, mirror_z, smooth and scale_yz of a [rail] or [wheel] section.
void ReadProfileOptions(const Section& section, ProfileSource& profile) {
  const std::optional<bool> mirror_y = ReadMirror(section, "mirror_y", false);
  profile.mirror_y = mirror_y.value_or(false);
  profile.mirror_y_auto = !mirror_y;
  // Without the key z is decided automatically, silently, as it always was; written as "auto",
  // the decision is reported.
  const std::optional<bool> mirror_z = ReadMirror(section, "mirror_z", false);
  const bool z_written = section.Has("mirror_z");
  profile.mirror_z = !z_written || !mirror_z ? MirrorZ::kAuto
                     : *mirror_z             ? MirrorZ::kYes
                                             : MirrorZ::kNo;
  profile.report_orientation = !mirror_y || (z_written && !mirror_z);
  profile.smooth = section.Number("smooth", profile.smooth);
  RequireNonNegative(section, "smooth", profile.smooth);
  if (profile.smooth > kMaxSmoothingWavelength) {
    section.Fail("smooth", "must be at most " + FormatNumber(kMaxSmoothingWavelength) +
                               " mm (a wavelength along the profile; 0 = no smoothing)");
  }
  profile.scale_yz = section.Number("scale_yz", profile.scale_yz);
  RequirePositive(section, "scale_yz", profile.scale_yz);
}

/// Reads the profile file as the wheel-rail solver does (wrc::ReadProfile with the section's
/// options, then the arc-length spline), so that a broken profile is
/// reported with the key that names it, before any solve:
/// `case.toml:4: rail.profile = "rail.csv": /.../rail.csv:5: 'five' is not a number ...`.
/// Costs about 1-2 ms per profile.
void CheckProfileContents(const Section& section, ProfileSource& profile, ProfileKind kind) {
  try {
    profile.spline = std::make_shared<const ProfileSpline>(
        wrc::ReadProfile(profile.path.string(), kind, ProfileOptionsOf(profile)));
  } catch (const InputError& error) {
    section.Fail("profile", error.what());
  }
}

ProfileSource ReadProfileSource(const Section& section, ProfileKind kind,
                                const std::filesystem::path& base_dir, bool check_file) {
  ProfileSource profile;
  const std::optional<std::string> written = section.OptionalString("profile");
  if (!written) {
    section.FailMissing("profile",
                        "wheel-rail problems need the " + section.name() + " profile file");
  }
  if (written->empty()) section.Fail("profile", "must name a profile file");
  profile.path_as_written = *written;
  const std::filesystem::path as_given(*written);
  profile.path = as_given.is_absolute() ? as_given : (base_dir / as_given).lexically_normal();
  ReadProfileOptions(section, profile);
  if (check_file) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(profile.path, error)) {
      const bool exists = std::filesystem::exists(profile.path, error);
      section.Fail("profile", (exists ? "not a regular file (a directory, device or FIFO): "
                                      : "file not found: ") +
                                  profile.path.string());
    }
    CheckProfileContents(section, profile, kind);
  }
  return profile;
}

Track ReadTrack(const Section& section) {
  Track track;
  track.gauge_height = section.Number("gauge_height", track.gauge_height);
  track.cant = section.Number("cant", track.cant);
  // The rail's inclination: 1:20 to 1:40 (0.05 to 0.025 rad) on real track, 0 on test rigs.
  // Beyond 0.2 rad the rail leans so far that the wheel meets the side of its head; 1e10 rad
  // (a unit slip) used to be taken modulo a turn and solved as ok.
  RequireMagnitudeAtMost(section, "cant", track.cant, 0.2, "rad, rail inclination; 1:40 is 0.025");
  if (track.absolute_placement()) {
    // gauge_width would be silently ignored: say so rather than surprise the user.
    if (section.Has("gauge_width")) {
      section.Fail("gauge_width",
                   "not used with absolute placement (track.gauge_height <= 0); the rail is "
                   "placed by track.rail_y and track.rail_z");
    }
    track.rail_y = section.Number("rail_y", track.rail_y);
    track.rail_z = section.Number("rail_z", track.rail_z);
  } else {
    for (std::string_view key : {"rail_y", "rail_z"}) {
      if (section.Has(key)) {
        section.Fail(key,
                     "only used with absolute placement (track.gauge_height <= 0); with "
                     "gauge_height > 0 the rail is placed by gauge_width and cant");
      }
    }
    track.gauge_width = section.Number("gauge_width", track.gauge_width);
    RequireWithin(section, "gauge_width", track.gauge_width, kMinTrackDimension, kMaxTrackDimension,
                  "mm; standard gauge is 1435");
  }
  return track;
}

// With absolute placement the wheel sits in the profiles' own coordinates and the flange-back
// distance may be anything, 0 included; placed by gauge it sets where the wheel is.
Wheelset ReadWheelset(const Section& section, const Track& track) {
  Wheelset wheelset;
  wheelset.side = section.Choice("side", {{"right", WheelSide::kRight}, {"left", WheelSide::kLeft}},
                                 wheelset.side);
  wheelset.flange_back_distance =
      section.Number("flange_back_distance", wheelset.flange_back_distance);
  wheelset.flange_back_position =
      section.Number("flange_back_position", wheelset.flange_back_position);
  if (track.absolute_placement()) {
    RequireMagnitudeAtMost(section, "flange_back_distance", wheelset.flange_back_distance,
                           kMaxTrackDimension, "mm");
  } else {
    RequireWithin(section, "flange_back_distance", wheelset.flange_back_distance,
                  kMinTrackDimension, kMaxTrackDimension, "mm; 1360 on standard gauge");
  }
  wheelset.nominal_radius = section.Number("nominal_radius", wheelset.nominal_radius);
  RequireWithin(section, "nominal_radius", wheelset.nominal_radius, kMinWheelRadius,
                kMaxWheelRadius, "mm; 460 for a 920 mm wheel");
  return wheelset;
}

/// `key = value` for both bodies or `key = [rail, wheel]`.
std::vector<NumberAt> ReadPerBody(const Section& section, std::string_view key) {
  std::vector<NumberAt> values = section.NumberOrArray(key);
  if (values.empty()) return values;
  if (!section.Find(key)->is_array()) return {values[0], values[0]};
  if (values.size() != 2) {
    section.Fail(key, "must be one number for both bodies or an array [rail, wheel]");
  }
  return values;
}

void ReadMaterials(const Section& section, Case& result) {
  const std::vector<NumberAt> poisson = ReadPerBody(section, "poisson");
  for (const NumberAt& value : poisson) {
    if (value.value < 0.0 || value.value >= 0.5) {
      section.file().Fail(value.node, value.path, "must be in [0, 0.5)");
    }
  }
  const std::vector<NumberAt> modulus = ReadPerBody(section, "shear_modulus");
  // Shear moduli from soft polymers (~1 N/mm²) to diamond (~5e5 N/mm²) lie well inside; outside,
  // the elastic displacements under any load overflow or vanish against the geometry, and the
  // solver used to fail on a profile's arc length instead of naming this key.
  constexpr double kMinShearModulus = 1e-2, kMaxShearModulus = 1e7;
  for (const NumberAt& value : modulus) {
    if (!(value.value >= kMinShearModulus && value.value <= kMaxShearModulus)) {
      section.file().Fail(value.node, value.path,
                          "must be between 0.01 and 1e+07 N/mm² (steel: 82000)");
    }
  }
  // Body 1 is the rail, body 2 the wheel.
  if (!poisson.empty()) {
    result.rail_material.poisson = poisson[0].value;
    result.wheel_material.poisson = poisson[1].value;
  }
  // Rail and wheel steels yield in shear at 200–600 N/mm²; the bounds only keep out other units.
  const std::vector<NumberAt> yield = ReadPerBody(section, "shear_yield");
  for (const NumberAt& value : yield) {
    if (!(value.value >= 1.0 && value.value <= 1e4)) {
      section.file().Fail(value.node, value.path,
                          "must be between 1 and 10000 N/mm² (the yield limit in pure shear)");
    }
  }
  if (!yield.empty()) {
    result.rail_material.shear_yield = yield[0].value;
    result.wheel_material.shear_yield = yield[1].value;
  }
  if (!modulus.empty()) {
    result.rail_material.shear_modulus = modulus[0].value;
    result.wheel_material.shear_modulus = modulus[1].value;
  }
}

Friction ReadFriction(const Section& section) {
  Friction friction;
  const toml::node* mu_node = section.Find("mu");
  const bool varying = section.Has("alpha_deg");
  if (mu_node == nullptr) {
    if (varying) section.FailMissing("mu", "friction.alpha_deg needs an array mu of equal length");
    return friction;
  }
  if (!varying) {
    if (mu_node->is_array()) {
      section.Fail("mu",
                   "an array of mu needs friction.alpha_deg (one angle per value); for "
                   "constant friction give one number");
    }
    const double mu = ReadNumber(section.file(), *mu_node, section.Path("mu"));
    RequireFriction(section, "mu", mu);
    return Friction::Constant(mu);
  }
  if (!mu_node->is_array()) {
    section.Fail("mu", "must be an array with one value per friction.alpha_deg");
  }
  const std::vector<NumberAt> alpha = section.NumberArray("alpha_deg");
  const std::vector<NumberAt> mu = section.NumberArray("mu");
  if (alpha.size() != mu.size()) {
    section.Fail("mu", "has " + std::to_string(mu.size()) + " values but friction.alpha_deg has " +
                           std::to_string(alpha.size()) + "; they must have the same length");
  }
  // A contact angle: within ±90° (the angle of the contact normal from the vertical).
  for (const NumberAt& a : alpha) {
    if (!(std::fabs(a.value) <= 90.0)) {
      section.file().Fail(a.node, a.path,
                          "must lie within ±90 (degrees: the contact angle at which mu applies)");
    }
  }
  for (std::size_t i = 1; i < alpha.size(); ++i) {
    if (!(alpha[i].value > alpha[i - 1].value)) {
      section.file().Fail(alpha[i].node, alpha[i].path,
                          "friction.alpha_deg must be strictly ascending (previous value " +
                              DescribeValue(*alpha[i - 1].node) + ")");
    }
  }
  friction.alpha_deg.clear();
  friction.mu.clear();
  for (std::size_t i = 0; i < mu.size(); ++i) {
    if (mu[i].value < 0.0) section.file().Fail(mu[i].node, mu[i].path, "must not be negative");
    if (mu[i].value != 0.0 && (mu[i].value < kMinFriction || mu[i].value > kMaxFriction)) {
      section.file().Fail(mu[i].node, mu[i].path,
                          "must be 0 or between " + FormatNumber(kMinFriction) + " and " +
                              FormatNumber(kMaxFriction));
    }
    friction.alpha_deg.push_back(alpha[i].value);
    friction.mu.push_back(mu[i].value);
  }
  return friction;
}

Interval ReadInterval(const Section& section, std::string_view key) {
  const std::vector<NumberAt> bounds = section.NumberArray(key);
  if (bounds.size() != 2) section.Fail(key, "must be an array [min, max]");
  if (!(bounds[0].value < bounds[1].value)) section.Fail(key, "min must be less than max");
  return Interval{bounds[0].value, bounds[1].value};
}

// The elements an explicit range holds, counted in floating point (no integer to wrap), at
// most Grid::kMaxElementsAlong.
void RequireElementCount(const Section& section, std::string_view key,
                         const std::optional<Interval>& range, double step,
                         std::string_view step_key) {
  if (!range) return;
  const double count = std::round((range->max - range->min) / step);
  if (!(count <= Grid::kMaxElementsAlong)) {
    section.Fail(key, "holds " + FormatNumber(count) + " elements of grid." +
                          std::string(step_key) + " = " + FormatNumber(step) + " mm, more than " +
                          std::to_string(Grid::kMaxElementsAlong));
  }
}

GridSettings ReadGrid(const Section& section, CaseType type) {
  GridSettings grid;
  const std::string why = "the grid must be given for " + TypeName(type) + " problems";
  grid.dx = section.RequiredNumber("dx", why);
  RequireElementSize(section, "dx", grid.dx);
  if (type == CaseType::kWheelRail) {
    grid.ds = section.RequiredNumber("ds", why);
    RequireElementSize(section, "ds", grid.ds);
  } else {
    grid.dy = section.RequiredNumber("dy", why);
    RequireElementSize(section, "dy", grid.dy);
    if (section.Has("x")) grid.x = ReadInterval(section, "x");
    if (section.Has("y")) grid.y = ReadInterval(section, "y");
    RequireElementCount(section, "x", grid.x, grid.dx, "dx");
    RequireElementCount(section, "y", grid.y, grid.dy, "dy");
  }
  return grid;
}

Method ReadMethod(const Section& section) {
  Method method;
  method.reference = section.Choice(
      "reference", {{"curved", ReferenceSurface::kCurved}, {"planar", ReferenceSurface::kPlanar}},
      method.reference);
  method.position = section.Choice(
      "position",
      {{"initial", ReferencePosition::kInitial}, {"weighted", ReferencePosition::kWeighted}},
      method.position);
  method.angle = section.Choice(
      "angle", {{"sampled", ReferenceAngle::kSampled}, {"weighted", ReferenceAngle::kWeighted}},
      method.angle);
  method.weights = section.Choice(
      "weights",
      {{"linear", ReferenceWeights::kLinear}, {"quadratic", ReferenceWeights::kQuadratic}},
      method.weights);
  method.combine_distance = section.Number("combine_distance", method.combine_distance);
  RequireNonNegative(section, "combine_distance", method.combine_distance);
  return method;
}

Effects ReadEffects(const Section& section) {
  Effects effects;
  effects.tangential = section.Bool("tangential", effects.tangential);
  effects.midplane_correction = section.Bool("midplane_correction", effects.midplane_correction);
  return effects;
}

HalfspaceGeometry ReadGeometry(const Section& section) {
  HalfspaceGeometry geometry;
  const char* why = "half-space problems need [geometry] a1 and b1";
  geometry.a1 = section.RequiredNumber("a1", why);
  RequirePositive(section, "a1", geometry.a1);
  geometry.b1 = section.RequiredNumber("b1", why);
  RequirePositive(section, "b1", geometry.b1);
  return geometry;
}

}  // namespace

// One set of range checks for the wheelset's state, wherever it comes from (a case file, the
// axes of a scene): each bound is far outside any real wheel-rail contact, so only a mistake (a
// unit slip, a typo in an exponent) reaches it, and the message names the key.
void CheckWheelsetState(const WheelsetState& state, const Wheelset& wheelset, bool omega_given,
                        const StateRangeFailure& fail) {
  const auto magnitude_at_most = [&fail](std::string_view key, double value, double limit,
                                         const std::string& why) {
    if (!(std::fabs(value) <= limit)) {
      fail(key, "must be within ±" + FormatNumber(limit) + " (" + why + ")");
    }
  };
  if (state.z) {
    magnitude_at_most("z", *state.z, kMaxVerticalPosition,
                      "mm, the wheelset's vertical position; contact is within a few mm");
  }
  magnitude_at_most("velocity", state.velocity, WRC_VELOCITY_MAX, "mm/s, i.e. 1 km/s");
  if (state.velocity != 0.0 && !(std::fabs(state.velocity) >= WRC_VELOCITY_MIN)) {
    fail("velocity", "must be 0 or at least " + FormatNumber(WRC_VELOCITY_MIN) +
                         " mm/s in magnitude (1 µm/s; slower is standing still)");
  }
  // The creepages the lateral, roll and yaw rates add (vy/V, vroll·r0/V, vyaw·lever/V) stay
  // within 100 % slip, as spin does; at rest (V = 0) any rate would be infinite slip.
  const double speed = std::fabs(state.velocity);
  const std::tuple<std::string_view, double, double, const char*> rates[] = {
      {"vy", state.vy, 1.0, "mm/s; vy / velocity is a lateral creepage"},
      {"vroll", state.vroll, wheelset.nominal_radius,
       "rad/s; vroll·nominal_radius / velocity is a lateral creepage"},
      {"vyaw", state.vyaw, kYawRateLever,
       "rad/s; vyaw·1000 mm / velocity is a longitudinal creepage"}};
  for (const auto& [key, rate, lever, why] : rates) {
    if (rate != 0.0) magnitude_at_most(key, rate, kMaxCreepage * speed / lever, why);
  }
  if (omega_given) {
    const double free_rolling = OmegaFromSpin(0.0, state.velocity, wheelset.nominal_radius);
    if (state.velocity != 0.0 && !(std::fabs(state.omega / free_rolling - 1.0) <= kMaxCreepage)) {
      fail("omega", "must lie within 100 % of free rolling, -velocity / nominal_radius = " +
                        FormatNumber(free_rolling) + " rad/s (omega is in rad/s)");
    }
  }
  if (state.spin) {
    magnitude_at_most("spin", *state.spin, kMaxCreepage, "a relative creepage; 1 is 100 % slip");
    // Finite inputs of absurd size (velocity 1e300 on a 1e-300 mm wheel) overflow.
    if (!std::isfinite(state.omega)) {
      fail("spin",
           "gives a non-finite omega = -(state.velocity / wheelset.nominal_radius)·(1 + spin)");
    }
  }
}

namespace {

WheelsetState ReadWheelsetState(const Section& section, const Wheelset& wheelset,
                                const CaseParseOptions& options) {
  // What [state] leaves out is 0 (free rolling: spin = 0); the velocity must be given.
  WheelsetState state;
  state.y = section.Number("y", state.y);
  state.z = section.OptionalNumber("z");
  state.fz = section.OptionalNumber("fz");
  if (state.z && state.fz) section.Fail("fz", "give either state.z or state.fz, not both");
  const bool vertical_on_axis = options.axis_names.count("z") + options.axis_names.count("fz") > 0;
  if (!state.z && !state.fz && !vertical_on_axis) {
    section.file().FailAt(section.position(), "state.z",
                          "missing: give the vertical position state.z (mm) or the vertical "
                          "force state.fz (N)");
  }
  if (state.fz) RequireForce(section, "fz", *state.fz);
  state.roll = section.Number("roll", state.roll);
  state.yaw = section.Number("yaw", state.yaw);
  // The speed sets the creepages and omega; no value is a sensible guess for every user.
  state.velocity = section.RequiredNumber("velocity", "the forward velocity of the wheelset, mm/s");
  state.vy = section.Number("vy", state.vy);
  state.vroll = section.Number("vroll", state.vroll);
  state.vyaw = section.Number("vyaw", state.vyaw);

  const std::optional<double> omega = section.OptionalNumber("omega");
  state.spin = section.OptionalNumber("spin");
  if (omega && state.spin) section.Fail("spin", "give either state.omega or state.spin, not both");
  const bool rotation_on_axis =
      options.axis_names.count("spin") + options.axis_names.count("omega") > 0;
  // Without omega or spin (and no axis for them) the wheelset rolls freely: spin = 0.
  if (!omega && !state.spin && !rotation_on_axis) state.spin = 0.0;
  if (omega) state.omega = *omega;
  if (state.spin && std::fabs(*state.spin) <= kMaxCreepage) {
    state.omega = OmegaFromSpin(*state.spin, state.velocity, wheelset.nominal_radius);
  }
  CheckWheelsetState(
      state, wheelset, omega.has_value(),
      [&section](std::string_view key, const std::string& message) { section.Fail(key, message); });
  return state;
}

HalfspaceState ReadHalfspaceState(const Section& section) {
  HalfspaceState state;
  state.fn = section.OptionalNumber("fn");
  state.approach = section.OptionalNumber("approach");
  if (state.fn && state.approach) {
    section.Fail("approach", "give either state.fn or state.approach, not both");
  }
  if (!state.fn && !state.approach) {
    section.file().FailAt(section.position(), "state.fn",
                          "missing: give the normal force state.fn (N) or the approach "
                          "state.approach (mm)");
  }
  if (state.fn) RequireForce(section, "fn", *state.fn);
  if (state.approach) {
    RequireMagnitudeAtMost(section, "approach", *state.approach, kMaxVerticalPosition,
                           "mm, the bodies' approach; a contact's is a small fraction of a mm");
  }
  state.cksi = section.Number("cksi", state.cksi);
  RequireMagnitudeAtMost(section, "cksi", state.cksi, kMaxCreepage,
                         "a relative creepage; 1 is 100 % slip");
  state.ceta = section.Number("ceta", state.ceta);
  RequireMagnitudeAtMost(section, "ceta", state.ceta, kMaxCreepage,
                         "a relative creepage; 1 is 100 % slip");
  state.cphi = section.Number("cphi", state.cphi);
  RequireMagnitudeAtMost(section, "cphi", state.cphi, kMaxSpinCreepage, "1/mm");
  return state;
}

}  // namespace

CaseType ReadCaseType(const toml::table& root, const SourceFile& file) {
  const Section problem(file, root, "problem");
  return problem.Choice("type",
                        {{"wheel-rail", CaseType::kWheelRail}, {"halfspace", CaseType::kHalfspace}},
                        CaseType::kWheelRail);
}

Case ReadCase(const toml::table& root, const SourceFile& file,
              const std::filesystem::path& base_dir, const CaseParseOptions& options) {
  Case result;
  result.type = ReadCaseType(root, file);
  CheckNames(root, file, result.type, options.allow_table_section);
  result.source_name = file.name();
  result.base_dir = base_dir;

  ReadMaterials(Section(file, root, "material"), result);
  result.friction = ReadFriction(Section(file, root, "friction"));
  result.grid = ReadGrid(Section(file, root, "grid"), result.type);
  result.effects = ReadEffects(Section(file, root, "effects"));

  if (result.type == CaseType::kWheelRail) {
    result.rail = ReadProfileSource(Section(file, root, "rail"), ProfileKind::kRail, base_dir,
                                    options.check_files_exist);
    result.wheel = ReadProfileSource(Section(file, root, "wheel"), ProfileKind::kWheel, base_dir,
                                     options.check_files_exist);
    result.track = ReadTrack(Section(file, root, "track"));
    result.wheelset = ReadWheelset(Section(file, root, "wheelset"), result.track);
    result.method = ReadMethod(Section(file, root, "method"));
    result.state = ReadWheelsetState(Section(file, root, "state"), result.wheelset, options);
  } else {
    result.geometry = ReadGeometry(Section(file, root, "geometry"));
    result.halfspace_state = ReadHalfspaceState(Section(file, root, "state"));
  }
  return result;
}

namespace {

// Closes a descriptor when the read is done, however it ends.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

std::string SystemError(const std::filesystem::path& path, const std::string& what) {
  return path.string() + ": " + what + ": " + std::strerror(errno);
}

}  // namespace

std::string ReadTextFile(const std::filesystem::path& path, std::size_t max_bytes) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer; fstat then refuses it.
  const Descriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
  if (file.fd < 0) throw InputError(SystemError(path, "cannot open file"));
  struct stat info {};
  if (::fstat(file.fd, &info) != 0) throw InputError(SystemError(path, "cannot inspect file"));
  if (S_ISDIR(info.st_mode)) throw InputError(path.string() + ": is a directory, not a file");
  if (!S_ISREG(info.st_mode)) {
    throw InputError(path.string() + ": is not a regular file (a device, FIFO or socket)");
  }
  const auto too_large = [&] {
    return InputError(path.string() + ": larger than " + std::to_string(max_bytes >> 20) +
                      " MiB, too large for an input file");
  };
  if (static_cast<std::uintmax_t>(info.st_size) > max_bytes) throw too_large();
  std::string contents;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(file.fd, buffer, sizeof buffer);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      throw InputError(SystemError(path, "cannot read file"));
    }
    contents.append(buffer, static_cast<std::size_t>(n));
    if (contents.size() > max_bytes) throw too_large();  // grew while being read
  }
  return contents;
}

}  // namespace io

double Friction::MuAt(double alpha_rad) const {
  if (is_constant() || mu.size() == 1) return mu.front();
  constexpr double kDegreesPerRadian = 57.29577951308232;
  const double alpha = alpha_rad * kDegreesPerRadian;
  if (alpha <= alpha_deg.front()) return mu.front();
  if (alpha >= alpha_deg.back()) return mu.back();
  // First angle above alpha; alpha lies in [alpha_deg[i-1], alpha_deg[i]).
  const std::size_t i = static_cast<std::size_t>(
      std::upper_bound(alpha_deg.begin(), alpha_deg.end(), alpha) - alpha_deg.begin());
  const double t = (alpha - alpha_deg[i - 1]) / (alpha_deg[i] - alpha_deg[i - 1]);
  return mu[i - 1] + t * (mu[i] - mu[i - 1]);
}

ProfileOptions ProfileOptionsOf(const ProfileSource& source) {
  ProfileOptions options;
  options.mirror_y = source.mirror_y;
  options.detect_mirror_y = source.mirror_y_auto;
  options.mirror_z = source.mirror_z;
  options.report_orientation = source.report_orientation;
  options.smoothing = source.smooth;
  options.scale_yz = source.scale_yz;
  return options;
}

std::shared_ptr<const ProfileSpline> SplineOf(const ProfileSource& source, ProfileKind kind) {
  if (source.spline) return source.spline;
  return std::make_shared<const ProfileSpline>(
      ReadProfile(source.path.string(), kind, ProfileOptionsOf(source)));
}

Case ParseCase(std::string_view toml_text, const std::filesystem::path& base_dir,
               std::string_view display_name) {
  const io::SourceFile file{std::string(display_name)};
  const toml::table root = file.Parse(toml_text);
  Case result = io::ReadCase(root, file, base_dir, io::CaseParseOptions{});
  result.source_text = std::string(toml_text);
  return result;
}

Case LoadCase(const std::filesystem::path& path) {
  const std::string text = io::ReadTextFile(path);
  const io::SourceFile file{path.string()};
  const toml::table root = file.Parse(text);
  io::CaseParseOptions options;
  options.check_files_exist = true;
  Case result = io::ReadCase(root, file, std::filesystem::absolute(path).parent_path(), options);
  result.source_text = text;
  return result;
}

}  // namespace wrc
