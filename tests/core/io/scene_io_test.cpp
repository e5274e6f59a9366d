#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "wrc/core/errors.h"
#include "wrc/core/scene.h"

namespace wrc {
namespace {

namespace fs = std::filesystem;

// The case part of a scene: no y, z/fz, omega/spin in [state], so that tables may vary them.
const std::string kSceneCase = R"([problem]
type = "wheel-rail"
[rail]
profile = "../profiles/MBench_UIC60_v3.prr"
[wheel]
profile = "../profiles/MBench_S1002_v3.prw"
[wheelset]
nominal_radius = 460.0
[grid]
dx = 0.2
ds = 0.2
[state]
roll = 0.0
velocity = 2000.0
)";

// The scene example of docs/reference/case-files.md, with fz fixed in [state].
const std::string kSpecTable = R"([table]
axes    = ["y", "roll", "yaw", "spin"]
y       = {from = -10.0, to = 10.0, step = 0.5}
roll    = [-0.002, 0.0, 0.002]
yaw     = {from = -0.01, to = 0.01, count = 5}
spin    = {from = -0.01, to = 0.01, count = 9}
outputs = ["fx", "fy", "fz", "mx", "my", "mz"]
)";

std::string WithoutLine(std::string text, const std::string& line) {
  const std::size_t at = text.find(line + "\n");
  EXPECT_NE(at, std::string::npos) << line;
  if (at != std::string::npos) text.erase(at, line.size() + 1);
  return text;
}

/// A scene with fz prescribed and the given [table] text.
std::string SceneWith(const std::string& table, const std::string& state_extra = "fz = 10000.0\n") {
  return WithoutLine(kSceneCase, "roll = 0.0") + state_extra + table;
}

Scene Parse(const std::string& text) { return ParseScene(text, "/work/scenes", "scene.toml"); }

