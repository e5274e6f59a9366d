#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "wrc/core/case.h"
#include "wrc/core/errors.h"

namespace wrc {
namespace {

namespace fs = std::filesystem;

const fs::path kCasesDir = fs::path(WRC_TEST_DATA_DIR) / "reference" / "cases";

// A complete wheel-rail case; tests replace single lines to make it wrong in one place.
const std::string kWheelRailCase = R"(# test case
[problem]
type = "wheel-rail"

[rail]
profile = "profiles/rail.prr"
[wheel]
profile = "profiles/wheel.prw"

[track]
gauge_height = 14.0

[grid]
dx = 0.2
ds = 0.2

[material]
poisson = 0.28
shear_modulus = 82000.0

[friction]
mu = 0.3

[method]
reference = "curved"

[wheelset]
side = "right"
nominal_radius = 460.0

[effects]
tangential = true

[state]
y = 1.0
fz = 10000.0
velocity = 2000.0
omega = -4.35
)";

const std::string kHalfspaceCase = R"([problem]
type = "halfspace"
[geometry]
a1 = 0.001
b1 = 0.002
[grid]
dx = 0.1
dy = 0.1
x = [-3.0, 3.0]
y = [-3.0, 3.0]
[material]
poisson = 0.28
shear_modulus = 82000.0
[friction]
mu = 0.3
[effects]
tangential = true
[state]
fn = 1000.0
cksi = 0.001
)";

/// `text` with the first occurrence of `from` replaced by `to` (which must exist).
std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test text lacks: " << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

/// 1-based line of the first occurrence of `needle`.
int LineOf(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
}