std::string ErrorOf(const std::string& text) {
  try {
    Parse(text);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

/// 1-based number of the first line that starts with `start`.
int LineOf(const std::string& text, const std::string& start) {
  const std::size_t at = text.rfind(start, 0) == 0 ? 0 : text.find("\n" + start) + 1;
  EXPECT_NE(at, std::string::npos) << start;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
}

/// Expects an InputError whose message has "scene.toml:<line of line_of>: " and all `parts`.
void ExpectSceneError(const std::string& text, const std::string& line_of,
                      const std::vector<std::string>& parts) {
  const std::string message = ErrorOf(text);
  ASSERT_FALSE(message.empty()) << "no error for:\n" << text;
  if (!line_of.empty()) {
    const std::string location = "scene.toml:" + std::to_string(LineOf(text, line_of)) + ": ";
    EXPECT_NE(message.find(location), std::string::npos) << message << "\nexpected " << location;
  }
  for (const std::string& part : parts) {
    EXPECT_NE(message.find(part), std::string::npos) << message << "\nexpected " << part;
  }
}

void ExpectValues(const std::vector<double>& actual, const std::vector<double>& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(actual[i], expected[i], 1e-12) << "value " << i;
  }
}

TEST(SceneIo, SpecExampleAxes) {
  const std::string text = WithoutLine(kSceneCase, "roll = 0.0") + "fz = 10000.0\n" + kSpecTable;
  const Scene scene = Parse(text);
  ASSERT_EQ(scene.axes.size(), 4u);
  EXPECT_EQ(scene.axes[0].name, "y");
  EXPECT_EQ(scene.axes[1].name, "roll");
  EXPECT_EQ(scene.axes[2].name, "yaw");
  EXPECT_EQ(scene.axes[3].name, "spin");
  const std::vector<double>& y = scene.axes[0].values;
  ASSERT_EQ(y.size(), 41u);
  EXPECT_EQ(y.front(), -10.0);
  EXPECT_EQ(y[20], 0.0);
  EXPECT_EQ(y.back(), 10.0);
  ExpectValues(scene.axes[1].values, {-0.002, 0.0, 0.002});
  ExpectValues(scene.axes[2].values, {-0.01, -0.005, 0.0, 0.005, 0.01});
  EXPECT_EQ(scene.axes[2].values.back(), 0.01);
  ASSERT_EQ(scene.axes[3].values.size(), 9u);
  EXPECT_NEAR(scene.axes[3].values[4], 0.0, 1e-18);
  EXPECT_EQ(scene.Shape(), (std::vector<std::size_t>{41, 3, 5, 9}));
  EXPECT_EQ(scene.PointCount(), 41u * 3u * 5u * 9u);
  // count written as a whole float is the same count.
  std::string float_count = text;
  float_count.replace(float_count.find("count = 5}"), 10, "count = 5.0}");
  ExpectValues(Parse(float_count).axes[2].values, {-0.01, -0.005, 0.0, 0.005, 0.01});
  EXPECT_EQ(scene.outputs, (std::vector<std::string>{"fx", "fy", "fz", "mx", "my", "mz"}));
  EXPECT_EQ(scene.base.source_text, text);
  EXPECT_EQ(scene.base.source_name, "scene.toml");
  // The base case carries the first value of every axis.
  EXPECT_EQ(scene.base.state.y, -10.0);
  EXPECT_EQ(scene.base.state.roll, -0.002);
  EXPECT_EQ(*scene.base.state.spin, -0.01);
  EXPECT_DOUBLE_EQ(scene.base.state.omega, -(2000.0 / 460.0) * 0.99);
  EXPECT_EQ(scene.base.rail.path, fs::path("/work/profiles/MBench_UIC60_v3.prr"));
}

TEST(SceneIo, StepRangeIncludesEndOnlyWhenOnGrid) {
  // 0.1 is not exact in binary: the end must still be included, and exactly as written.
  Scene scene =
      Parse(SceneWith("[table]\naxes = [\"y\"]\ny = {from = 0.0, to = 1.0, step = 0.1}\n"));
  ASSERT_EQ(scene.axes[0].values.size(), 11u);
  EXPECT_EQ(scene.axes[0].values.back(), 1.0);
  EXPECT_NEAR(scene.axes[0].values[3], 0.3, 1e-15);

  scene = Parse(SceneWith("[table]\naxes = [\"y\"]\ny = {from = 0.0, to = 1.0, step = 0.3}\n"));
  ExpectValues(scene.axes[0].values, {0.0, 0.3, 0.6, 0.9});

  scene = Parse(SceneWith("[table]\naxes = [\"y\"]\ny = {from = -1, to = 2, step = 1}\n"));
  ExpectValues(scene.axes[0].values, {-1.0, 0.0, 1.0, 2.0});

  scene = Parse(SceneWith("[table]\naxes = [\"y\"]\ny = {from = 2.5, to = 2.5, step = 1}\n"));
  ExpectValues(scene.axes[0].values, {2.5});
}

TEST(SceneIo, CountAndListRanges) {
  Scene scene =
      Parse(SceneWith("[table]\naxes = [\"yaw\", \"y\"]\n"
                      "yaw = {from = 0.0, to = 0.01, count = 3}\n"
                      "y = [-1.5, 0, 2]\n"));
  ExpectValues(scene.axes[0].values, {0.0, 0.005, 0.01});
  ExpectValues(scene.axes[1].values, {-1.5, 0.0, 2.0});

  scene = Parse(SceneWith("[table]\naxes = [\"y\"]\ny = {from = 3.0, to = 3.0, count = 1}\n"));
  ExpectValues(scene.axes[0].values, {3.0});

  // A range may also be written as a sub-table.
  scene = Parse(SceneWith("[table]\naxes = [\"y\"]\n[table.y]\nfrom = 0\nto = 4\ncount = 5\n"));
  ExpectValues(scene.axes[0].values, {0.0, 1.0, 2.0, 3.0, 4.0});
}

TEST(SceneIo, DefaultOutputsDependOnWhatIsPrescribed) {
  const std::vector<std::string> common = {
      "fx", "fy", "fz", "mx", "my", "mz", "n_patches", "contact_y", "contact_angle", "pmax"};
  std::vector<std::string> with_z = common;
  with_z.push_back("z");
  Scene scene = Parse(SceneWith("[table]\naxes = [\"y\"]\ny = [0.0, 1.0]\n"));
  EXPECT_EQ(scene.outputs, with_z);
  scene = Parse(SceneWith("[table]\naxes = [\"y\"]\ny = [0.0, 1.0]\n", "z = 0.1\n"));
  EXPECT_EQ(scene.outputs, common);
  scene = Parse(SceneWith("[table]\naxes = [\"fz\"]\nfz = [5000.0, 10000.0]\n", ""));
  EXPECT_EQ(scene.outputs, with_z);
  EXPECT_EQ(DefaultSceneOutputs(false), common);
}

// The surface-fatigue outputs judge the load against a body's yield limit in shear, which the
// solve itself does not need: a scene asking for one without it is refused at the output.
TEST(SceneIo, FatigueOutputsNeedTheYieldLimit) {
  const std::string table =
      "[table]\naxes = [\"y\"]\ny = [0.0, 1.0]\noutputs = [\"fy\", "
      "\"t_gamma_slip\", \"fi_surf_wheel\"]\n";
  ExpectSceneError(SceneWith(table), "outputs",
                   {"table.outputs[2]", "fi_surf_wheel needs", "material.shear_yield"});
  const Scene scene = Parse(SceneWith(table) + "[material]\nshear_yield = 320.0\n");
  EXPECT_EQ(scene.outputs, (std::vector<std::string>{"fy", "t_gamma_slip", "fi_surf_wheel"}));
  EXPECT_EQ(QuantityUnit("fi_surf_wheel"), "-");
  EXPECT_EQ(QuantityUnit("t_gamma_slip"), "N");
}

TEST(SceneIo, CaseAtPointAppliesAxisValues) {
  const std::string text = SceneWith(
      "[table]\naxes = [\"y\", \"z\", \"spin\", \"mu\", \"yaw\", \"vy\"]\n"
      "y = [0.0, 5.0]\nz = [0.0, 0.1]\nspin = [0.0, 0.01]\nmu = [0.2, 0.4]\n"
      "yaw = [0.0, 0.01]\nvy = [0.0, 10.0]\n",
      "vyaw = 0.5\n");
  const Scene scene = Parse(text);
  const Case point = CaseAtPoint(scene, {2.5, 0.05, 0.01, 0.35, 0.004, 3.0});
  EXPECT_EQ(point.state.y, 2.5);
  ASSERT_TRUE(point.state.z.has_value());
  EXPECT_EQ(*point.state.z, 0.05);
  EXPECT_FALSE(point.state.fz.has_value());
  EXPECT_DOUBLE_EQ(point.state.omega, -(2000.0 / 460.0) * 1.01);
  EXPECT_EQ(*point.state.spin, 0.01);
  EXPECT_TRUE(point.friction.is_constant());
  EXPECT_EQ(point.friction.MuAt(0.0), 0.35);
  EXPECT_EQ(point.state.yaw, 0.004);
  EXPECT_EQ(point.state.vy, 3.0);
  EXPECT_EQ(point.state.vyaw, 0.5);         // not an axis: from [state]
  EXPECT_EQ(point.state.velocity, 2000.0);  // not an axis: from [state]

  const Case node = CaseAtIndex(scene, {1, 1, 0, 1, 0, 0});
  EXPECT_EQ(node.state.y, 5.0);
  EXPECT_EQ(*node.state.z, 0.1);
  EXPECT_DOUBLE_EQ(node.state.omega, -2000.0 / 460.0);
  EXPECT_EQ(node.friction.mu, std::vector<double>{0.4});

  EXPECT_THROW(CaseAtPoint(scene, {1.0}), std::invalid_argument);
  EXPECT_THROW(CaseAtIndex(scene, {2, 0, 0, 0, 0, 0}), std::out_of_range);
  EXPECT_THROW(CaseAtPoint(scene, {0.0, 0.0, 0.0, -0.1, 0.0, 0.0}), InputError);
  EXPECT_THROW(CaseAtPoint(scene, {std::nan(""), 0.0, 0.0, 0.1, 0.0, 0.0}), InputError);
}

TEST(SceneIo, OmegaAndFzAxes) {
  const Scene scene = Parse(SceneWith(
      "[table]\naxes = [\"fz\", \"omega\"]\nfz = [5000.0, 10000.0]\nomega = [-4.4, -4.3]\n", ""));
  const Case point = CaseAtPoint(scene, {7500.0, -4.35});
  EXPECT_EQ(*point.state.fz, 7500.0);
  EXPECT_FALSE(point.state.z.has_value());
  EXPECT_EQ(point.state.omega, -4.35);
  EXPECT_FALSE(point.state.spin.has_value());
}

TEST(SceneIo, RejectsBadAxes) {
  ExpectSceneError(SceneWith("[table]\naxes = [\"y\", \"rol\"]\ny = [0.0]\n"),
                   "axes =", {"table.axes[1] = \"rol\"", "unknown axis", "did you mean \"roll\"?"});
  ExpectSceneError(SceneWith("[table]\naxes = [\"y\", \"yaw\"]\ny = [0.0]\n"), "[table]",
                   {"table.yaw: missing", "listed in table.axes"});
  ExpectSceneError(SceneWith("[table]\naxes = [\"y\"]\ny = [0.0]\nyaw = [0.0, 0.1]\n"),
                   "yaw =", {"table.yaw = [0, 0.1]", "not listed in table.axes"});
  ExpectSceneError(SceneWith("[table]\naxes = [\"z\", \"fz\"]\nz = [0.0]\nfz = [1.0]\n", ""),
                   "axes =", {"table.axes", "z and fz"});
  ExpectSceneError(
      SceneWith("[table]\naxes = [\"spin\", \"omega\"]\nspin = [0.0]\nomega = [1.0]\n"),
      "axes =", {"table.axes", "spin and omega"});
  ExpectSceneError(SceneWith("[table]\naxes = [\"y\", \"y\"]\ny = [0.0]\n"),
                   "axes =", {"table.axes[1]", "twice"});
  ExpectSceneError(SceneWith("[table]\naxes = []\n"), "axes =", {"table.axes", "at least one"});
  ExpectSceneError(SceneWith("[table]\ny = [0.0]\n"), "[table]", {"table.axes: missing"});
  ExpectSceneError(SceneWith("[table]\naxes = [\"y\"]\ny = [0.0]\nouputs = [\"fx\"]\n"), "ouputs",
                   {"table.ouputs", "did you mean table.outputs?"});
  ExpectSceneError(kSceneCase + "fz = 1.0\n", "", {"scene.toml: [table]: missing"});
  ExpectSceneError(SceneWith("[table]\naxes = [\"y\", \"yaw\"]\n"
                             "y = {from = 0, to = 1, count = 100000}\n"
                             "yaw = {from = 0, to = 1, count = 100000}\n"),
                   "axes =", {"table.axes", "1e+10 points", "limit"});
}

TEST(SceneIo, RejectsBadRanges) {
  const std::string axes = "[table]\naxes = [\"y\"]\n";
  ExpectSceneError(SceneWith(axes + "y = {from = 0.0, to = 1.0, step = 0.0}\n"),
                   "y =", {"table.y.step = 0", "must be positive"});
  ExpectSceneError(SceneWith(axes + "y = {from = 0.0, to = 1.0, step = -0.1}\n"),
                   "y =", {"table.y.step = -0.1", "must be positive"});
  ExpectSceneError(SceneWith(axes + "y = {from = 1.0, to = 0.0, step = 0.1}\n"),
                   "y =", {"table.y.to = 0", "empty range"});
  ExpectSceneError(SceneWith(axes + "y = {from = 0.0, to = 1.0, count = 0}\n"),
                   "y =", {"table.y.count = 0", "at least 1"});
  ExpectSceneError(SceneWith(axes + "y = {from = 0.0, to = 1.0, count = 2.5}\n"),
                   "y =", {"table.y.count = 2.5", "whole number"});
  ExpectSceneError(SceneWith(axes + "y = {from = 0.0, to = 1.0, step = 5.0}\n"),
                   "y =", {"table.y.step = 5", "only its start"});
  ExpectSceneError(SceneWith(axes + "y = {from = 0.0, to = 1.0, count = 1}\n"),
                   "y =", {"table.y.count = 1", "from = to"});
  ExpectSceneError(SceneWith(axes + "y = {from = 0.0, to = 1.0}\n"),
                   "y =", {"table.y", "exactly one of table.y.step and table.y.count"});
  ExpectSceneError(SceneWith(axes + "y = {from = 0.0, to = 1.0, step = 0.1, count = 3}\n"),
                   "y =", {"table.y", "exactly one of"});
  ExpectSceneError(SceneWith(axes + "y = {from = 0.0, step = 0.1}\n"),
                   "y =", {"table.y.to: missing"});
  ExpectSceneError(SceneWith(axes + "y = {form = 0.0, to = 1.0, step = 0.1}\n"),
                   "y =", {"table.y.form = 0", "did you mean table.y.from?"});
  ExpectSceneError(SceneWith(axes + "y = [0.0, 1.0, 1.0]\n"),
                   "y =", {"table.y[2] = 1", "strictly ascending"});
  ExpectSceneError(SceneWith(axes + "y = []\n"), "y =", {"table.y", "at least one value"});
  // Values the runtime could not interpolate between: refused before any point is solved.
  ExpectSceneError(SceneWith(axes + "y = [0.0, 5e-324]\n"), "y =", {"table.y[1]", "too close"});
  ExpectSceneError(SceneWith(axes + "y = [1.0, 1.0000000000001]\n"),
                   "y =", {"table.y[1]", "too close"});
  ExpectSceneError(SceneWith(axes + "y = [-1e308, 0.0]\n"), "y =", {"table.y[0]", "beyond"});
  ExpectSceneError(SceneWith(axes + "y = {from = 0.0, to = 1e-300, count = 3}\n"),
                   "y =", {"table.y", "too small"});
  ExpectSceneError(SceneWith(axes + "y = [0.0, nan]\n"), "y =", {"table.y[1] = nan", "finite"});
  ExpectSceneError(SceneWith(axes + "y = {from = nan, to = 1.0, step = 0.1}\n"),
                   "y =", {"table.y.from = nan", "finite"});
  ExpectSceneError(SceneWith(axes + "y = \"0..1\"\n"), "y =", {"table.y = \"0..1\"", "{from"});
  ExpectSceneError(SceneWith(axes + "y = {from = 0.0, to = 1e9, step = 1e-3}\n"),
                   "y =", {"table.y.step", "more than"});
  ExpectSceneError(SceneWith("[table]\naxes = [\"mu\"]\nmu = [-0.1, 0.3]\n"),
                   "mu =", {"table.mu[0] = -0.1", "negative"});
  ExpectSceneError(SceneWith("[table]\naxes = [\"fz\"]\nfz = {from = 0, to = 10, count = 3}\n", ""),
                   "fz =", {"table.fz.from = 0", "positive"});
}

TEST(SceneIo, RejectsQuantityBothFixedAndOnAxis) {
  const std::string state_y = "y = 6.0\nfz = 10000.0\n";
  ExpectSceneError(SceneWith("[table]\naxes = [\"y\"]\ny = [0.0, 1.0]\n", state_y), "y = 6.0",
                   {"state.y = 6", "also varied by table axis \"y\""});
  ExpectSceneError(SceneWith("[table]\naxes = [\"z\"]\nz = [0.0, 1.0]\n"), "fz = 10000.0",
                   {"state.fz = 10000", "table axis \"z\""});
  ExpectSceneError(
      SceneWith("[table]\naxes = [\"omega\"]\nomega = [-4.0, -3.0]\n", "fz = 1.0\nspin = 0.0\n"),
      "spin = 0.0", {"state.spin = 0", "table axis \"omega\""});
  ExpectSceneError(
      SceneWith("[table]\naxes = [\"mu\"]\nmu = [0.1, 0.3]\n") + "[friction]\nmu = 0.3\n",
      "mu = 0.3", {"friction.mu = 0.3", "table axis \"mu\""});
}

TEST(SceneIo, RejectsBadOutputs) {
  const std::string base = "[table]\naxes = [\"y\"]\ny = [0.0]\n";
  ExpectSceneError(SceneWith(base + "outputs = [\"fx\", \"fyy\"]\n"), "outputs",
                   {"table.outputs[1] = \"fyy\"", "unknown output", "did you mean \"fy\"?"});
  ExpectSceneError(SceneWith(base + "outputs = [\"fx\", \"z\"]\n", "z = 0.1\n"), "outputs",
                   {"table.outputs[1] = \"z\"", "only when fz is prescribed"});
  ExpectSceneError(SceneWith(base + "outputs = [\"fx\", \"fx\"]\n"), "outputs",
                   {"table.outputs[1]", "twice"});
  ExpectSceneError(SceneWith(base + "outputs = []\n"), "outputs",
                   {"table.outputs", "at least one"});
}

TEST(SceneIo, CaseErrorsStillReported) {
  // The case part is checked as strictly as a case file.
  ExpectSceneError(SceneWith("[table]\naxes = [\"y\"]\ny = [0.0]\n", "fz = 1.0\nspn = 0.0\n"),
                   "spn", {"state.spn", "did you mean state.spin?"});
  ExpectSceneError(SceneWith("[table]\naxes = [\"y\"]\ny = [0.0]\n", ""), "[state]",
                   {"state.z: missing"});
  const std::string halfspace = R"([problem]
type = "halfspace"
[geometry]
a1 = 0.001
b1 = 0.001
[grid]
dx = 0.1
dy = 0.1
[state]
fn = 100.0
[table]
axes = ["mu"]
mu = [0.1, 0.2]
)";
  ExpectSceneError(halfspace, "type =", {"problem.type = \"halfspace\"", "wheel-rail"});
}