/// The InputError message of parsing `text`, or "" when it parses.
std::string ErrorOf(const std::string& text) {
  try {
    ParseCase(text, "/cases", "case.toml");
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

/// Replaces `from` by `to` in `base` and expects an error naming the file, the line of `at`
/// (default: of `to`) and every one of `parts`.
void ExpectCaseError(const std::string& base, const std::string& from, const std::string& to,
                     const std::vector<std::string>& parts, const std::string& at = "") {
  const std::string text = Replace(base, from, to);
  const std::string message = ErrorOf(text);
  ASSERT_FALSE(message.empty()) << "no error for: " << to;
  const std::string location =
      "case.toml:" + std::to_string(LineOf(text, at.empty() ? to : at)) + ": ";
  EXPECT_NE(message.find(location), std::string::npos) << message << "\nexpected " << location;
  for (const std::string& part : parts) {
    EXPECT_NE(message.find(part), std::string::npos) << message << "\nexpected " << part;
  }
}

std::vector<fs::path> ReferenceCaseFiles() {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(kCasesDir)) {
    if (entry.is_regular_file() && entry.path().extension() == ".toml") {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(CaseIo, EveryReferenceCaseLoads) {
  const std::vector<fs::path> files = ReferenceCaseFiles();
  ASSERT_GE(files.size(), 40u);
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    Case loaded;
    ASSERT_NO_THROW(loaded = LoadCase(file));
    EXPECT_FALSE(loaded.source_text.empty());
    EXPECT_EQ(loaded.source_name, file.string());
    if (loaded.type == CaseType::kWheelRail) {
      EXPECT_TRUE(fs::is_regular_file(loaded.rail.path));
      EXPECT_TRUE(fs::is_regular_file(loaded.wheel.path));
      EXPECT_NE(loaded.state.z.has_value(), loaded.state.fz.has_value());
    } else {
      EXPECT_NE(loaded.halfspace_state.fn.has_value(), loaded.halfspace_state.approach.has_value());
    }
  }
}

TEST(CaseIo, HeavyHaulFrictionArraysAndPose) {
  const Case c = LoadCase(kCasesDir / "heavy_haul" / "heavy_haul_z1.087.toml");
  EXPECT_EQ(c.type, CaseType::kWheelRail);
  EXPECT_EQ(c.friction.alpha_deg, (std::vector<double>{-30.0, -20.0}));
  EXPECT_EQ(c.friction.mu, (std::vector<double>{0.2, 0.35}));
  EXPECT_FALSE(c.friction.is_constant());
  EXPECT_DOUBLE_EQ(c.friction.MuAt(-25.0 * M_PI / 180.0), 0.275);
  EXPECT_DOUBLE_EQ(c.friction.MuAt(-1.0), 0.2);
  EXPECT_DOUBLE_EQ(c.friction.MuAt(0.0), 0.35);
  ASSERT_TRUE(c.state.z.has_value());
  EXPECT_DOUBLE_EQ(*c.state.z, 1.087);
  EXPECT_FALSE(c.state.fz.has_value());
  EXPECT_DOUBLE_EQ(c.state.y, 14.85);
  EXPECT_DOUBLE_EQ(c.state.roll, -0.0013);
  EXPECT_DOUBLE_EQ(c.state.yaw, 0.005);
  EXPECT_DOUBLE_EQ(c.state.velocity, 15000.0);
  EXPECT_DOUBLE_EQ(c.state.omega, -32.1);
  EXPECT_FALSE(c.state.spin.has_value());
  EXPECT_DOUBLE_EQ(c.track.gauge_height, 15.875);
  EXPECT_DOUBLE_EQ(c.track.gauge_width, 1435.1);
  EXPECT_DOUBLE_EQ(c.track.cant, 0.0);
  EXPECT_DOUBLE_EQ(c.wheelset.flange_back_distance, 1347.4);
  EXPECT_DOUBLE_EQ(c.wheelset.flange_back_position, 0.0);
  EXPECT_DOUBLE_EQ(c.wheelset.nominal_radius, 444.0);
  EXPECT_DOUBLE_EQ(c.grid.dx, 0.4);
  EXPECT_DOUBLE_EQ(c.grid.ds, 0.4);
  EXPECT_DOUBLE_EQ(c.method.combine_distance, 30.0);
  EXPECT_EQ(c.rail.path.filename(), "site_b_hr.prr");
  EXPECT_EQ(c.wheel.path.filename(), "worn_high_mileage.prw");
}

TEST(CaseIo, GrooveAbsolutePlacement) {
  const Case c = LoadCase(kCasesDir / "groove" / "groove_r1005.toml");
  EXPECT_TRUE(c.track.absolute_placement());
  EXPECT_DOUBLE_EQ(c.track.gauge_height, -1.0);
  EXPECT_DOUBLE_EQ(c.track.rail_y, 0.0);
  EXPECT_DOUBLE_EQ(c.track.rail_z, 0.0);
  ASSERT_TRUE(c.state.fz.has_value());
  EXPECT_DOUBLE_EQ(*c.state.fz, 10000.0);
  EXPECT_DOUBLE_EQ(c.state.omega, -1.0006495);
  EXPECT_DOUBLE_EQ(c.grid.dx, 0.095833);
  EXPECT_DOUBLE_EQ(c.grid.ds, 0.25);
  EXPECT_DOUBLE_EQ(c.rail_material.shear_modulus, 80000.0);
  EXPECT_DOUBLE_EQ(c.wheel_material.shear_modulus, 80000.0);
  EXPECT_DOUBLE_EQ(c.method.combine_distance, 4.0);
  // Paths are resolved against the case file's folder and normalised.
  EXPECT_TRUE(c.rail.path.is_absolute());
  EXPECT_EQ(c.rail.path, fs::absolute(fs::path(WRC_TEST_DATA_DIR) / "profiles" / "groove_r1005.prr")
                             .lexically_normal());
  EXPECT_EQ(c.rail.path_as_written, "../../../profiles/groove_r1005.prr");
  EXPECT_EQ(c.wheel.path.filename(), "circ_r10.prw");
}

TEST(CaseIo, HalfspaceGridAndState) {
  const Case c = LoadCase(kCasesDir / "halfspace" / "ab03_ceta0.003.toml");
  EXPECT_EQ(c.type, CaseType::kHalfspace);
  EXPECT_DOUBLE_EQ(c.geometry.a1, 0.001087);
  EXPECT_DOUBLE_EQ(c.geometry.b1, 0.000174);
  EXPECT_DOUBLE_EQ(c.grid.dx, 0.18);
  EXPECT_DOUBLE_EQ(c.grid.dy, 0.62);
  ASSERT_TRUE(c.grid.x.has_value());
  ASSERT_TRUE(c.grid.y.has_value());
  EXPECT_DOUBLE_EQ(c.grid.x->min, -3.06);
  EXPECT_DOUBLE_EQ(c.grid.x->max, 3.06);
  EXPECT_DOUBLE_EQ(c.grid.y->min, -10.54);
  EXPECT_DOUBLE_EQ(c.grid.y->max, 10.54);
  ASSERT_TRUE(c.halfspace_state.fn.has_value());
  EXPECT_DOUBLE_EQ(*c.halfspace_state.fn, 10000.0);
  EXPECT_DOUBLE_EQ(c.halfspace_state.cksi, 0.0);
  EXPECT_DOUBLE_EQ(c.halfspace_state.ceta, 0.003);
  EXPECT_DOUBLE_EQ(c.halfspace_state.cphi, 0.0);
  EXPECT_TRUE(c.effects.tangential);

  const Case approach = LoadCase(kCasesDir / "halfspace" / "ab1_approach0.02.toml");
  EXPECT_FALSE(approach.halfspace_state.force_prescribed());
  ASSERT_TRUE(approach.halfspace_state.approach.has_value());
  EXPECT_DOUBLE_EQ(*approach.halfspace_state.approach, 0.02);
  EXPECT_FALSE(approach.effects.tangential);
}

TEST(CaseIo, MbenchMethodAndSpin) {
  const Case curved = LoadCase(kCasesDir / "mbench_curved" / "mbench_curved_y6.toml");
  EXPECT_EQ(curved.method.reference, ReferenceSurface::kCurved);
  EXPECT_EQ(curved.method.position, ReferencePosition::kWeighted);
  EXPECT_EQ(curved.method.angle, ReferenceAngle::kWeighted);
  EXPECT_EQ(curved.method.weights, ReferenceWeights::kQuadratic);
  EXPECT_DOUBLE_EQ(curved.track.cant, 0.025);
  EXPECT_DOUBLE_EQ(curved.state.y, 6.0);
  ASSERT_TRUE(curved.state.spin.has_value());
  EXPECT_DOUBLE_EQ(*curved.state.spin, 0.0);
  EXPECT_DOUBLE_EQ(curved.state.omega, -2000.0 / 460.0);

  const Case planar = LoadCase(kCasesDir / "mbench_planar" / "mbench_planar_y6.toml");
  EXPECT_EQ(planar.method.reference, ReferenceSurface::kPlanar);

  const Case varfric = LoadCase(kCasesDir / "mbench_varfric" / "mbench_varfric_y4.toml");
  EXPECT_EQ(varfric.friction.alpha_deg, (std::vector<double>{-20.0, -10.0}));
  EXPECT_EQ(varfric.friction.mu, (std::vector<double>{0.2, 0.3}));
}

TEST(CaseIo, SpinConvertsToOmega) {
  const std::string text = Replace(kWheelRailCase, "omega = -4.35", "spin = 0.01");
  const Case c = ParseCase(text, "/cases", "case.toml");
  ASSERT_TRUE(c.state.spin.has_value());
  EXPECT_DOUBLE_EQ(*c.state.spin, 0.01);
  EXPECT_DOUBLE_EQ(c.state.omega, -(2000.0 / 460.0) * 1.01);
  EXPECT_DOUBLE_EQ(OmegaFromSpin(0.0, 2000.0, 460.0), -2000.0 / 460.0);
}

TEST(CaseIo, DefaultsFollowSpec) {
  const std::string text = R"([rail]
profile = "r.prr"
[wheel]
profile = "w.prw"
[grid]
dx = 0.5
ds = 0.25
[state]
z = 0.1
velocity = 3000.0
)";
  const Case c = ParseCase(text, "/data/cases", "minimal.toml");
  EXPECT_EQ(c.type, CaseType::kWheelRail);
  EXPECT_EQ(c.rail.path, fs::path("/data/cases/r.prr"));
  EXPECT_FALSE(c.rail.mirror_y);
  EXPECT_DOUBLE_EQ(c.track.gauge_height, 14.0);
  EXPECT_DOUBLE_EQ(c.track.gauge_width, 1435.0);
  EXPECT_DOUBLE_EQ(c.track.cant, 0.025);
  EXPECT_EQ(c.wheelset.side, WheelSide::kRight);
  EXPECT_DOUBLE_EQ(c.wheelset.flange_back_distance, 1360.0);
  EXPECT_DOUBLE_EQ(c.wheelset.flange_back_position, -70.0);
  EXPECT_DOUBLE_EQ(c.wheelset.nominal_radius, 460.0);
  EXPECT_DOUBLE_EQ(c.rail_material.poisson, 0.28);
  EXPECT_DOUBLE_EQ(c.wheel_material.shear_modulus, 82000.0);
  EXPECT_TRUE(c.friction.is_constant());
  EXPECT_DOUBLE_EQ(c.friction.MuAt(0.3), 0.3);
  EXPECT_EQ(c.method.reference, ReferenceSurface::kCurved);
  EXPECT_EQ(c.method.position, ReferencePosition::kWeighted);
  EXPECT_EQ(c.method.angle, ReferenceAngle::kWeighted);
  EXPECT_EQ(c.method.weights, ReferenceWeights::kQuadratic);
  EXPECT_DOUBLE_EQ(c.method.combine_distance, 6.0);
  EXPECT_TRUE(c.effects.tangential);
  EXPECT_TRUE(c.effects.midplane_correction);
  EXPECT_EQ(c.state.y, 0.0);
  EXPECT_DOUBLE_EQ(*c.state.z, 0.1);
  EXPECT_FALSE(c.state.fz.has_value());
  EXPECT_EQ(c.state.roll, 0.0);
  EXPECT_EQ(c.state.yaw, 0.0);
  EXPECT_DOUBLE_EQ(c.state.velocity, 3000.0);
  // Neither omega nor spin: free rolling at the nominal radius, spin = 0.
  ASSERT_TRUE(c.state.spin.has_value());
  EXPECT_EQ(*c.state.spin, 0.0);
  EXPECT_DOUBLE_EQ(c.state.omega, -3000.0 / 460.0);
  EXPECT_DOUBLE_EQ(c.state.vy, 0.0);
  EXPECT_DOUBLE_EQ(c.state.vroll, 0.0);
  EXPECT_DOUBLE_EQ(c.state.vyaw, 0.0);
  EXPECT_EQ(c.source_name, "minimal.toml");
  EXPECT_EQ(c.source_text, text);
}

TEST(CaseIo, MaterialPerBodyAndIntegers) {
  std::string text = Replace(kWheelRailCase, "poisson = 0.28", "poisson = [0.28, 0.3]");
  text = Replace(text, "shear_modulus = 82000.0", "shear_modulus = [82000, 80000]");
  text = Replace(text, "dx = 0.2", "dx = 1");
  text = Replace(text, "side = \"right\"", "side = \"left\"");
  const Case c = ParseCase(text, "/cases", "case.toml");
  EXPECT_DOUBLE_EQ(c.rail_material.poisson, 0.28);
  EXPECT_DOUBLE_EQ(c.wheel_material.poisson, 0.3);
  EXPECT_DOUBLE_EQ(c.rail_material.shear_modulus, 82000.0);
  EXPECT_DOUBLE_EQ(c.wheel_material.shear_modulus, 80000.0);
  EXPECT_DOUBLE_EQ(c.grid.dx, 1.0);
  EXPECT_EQ(c.wheelset.side, WheelSide::kLeft);
  EXPECT_TRUE(std::isnan(c.rail_material.shear_yield));  // not given: no fatigue index
  const Case yielding =
      ParseCase(Replace(text, "shear_modulus = [82000, 80000]",
                        "shear_modulus = [82000, 80000]\nshear_yield = [300, 350.5]"),
                "/cases", "case.toml");
  EXPECT_DOUBLE_EQ(yielding.rail_material.shear_yield, 300.0);
  EXPECT_DOUBLE_EQ(yielding.wheel_material.shear_yield, 350.5);
}

TEST(CaseIo, FrictionVaryingWithAngleInterpolates) {
  Friction friction;
  friction.alpha_deg = {-20.0, -10.0, 0.0};
  friction.mu = {0.2, 0.3, 0.5};
  const double deg = M_PI / 180.0;
  EXPECT_DOUBLE_EQ(friction.MuAt(-30.0 * deg), 0.2);
  EXPECT_DOUBLE_EQ(friction.MuAt(-15.0 * deg), 0.25);
  EXPECT_DOUBLE_EQ(friction.MuAt(-5.0 * deg), 0.4);
  EXPECT_DOUBLE_EQ(friction.MuAt(10.0 * deg), 0.5);
  EXPECT_DOUBLE_EQ(Friction::Constant(0.1).MuAt(1.0), 0.1);
}

TEST(CaseIo, RejectsUnknownSectionsAndKeys) {
  ExpectCaseError(kWheelRailCase, "[grid]", "[grdi]",
                  {"[grdi]", "unknown section", "did you mean [grid]?"});
  ExpectCaseError(kWheelRailCase, "dx = 0.2", "dxx = 0.2",
                  {"grid.dxx = 0.2", "unknown key", "did you mean grid.dx?"});
  ExpectCaseError(kWheelRailCase, "y = 1.0", "cksi = 0.001",
                  {"state.cksi", "not used by problem.type = \"wheel-rail\""});
  ExpectCaseError(kHalfspaceCase, "dy = 0.1", "ds = 0.1", {"grid.ds", "use grid.dy"});
  ExpectCaseError(kHalfspaceCase, "[effects]", "[track]", {"[track]", "not used by"});
  ExpectCaseError(kWheelRailCase, "# test case", "dx = 0.2", {"dx", "put it under [grid]"});
  ExpectCaseError(kWheelRailCase, "# test case", "[table]\naxes = [\"y\"]", {"[table]", "scene"});
}

TEST(CaseIo, RejectsWrongTypesAndNonFiniteNumbers) {
  ExpectCaseError(kWheelRailCase, "dx = 0.2", "dx = \"0.2\"",
                  {"grid.dx = \"0.2\"", "must be a number"});
  ExpectCaseError(kWheelRailCase, "dx = 0.2", "dx = nan", {"grid.dx = nan", "finite"});
  ExpectCaseError(kWheelRailCase, "y = 1.0", "y = inf", {"state.y = inf", "finite"});
  ExpectCaseError(kWheelRailCase, "tangential = true", "tangential = 1",
                  {"effects.tangential = 1", "true or false"});
  ExpectCaseError(kWheelRailCase, "profile = \"profiles/rail.prr\"", "profile = 3",
                  {"rail.profile = 3", "must be a string"});
  ExpectCaseError(Replace(kWheelRailCase, "[grid]\ndx = 0.2\nds = 0.2", ""), "# test case",
                  "grid = 0.2", {"grid = 0.2", "must be a section"});
}

TEST(CaseIo, RejectsOutOfRangeValues) {
  // The message format of the brief, with the exact line.
  const std::string text = Replace(kWheelRailCase, "dx = 0.2", "dx = -0.2");
  EXPECT_EQ(ErrorOf(text), "case.toml:14: grid.dx = -0.2: must be positive");

  ExpectCaseError(kWheelRailCase, "ds = 0.2", "ds = 0", {"grid.ds = 0", "must be positive"});
  ExpectCaseError(kHalfspaceCase, "dy = 0.1", "dy = -1", {"grid.dy = -1", "must be positive"});
  ExpectCaseError(kWheelRailCase, "poisson = 0.28", "poisson = 0.5",
                  {"material.poisson = 0.5", "[0, 0.5)"});
  ExpectCaseError(kWheelRailCase, "poisson = 0.28", "poisson = [0.28, -0.1]",
                  {"material.poisson[1] = -0.1", "[0, 0.5)"});
  ExpectCaseError(kWheelRailCase, "poisson = 0.28", "poisson = [0.28, 0.3, 0.3]",
                  {"material.poisson", "[rail, wheel]"});
  ExpectCaseError(kWheelRailCase, "shear_modulus = 82000.0", "shear_modulus = 0",
                  {"material.shear_modulus = 0", "must be between 0.01 and 1e+07"});
  // 1e-300 used to end in "arc length nan mm outside the profile", blaming the rail profile.
  ExpectCaseError(kWheelRailCase, "shear_modulus = 82000.0", "shear_modulus = [82000.0, 1e-300]",
                  {"material.shear_modulus[1] = 1e-300", "must be between 0.01 and 1e+07"});
  // A cant of 1e10 rad used to be solved as ok (the angle taken modulo a turn).
  ExpectCaseError(kWheelRailCase, "gauge_height = 14.0", "gauge_height = 14.0\ncant = 1e10",
                  {"track.cant = 1e+10", "must be within ±0.2"}, "cant");
  ExpectCaseError(kWheelRailCase, "mu = 0.3", "mu = -0.1",
                  {"friction.mu = -0.1", "must not be negative"});
  ExpectCaseError(kHalfspaceCase, "x = [-3.0, 3.0]", "x = [3.0, -3.0]",
                  {"grid.x = [3, -3]", "min must be less than max"});
  ExpectCaseError(kHalfspaceCase, "y = [-3.0, 3.0]", "y = [1.0, 1.0]", {"grid.y"});
  ExpectCaseError(kHalfspaceCase, "y = [-3.0, 3.0]", "y = [1.0]", {"grid.y", "[min, max]"});
  ExpectCaseError(kHalfspaceCase, "a1 = 0.001", "a1 = 0", {"geometry.a1 = 0", "positive"});
  ExpectCaseError(kWheelRailCase, "nominal_radius = 460.0", "nominal_radius = -460",
                  {"wheelset.nominal_radius = -460", "between 10 and 2000"});
  ExpectCaseError(kWheelRailCase, "fz = 10000.0", "fz = -5", {"state.fz = -5", "positive"});
  ExpectCaseError(kHalfspaceCase, "fn = 1000.0", "fn = 0", {"state.fn = 0", "positive"});
  ExpectCaseError(kWheelRailCase, "gauge_height = 14.0", "gauge_height = 14.0\nrail_y = 3.0",
                  {"track.rail_y = 3", "absolute placement"}, "rail_y");
  ExpectCaseError(kWheelRailCase, "gauge_height = 14.0", "gauge_height = -1\ngauge_width = 1435",
                  {"track.gauge_width = 1435", "absolute placement"}, "gauge_width");
}

TEST(CaseIo, RejectsInvalidChoices) {
  ExpectCaseError(kWheelRailCase, "reference = \"curved\"", "reference = \"curvy\"",
                  {"method.reference = \"curvy\"", "must be one of \"curved\", \"planar\""});
  ExpectCaseError(kWheelRailCase, "reference = \"curved\"", "weights = \"cubic\"",
                  {"method.weights = \"cubic\"", "\"linear\", \"quadratic\""});
  ExpectCaseError(kWheelRailCase, "reference = \"curved\"", "position = \"centre\"",
                  {"method.position", "\"initial\", \"weighted\""});
  ExpectCaseError(kWheelRailCase, "reference = \"curved\"", "angle = \"mean\"",
                  {"method.angle", "\"sampled\", \"weighted\""});
  ExpectCaseError(kWheelRailCase, "side = \"right\"", "side = \"middle\"",
                  {"wheelset.side = \"middle\"", "\"right\", \"left\""});
  ExpectCaseError(kWheelRailCase, "type = \"wheel-rail\"", "type = \"half-space\"",
                  {"problem.type = \"half-space\"", "\"wheel-rail\", \"halfspace\""});
}

TEST(CaseIo, RejectsBadFrictionArrays) {
  ExpectCaseError(kWheelRailCase, "mu = 0.3", "alpha_deg = [-20.0, -10.0]\nmu = [0.2, 0.3, 0.4]",
                  {"friction.mu", "same length"}, "mu = [");
  ExpectCaseError(kWheelRailCase, "mu = 0.3", "mu = [0.2, 0.3]\nalpha_deg = [-10.0, -20.0]",
                  {"friction.alpha_deg[1] = -20", "strictly ascending"}, "alpha_deg");
  ExpectCaseError(kWheelRailCase, "mu = 0.3", "mu = [0.2, 0.3]", {"friction.mu", "alpha_deg"});
  ExpectCaseError(kWheelRailCase, "mu = 0.3", "mu = 0.3\nalpha_deg = [-10.0, -20.0]",
                  {"friction.mu = 0.3", "array"});
  ExpectCaseError(kWheelRailCase, "mu = 0.3", "alpha_deg = [-20.0, -10.0]\nmu = [0.2, -0.3]",
                  {"friction.mu[1] = -0.3", "negative"}, "mu = [");
}

TEST(CaseIo, RejectsMissingRequiredKeys) {
  {
    const std::string message =
        ErrorOf(Replace(kWheelRailCase, "profile = \"profiles/rail.prr\"", ""));
    EXPECT_NE(message.find("case.toml:5: rail.profile: missing"), std::string::npos) << message;
  }
  {
    const std::string message =
        ErrorOf(Replace(kWheelRailCase, "[wheel]\nprofile = \"profiles/wheel.prw\"", ""));
    EXPECT_NE(message.find("case.toml: wheel.profile: missing"), std::string::npos) << message;
  }
  {
    const std::string message = ErrorOf(Replace(kWheelRailCase, "[grid]\ndx = 0.2\nds = 0.2", ""));
    EXPECT_NE(message.find("grid.dx: missing"), std::string::npos) << message;
  }
  {
    const std::string message = ErrorOf(Replace(kWheelRailCase, "ds = 0.2", ""));
    EXPECT_NE(message.find("case.toml:13: grid.ds: missing"), std::string::npos) << message;
  }
  {
    const std::string message =
        ErrorOf(Replace(kHalfspaceCase, "[geometry]\na1 = 0.001\nb1 = 0.002", ""));
    EXPECT_NE(message.find("geometry.a1: missing"), std::string::npos) << message;
  }
  {
    const std::string message = ErrorOf(Replace(kWheelRailCase, "fz = 10000.0", ""));
    EXPECT_NE(message.find("case.toml:" + std::to_string(LineOf(kWheelRailCase, "[state]")) +
                           ": state.z: missing"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("state.fz"), std::string::npos) << message;
  }
  {
    const std::string message = ErrorOf(Replace(kWheelRailCase, "velocity = 2000.0", ""));
    EXPECT_NE(message.find("case.toml:" + std::to_string(LineOf(kWheelRailCase, "[state]")) +
                           ": state.velocity: missing"),
              std::string::npos)
        << message;
  }
  {
    const std::string message = ErrorOf(Replace(kHalfspaceCase, "fn = 1000.0", ""));
    EXPECT_NE(message.find("state.fn: missing"), std::string::npos) << message;
    EXPECT_NE(message.find("state.approach"), std::string::npos) << message;
  }
}

TEST(CaseIo, RejectsConflictingStateKeys) {
  ExpectCaseError(kWheelRailCase, "fz = 10000.0", "fz = 10000.0\nz = 0.1",
                  {"state.fz = 10000", "either state.z or state.fz"});
  ExpectCaseError(kWheelRailCase, "omega = -4.35", "omega = -4.35\nspin = 0.0",
                  {"state.spin = 0", "either state.omega or state.spin"}, "spin");
  ExpectCaseError(kHalfspaceCase, "fn = 1000.0", "fn = 1000.0\napproach = 0.01",
                  {"state.approach = 0.01", "either state.fn or state.approach"}, "approach");
}

TEST(CaseIo, ReportsSyntaxErrorsWithLineAndColumn) {
  const std::string message = ErrorOf(Replace(kWheelRailCase, "dx = 0.2", "dx = 0.2.3"));
  EXPECT_NE(message.find("case.toml:14:"), std::string::npos) << message;
  EXPECT_NE(message.find("TOML syntax error"), std::string::npos) << message;
  const std::string duplicate = ErrorOf(Replace(kWheelRailCase, "dx = 0.2", "dx = 0.2\ndx = 0.3"));
  EXPECT_NE(duplicate.find("case.toml:15:"), std::string::npos) << duplicate;
}

TEST(CaseIo, LoadChecksFiles) {
  const fs::path dir = fs::temp_directory_path() / "wrc_case_io_test";
  fs::create_directories(dir);
  const fs::path file = dir / "case.toml";
  {
    std::ofstream out(file);
    out << kWheelRailCase;
  }
  try {
    LoadCase(file);
    ADD_FAILURE() << "missing profile not reported";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(
        message.find(file.string() + ":6: rail.profile = \"profiles/rail.prr\": file not found"),
        std::string::npos)
        << message;
  }
  // ParseCase does not look for the files: a table carries its profiles along.
  EXPECT_NO_THROW(ParseCase(kWheelRailCase, dir, "case.toml"));
  EXPECT_THROW(LoadCase(dir / "absent.toml"), InputError);
  fs::remove_all(dir);
}

// A profile file that exists but does not read as a profile is reported at the case key that
// names it, with the case file and line, the value as written and the profile's own file, line
// and problem; the wheel, mirrored or not, is checked the same way.
TEST(CaseIo, LoadReportsBrokenProfilesAtTheirCaseKey) {
  const fs::path dir = fs::temp_directory_path() / "wrc_case_io_broken_profile";
  fs::remove_all(dir);
  fs::create_directories(dir / "profiles");
  const fs::path shared = fs::path(WRC_TEST_DATA_DIR) / "profiles";
  fs::copy_file(shared / "MBench_UIC60_v3.prr", dir / "profiles" / "rail.prr");
  fs::copy_file(shared / "MBench_S1002_v3.prw", dir / "profiles" / "wheel.prw");
  const fs::path file = dir / "case.toml";
  const auto write_case = [&file](const std::string& text) { std::ofstream(file) << text; };
  const auto load_error = [&file]() -> std::string {
    try {
      LoadCase(file);
    } catch (const InputError& error) {
      return error.what();
    }
    return "";
  };
  // The base loads: the shared profiles are good.
  write_case(kWheelRailCase);
  ASSERT_EQ(load_error(), "");

  struct Broken {
    std::string name, contents, problem;
  };
  const std::vector<Broken> broken = {
      {"text.csv", "y,z\n-10,0\n-5,0.1\n0,0\nfive,0.1\n10,0\n",
       "text.csv:5: 'five' is not a number (in 'five,0.1')"},
      {"nan.csv", "-10,0\n-5,0.1\n0,nan\n5,0.1\n10,0\n",
       "nan.csv:3: value 'nan' is not a finite number"},
      {"two.csv", "-10,0\n10,0\n", "two.csv:2: only 2 profile point(s)"},
      {"empty.csv", "\n", "empty.csv:1: the profile file is empty"},
      {"garbage.prr", "not a profile\n", "garbage.prr:1: no point.begin ... point.end block"},
      {"units.prr",
       "spline.begin\n units.len.f = -5\n point.begin\n 0 0\n 5 0\n 10 0\n 15 0\n point.end\n"
       "spline.end\n",
       "units.prr:2: units.len.f = '-5' must be positive"},
      {"metres.csv", "0,0\n0.001,0\n0.002,0\n0.003,0\n",
       "metres.csv: profile length 0.003 mm is outside [5, 500] mm"},
  };
  for (const Broken& b : broken) {
    SCOPED_TRACE(b.name);
    std::ofstream(dir / "profiles" / b.name) << b.contents;
    const std::string text = Replace(kWheelRailCase, "profile = \"profiles/rail.prr\"",
                                     "profile = \"profiles/" + b.name + "\"");
    write_case(text);
    const std::string message = load_error();
    const std::string key = file.string() + ":" +
                            std::to_string(LineOf(text, "profiles/" + b.name)) +
                            ": rail.profile = \"profiles/" + b.name + "\": ";
    EXPECT_EQ(message.rfind(key, 0), 0u) << message << "\nexpected to start with " << key;
    EXPECT_NE(message.find((dir / "profiles" / b.name).string() + ":"), std::string::npos)
        << message;
    EXPECT_NE(message.find(b.problem), std::string::npos) << message << "\nexpected " << b.problem;
  }

  // The wheel, with mirror_y: a wheel profile of 2 points.
  const std::string wheel_text = Replace(
      Replace(kWheelRailCase, "profile = \"profiles/wheel.prw\"", "profile = \"profiles/two.csv\""),
      "[track]", "mirror_y = true\n[track]");
  write_case(wheel_text);
  const std::string wheel_message = load_error();
  EXPECT_NE(wheel_message.find(file.string() + ":" +
                               std::to_string(LineOf(wheel_text, "profiles/two.csv")) +
                               ": wheel.profile = \"profiles/two.csv\": "),
            std::string::npos)
      << wheel_message;
  EXPECT_NE(wheel_message.find("two.csv:2: only 2 profile point(s)"), std::string::npos)
      << wheel_message;

  // ParseCase does not read the files at all (a table carries its profiles along).
  EXPECT_NO_THROW(ParseCase(wheel_text, dir, "case.toml"));
  fs::remove_all(dir);
}

TEST(CaseIo, RejectsRadiiWhoseOmegaWouldOverflow) {
  // Found by fuzzing: every value finite, yet omega = -(velocity / nominal_radius)·(1 + spin)
  // overflowed to -inf for a subnormal radius. The radius is now range-checked at its key.
  const std::string with_spin = Replace(Replace(kWheelRailCase, "omega = -4.35", "spin = 0.0"),
                                        "velocity = 2000.0", "velocity = 1e6");
  ExpectCaseError(with_spin, "nominal_radius = 460.0", "nominal_radius = 1e-310",
                  {"wheelset.nominal_radius = 1e-310: ", "between 10 and 2000"});
  ExpectCaseError(kWheelRailCase, "nominal_radius = 460.0", "nominal_radius = 1e-310",
                  {"wheelset.nominal_radius = 1e-310: ", "between 10 and 2000"});
}

TEST(CaseIo, RejectsValuesOutsideTheirPlausibleRange) {
  ExpectCaseError(kWheelRailCase, "velocity = 2000.0", "velocity = 1e200",
                  {"state.velocity = 1e+200: ", "within ±1e+06"});
  ExpectCaseError(kWheelRailCase, "dx = 0.2", "dx = 1e6", {"grid.dx = 1e+06: ", "between"});
  // Absurd dimensions and rates are named at their key, not where the geometry or the
  // tangential solver later fails on them.
  ExpectCaseError(kWheelRailCase, "nominal_radius = 460.0", "nominal_radius = 1e308",
                  {"wheelset.nominal_radius = 1e+308: ", "between 10 and 2000"});
  ExpectCaseError(kWheelRailCase, "omega = -4.35", "omega = 1e308",
                  {"state.omega = 1e+308: ", "within 100 % of free rolling"});
  // A locked wheel (omega = 0, 100 % slip) is a real braking case: accepted.
  EXPECT_EQ(ErrorOf(Replace(kWheelRailCase, "omega = -4.35", "omega = 0.0")), "");
  ExpectCaseError(kWheelRailCase, "velocity = 2000.0", "velocity = 2000.0\nvyaw = 1e308",
                  {"state.vyaw = 1e+308: ", "within ±2 "}, "vyaw = 1e308");
  ExpectCaseError(kWheelRailCase, "velocity = 2000.0", "velocity = 2000.0\nvy = -3000.0",
                  {"state.vy = -3000: ", "lateral creepage"}, "vy = -3000.0");
  ExpectCaseError(kWheelRailCase, "velocity = 2000.0", "velocity = 2000.0\nvroll = 5.0",
                  {"state.vroll = 5: ", "lateral creepage"}, "vroll = 5.0");
  EXPECT_EQ(ErrorOf(Replace(kWheelRailCase, "velocity = 2000.0",
                            "velocity = 2000.0\nvy = 20.0\nvroll = 0.01\nvyaw = 0.2")),
            "");
  ExpectCaseError(kWheelRailCase, "gauge_height = 14.0", "gauge_height = 14.0\ngauge_width = 1e308",
                  {"track.gauge_width = 1e+308: ", "between 300 and 3000"}, "gauge_width = 1e308");
  ExpectCaseError(kWheelRailCase, "side = \"right\"", "side = \"right\"\nflange_back_distance = 0",
                  {"wheelset.flange_back_distance = 0: ", "between 300 and 3000"},
                  "flange_back_distance = 0");
  ExpectCaseError(kWheelRailCase, "fz = 10000.0", "z = 1e308",
                  {"state.z = 1e+308: ", "within ±1000"});
  ExpectCaseError(
      kWheelRailCase, "shear_modulus = 82000.0", "shear_modulus = 82000.0\nshear_yield = 3e5",
      {"material.shear_yield = 3e+05: ", "between 1 and 10000 N/mm²"}, "shear_yield = 3e5");
}

}  // namespace
}  // namespace wrc