TEST(SceneIo, UnitsForTableAttributes) {
  EXPECT_EQ(QuantityUnit("y"), "mm");
  EXPECT_EQ(QuantityUnit("fz"), "N");
  EXPECT_EQ(QuantityUnit("mz"), "N*mm");
  EXPECT_EQ(QuantityUnit("omega"), "rad/s");
  EXPECT_EQ(QuantityUnit("pmax"), "N/mm^2");
  EXPECT_EQ(QuantityUnit("spin"), "-");
  EXPECT_EQ(QuantityUnit("bogus"), "");
  for (const StateQuantity& q : kStateQuantities) EXPECT_FALSE(q.unit.empty()) << q.name;
  for (const OutputQuantity& q : kOutputQuantities) EXPECT_FALSE(q.unit.empty()) << q.name;
}

TEST(SceneIo, LoadSceneResolvesProfilesNextToTheFile) {
  const fs::path dir = fs::path(WRC_TEST_DATA_DIR) / "profiles";
  const fs::path scene_dir = fs::temp_directory_path() / "wrc_scene_io_test" / "scenes";
  fs::create_directories(scene_dir);
  const fs::path file = scene_dir / "scene.toml";
  std::string text = SceneWith(kSpecTable);
  // Point the profiles at the test data folder with an absolute path.
  const std::string rail_line = "profile = \"../profiles/MBench_UIC60_v3.prr\"";
  const std::string wheel_line = "profile = \"../profiles/MBench_S1002_v3.prw\"";
  text.replace(text.find(rail_line), rail_line.size(),
               "profile = \"" + (dir / "MBench_UIC60_v3.prr").string() + "\"");
  text.replace(text.find(wheel_line), wheel_line.size(),
               "profile = \"" + (dir / "MBench_S1002_v3.prw").string() + "\"");
  {
    std::ofstream out(file);
    out << text;
  }
  const Scene scene = LoadScene(file);
  EXPECT_EQ(scene.PointCount(), 41u * 3u * 5u * 9u);
  EXPECT_EQ(scene.base.source_text, text);
  EXPECT_TRUE(fs::is_regular_file(scene.base.rail.path));

  // With the relative paths of SceneWith the profiles are not found next to the temp file.
  {
    std::ofstream out(file);
    out << SceneWith(kSpecTable);
  }
  try {
    LoadScene(file);
    ADD_FAILURE() << "missing profile not reported";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(":4: rail.profile"), std::string::npos)
        << error.what();
  }

  // A wheel profile that exists but is no profile: the message names the scene's key and line
  // before the profile's own file, line and problem.
  std::ofstream(scene_dir / "two.csv") << "-10,0\n10,0\n";
  const std::string absolute_wheel = "profile = \"" + (dir / "MBench_S1002_v3.prw").string() + "\"";
  std::string broken = text;
  broken.replace(broken.find(absolute_wheel), absolute_wheel.size(), "profile = \"two.csv\"");
  std::ofstream(file) << broken;
  try {
    LoadScene(file);
    ADD_FAILURE() << "broken wheel profile not reported";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(file.string() + ":6: wheel.profile = \"two.csv\": " +
                           (scene_dir / "two.csv").string() + ":2: only 2 profile point(s)"),
              std::string::npos)
        << message;
  }
  fs::remove_all(scene_dir.parent_path());
}

TEST(SceneIo, RejectsWheelRadiusThatWouldOverflowASpinAxis) {
  // Found by fuzzing: a spin axis on a 1e-310 mm wheel at the largest accepted speed, 1e6 mm/s,
  // gave omega = -inf at every node. The radius is refused at its own key first.
  std::string text = SceneWith(kSpecTable);
  text.replace(text.find("velocity = 2000.0"), 17, "velocity = 1e6");
  text.replace(text.find("nominal_radius = 460.0"), 22, "nominal_radius = 1e-310");
  ExpectSceneError(
      text, "nominal_radius =", {"wheelset.nominal_radius = 1e-310: ", "between 10 and 2000"});
}

}  // namespace
}  // namespace wrc

namespace wrc {
namespace {

const std::string kRefinedTable = R"([table]
axes    = ["y", "fz", "yaw"]
y       = {from = -4.0, to = 4.0, count = 3}
fz      = [5000.0, 20000.0]
yaw     = {from = -0.01, to = 0.01, count = 3}
outputs = ["fx", "fy", "fz", "n_patches", "z"]
)";

TEST(SceneRefine, DefaultsAndKeys) {
  const Scene plain = Parse(SceneWith(kRefinedTable, ""));
  EXPECT_FALSE(plain.refine.has_value());
  const Scene scene = Parse(SceneWith(kRefinedTable + "[table.refine]\n", ""));
  ASSERT_TRUE(scene.refine.has_value());
  const RefineSettings& r = *scene.refine;
  EXPECT_DOUBLE_EQ(r.load_fraction, 0.005);
  EXPECT_EQ(r.outputs, (std::vector<std::string>{"fx", "fy", "fz", "z"}));  // forces and z
  ASSERT_EQ(r.absolute.count("z"), 1u);
  EXPECT_DOUBLE_EQ(r.absolute.at("z"), 0.003);
  EXPECT_EQ(r.max_points, 1'000'000u);
  EXPECT_EQ(r.samples, 24);

  const Scene custom =
      Parse(SceneWith(kRefinedTable + "[table.refine]\ntarget = 0.02\nabsolute = {n_patches "
                                      "= 0.5}\nmax_points = 500\nmin_step = {yaw = 1e-4}\n",
                      ""));
  EXPECT_DOUBLE_EQ(custom.refine->load_fraction, 0.02);
  EXPECT_EQ(custom.refine->outputs, (std::vector<std::string>{"fx", "fy", "fz", "n_patches"}));
  EXPECT_EQ(custom.refine->max_points, 500u);
  EXPECT_DOUBLE_EQ(custom.refine->min_step.at("yaw"), 1e-4);
}

TEST(SceneRefine, RejectsBadSettings) {
  const auto error = [](const std::string& refine) {
    return ErrorOf(SceneWith(kRefinedTable + "[table.refine]\n" + refine, ""));
  };
  EXPECT_NE(error("taget = 0.01\n").find("table.refine.taget"), std::string::npos);
  EXPECT_NE(error("taget = 0.01\n").find("did you mean table.refine.target"), std::string::npos);
  EXPECT_NE(error("target = 2.0\n").find("table.refine.target"), std::string::npos);
  EXPECT_NE(error("absolute = {fy = 1.0}\n").find("not a non-force output"), std::string::npos);
  EXPECT_NE(error("outputs = [\"n_patches\"]\n").find("has no target"), std::string::npos);
  EXPECT_NE(error("max_points = 10\n").find("table.refine.max_points"), std::string::npos);
  EXPECT_NE(error("min_step = {roll = 0.1}\n").find("not an axis"), std::string::npos);
  EXPECT_NE(error("samples = 0\n").find("table.refine.samples"), std::string::npos);
  // A prescribed-z scene knows the load only from the solved fz.
  std::string z_table = kRefinedTable;
  z_table.replace(z_table.find("\"fz\", \"yaw\""), 11, "\"z\", \"yaw\"");
  z_table.replace(z_table.find("fz      = [5000.0, 20000.0]"), 27, "z = [0.0, 0.1]");
  z_table.replace(z_table.find("\"fz\", \"n_patches\", \"z\""), 22, "\"n_patches\"");
  EXPECT_NE(ErrorOf(SceneWith(z_table + "[table.refine]\n", "")).find("fz is among"),
            std::string::npos);
}

TEST(SceneRefine, WheelLateralPositionFollowsRoll) {
  const std::string table = R"([table]
axes    = ["y_wheel", "roll"]
y_wheel = [-2.0, 0.0, 2.0]
roll    = [-0.002, 0.002]
outputs = ["fy"]
)";
  const Scene scene = Parse(WithoutLine(kSceneCase, "roll = 0.0") + "fz = 10000.0\n" + table);
  // y = y_wheel + r0·roll, whichever order the axes come in.
  const Case c = CaseAtPoint(scene, {1.5, 0.002});
  EXPECT_DOUBLE_EQ(c.state.y, 1.5 + 460.0 * 0.002);
  EXPECT_DOUBLE_EQ(c.state.roll, 0.002);
  EXPECT_EQ(QuantityUnit("y_wheel"), "mm");
  const std::string both = R"([table]
axes = ["y", "y_wheel"]
y = [0.0, 1.0]
y_wheel = [0.0, 1.0]
)";
  EXPECT_NE(ErrorOf(SceneWith(both)).find("y and y_wheel"), std::string::npos);
}

}  // namespace
}  // namespace wrc
