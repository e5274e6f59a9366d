// `wrc plot` as a user runs it, from a directory outside the checkout: the files it writes, the
// data it draws checked against the solver's own output and an exact solve, and the messages
// for bad options.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/tools/tool_test_util.h"

namespace {

namespace fs = std::filesystem;

using wrc::tool_test::kSource;
using wrc::tool_test::ReadFile;

// Rows of numbers: a CSV after its header, or a .dat without its '#' lines and blank lines.
std::vector<std::vector<double>> Numbers(const fs::path& path) {
  std::vector<std::vector<double>> rows;
  std::istringstream text(ReadFile(path));
  std::string line;
  const bool csv = path.extension() == ".csv";
  if (csv) std::getline(text, line);
  while (std::getline(text, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (csv) std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream cells(line);
    std::vector<double> row;
    for (double v; cells >> v;) row.push_back(v);
    rows.push_back(row);
  }
  return rows;
}

bool HaveGnuplot() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

// A PNG worth looking at: the signature, and more than an empty canvas (an empty 1000 × 600
// pngcairo picture is about 3 kB; every plot here draws maps or curves of 20 kB and more).
void ExpectPicture(const fs::path& path) {
  if (!HaveGnuplot()) return;
  ASSERT_TRUE(fs::is_regular_file(path)) << path;
  EXPECT_EQ(ReadFile(path).substr(1, 3), "PNG") << path;
  EXPECT_GT(fs::file_size(path), 10000u) << path;
}

// A user's directory holding the Manchester case (1 mm elements, to keep the solves short), the
// half-space demo and a tiny scene of the Manchester pair: 5 × 2 points on non-uniform nodes.
class Plot : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("wrc_plot_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "profiles");
    for (const char* name : {"MBench_UIC60_v3.prr", "MBench_S1002_v3.prw"}) {
      fs::copy_file(kSource / "tables" / "profiles" / name, dir_ / "profiles" / name);
    }
    fs::copy_file(kSource / "tables" / "hertz_demo.toml", dir_ / "hertz.toml");
    std::ofstream(dir_ / "mbench.toml")
        << Coarse(ReadFile(kSource / "tables" / "mbench_case.toml"));
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::string Coarse(std::string text) {
    text.replace(text.find("dx = 0.5"), 8, "dx = 1.0");
    text.replace(text.find("ds = 0.5"), 8, "ds = 1.0");
    return text;
  }

  // The demo scene at 1 mm with its [table] axes replaced by `axes`.
  std::string TinyScene(const std::string& axes) const {
    std::string text = Coarse(ReadFile(kSource / "tables" / "demo.toml"));
    return text.substr(0, text.find("[table]")) + axes;
  }

  int Run(const std::string& args) const { return wrc::tool_test::RunWrcIn(dir_, args, 200); }
  std::string Err() const { return ReadFile(dir_ / "stderr.txt"); }
  std::string Out() const { return ReadFile(dir_ / "stdout.txt"); }

  fs::path dir_;
};

// The map data equal, element by element, the fields `wrc solve --out` writes in another
// process; the pressure integrates to the patch's normal force.
TEST_F(Plot, PatchMapsAreTheSolversFields) {
  ASSERT_EQ(Run("solve mbench.toml --out solved"), 0) << Err();
  ASSERT_EQ(Run("plot patch mbench.toml --out out"), 0) << Err();
  EXPECT_NE(Out().find("out/patch1.png"), std::string::npos) << Out();
  ExpectPicture(dir_ / "out" / "patch1.png");
  const auto fields = Numbers(dir_ / "solved" / "patch1_fields.csv");
  const auto map = Numbers(dir_ / "out" / "patch1_map.dat");
  ASSERT_EQ(map.size(), fields.size());
  ASSERT_GT(map.size(), 20u);
  // map: x s pn pt px ps state w wx ws; fields: i j x s h pn px ps sx ss wx ws state. Both carry
  // 10 significant digits of the same doubles; 1e-9 relative allows the last digit's rounding.
  const int columns[][2] = {{0, 2}, {1, 3}, {2, 5}, {4, 6}, {5, 7}, {6, 12}, {8, 10}, {9, 11}};
  const auto summary = nlohmann::json::parse(ReadFile(dir_ / "solved" / "summary.json"));
  const auto curve = Numbers(dir_ / "solved" / "patch1_curve.csv");  // j s y_tr z_tr angle
  const double reference_angle = summary["patches"][0]["contact_angle"].get<double>();
  double fn = 0.0;
  for (std::size_t k = 0; k < map.size(); ++k) {
    for (const auto& [m, f] : columns) {
      EXPECT_NEAR(map[k][m], fields[k][f], 1e-9 * (1.0 + std::fabs(fields[k][f]))) << k;
    }
    EXPECT_NEAR(map[k][3], std::hypot(fields[k][6], fields[k][7]), 1e-6) << k;
    // On the curved reference each row's tractions act along its own normal and tangent,
    // turned by angle_j − δ from the reference's (paper Eq. 21–23); square 1 mm elements.
    const double turn = curve[static_cast<std::size_t>(fields[k][1])][4] - reference_angle;
    fn += (std::cos(turn) * map[k][2] + std::sin(turn) * map[k][5]) * 1.0 * 1.0;
  }
  // The rows sum to the patch's normal force to the printed digits (10, relative 1e-9 per
  // element over ~100 elements in contact: 1e-7 relative leaves a margin).
  EXPECT_NEAR(fn, summary["patches"][0]["fn"].get<double>(), 1e-7 * fn);
}

// --frictional-power: a fifth panel whose data, the dissipated power per area, integrates to the
// patch's frictional power from the solver (−frictional_power, W) to the printed digits; only
// for wheel–rail solves.
TEST_F(Plot, PatchFrictionalPowerMapIntegratesToTheSolversPower) {
  ASSERT_EQ(Run("plot patch mbench.toml --frictional-power --out power"), 0) << Err();
  ExpectPicture(dir_ / "power" / "patch1.png");
  const auto map = Numbers(dir_ / "power" / "patch1_map.dat");
  const auto summary = nlohmann::json::parse(ReadFile(dir_ / "power" / "summary.json"));
  ASSERT_GT(map.size(), 20u);
  ASSERT_EQ(map[0].size(), 11u);
  double power = 0.0;
  for (const auto& element : map) {
    EXPECT_GE(element[10], -1e-9) << "power is dissipated, never gained";
    power += element[10] * 1.0 * 1.0;  // the fixture's square 1 mm elements
  }
  const double solver = summary["patches"][0]["frictional_power"].get<double>();
  ASSERT_LT(solver, 0.0);
  EXPECT_NEAR(power, -solver, 1e-7 * std::fabs(solver));
  ASSERT_EQ(Run("solve hertz.toml --out hertz-solved"), 0) << Err();
  EXPECT_EQ(Run("plot patch --from hertz-solved --frictional-power --out h"), 2);
  EXPECT_NE(Err().find("--frictional-power needs a wheel"), std::string::npos) << Err();
}

TEST_F(Plot, PatchFromASolveDirectoryOfEitherKind) {
  ASSERT_EQ(Run("solve hertz.toml --out hertz-solved"), 0) << Err();
  ASSERT_EQ(Run("plot patch --from hertz-solved --out hertz-plot"), 0) << Err();
  ExpectPicture(dir_ / "hertz-plot" / "patch1.png");
  const auto fields = Numbers(dir_ / "hertz-solved" / "fields.csv");
  const auto map = Numbers(dir_ / "hertz-plot" / "patch1_map.dat");
  ASSERT_EQ(map.size(), fields.size());
  // Half-space files have no rigid slip: the slip (sx, sy) is drawn, columns 8 and 9.
  for (std::size_t k = 0; k < map.size(); k += 37) {
    EXPECT_NEAR(map[k][8], fields[k][8], 1e-9 * (1.0 + std::fabs(fields[k][8])));
    EXPECT_NEAR(map[k][9], fields[k][9], 1e-9 * (1.0 + std::fabs(fields[k][9])));
  }
}

// The rail as the gauge rule places it (top on the track plane, gauge face at half the gauge
// width 14 mm down), and the gap negative only inside the drawn contact patch.
TEST_F(Plot, ProfilesInPlaceWithGapAndPatches) {
  ASSERT_EQ(Run("plot profiles mbench.toml --out out"), 0) << Err();
  ExpectPicture(dir_ / "out" / "profiles.png");
  const auto rail = Numbers(dir_ / "out" / "profiles_rail.dat");
  ASSERT_GT(rail.size(), 100u);
  double z_top = 1e300, y_gauge = NAN;
  for (std::size_t k = 0; k < rail.size(); ++k) {
    z_top = std::min(z_top, rail[k][1]);
    // The first crossing of z = 14 mm from the track-centre side is the gauge face.
    if (std::isnan(y_gauge) && k > 0 && (rail[k - 1][1] - 14.0) * (rail[k][1] - 14.0) <= 0.0) {
      const double t = (14.0 - rail[k - 1][1]) / (rail[k][1] - rail[k - 1][1]);
      y_gauge = rail[k - 1][0] + t * (rail[k][0] - rail[k - 1][0]);
    }
  }
  // Points every 0.1 mm along the profile: the crown (radius ≥ 80 mm) is missed by at most
  // 0.05²/(2·80) ≈ 2e-5 mm, a chord across the gauge face (radius ≥ 13 mm) by 1e-4 mm.
  EXPECT_NEAR(z_top, 0.0, 1e-4);
  EXPECT_NEAR(y_gauge, 1435.0 / 2.0, 1e-3);
  const auto patches = Numbers(dir_ / "out" / "profiles_patches.dat");
  ASSERT_GT(patches.size(), 2u);
  double y0 = 1e300, y1 = -1e300;
  for (const auto& p : patches) {
    y0 = std::min(y0, p[0]);
    y1 = std::max(y1, p[0]);
  }
  double g0 = 1e300, g1 = -1e300;  // where the undeformed profiles interpenetrate
  for (const auto& g : Numbers(dir_ / "out" / "profiles_gap.dat")) {
    if (g[1] >= 0.0) continue;
    g0 = std::min(g0, g[0]);
    g1 = std::max(g1, g[0]);
  }
  // The contact lies inside the interpenetration and covers most of it: for Hertzian contact
  // the interpenetration's half-width is √2 times the contact's (the approach is half the
  // depth of the undeformed overlap at the centre); this patch is not quite Hertzian (the
  // curvatures change across it), so up to twice. The drawn extent ends at the edges of the
  // outermost rows in contact, within one 1 mm element of the contact's true edge.
  EXPECT_GE(y0, g0 - 1.0);
  EXPECT_LE(y1, g1 + 1.0);
  EXPECT_LT(g1 - g0, 2.0 * (y1 - y0));
  EXPECT_GT(y1 - y0, 2.0);
  const auto normals = Numbers(dir_ / "out" / "profiles_normals.dat");
  ASSERT_EQ(normals.size(), 1u);

  // The left wheel of the mirrored state is the mirror image in y, drawn from its own solve.
  std::string left = ReadFile(dir_ / "mbench.toml");
  left.replace(left.find("side = \"right\""), 14, "side = \"left\"");
  left.replace(left.find("y = 4.0"), 7, "y = -4.0");
  left.replace(left.find("yaw = 0.002"), 11, "yaw = -0.002");
  std::ofstream(dir_ / "left.toml") << left;
  ASSERT_EQ(Run("plot profiles left.toml --out left"), 0) << Err();
  for (const char* name : {"profiles_rail.dat", "profiles_wheel.dat", "profiles_gap.dat",
                           "profiles_patches.dat", "profiles_normals.dat"}) {
    const auto right_rows = Numbers(dir_ / "out" / name);
    const auto left_rows = Numbers(dir_ / "left" / name);
    ASSERT_EQ(left_rows.size(), right_rows.size()) << name;
    for (std::size_t k = 0; k < left_rows.size(); ++k) {
      // Both solves mirror each other exactly up to the last digits of the z iteration (fz to
      // 1e-6 relative moves the wheel by ~1e-7 mm); 1e-4 mm is far below the 0.1 mm drawing step.
      EXPECT_NEAR(left_rows[k][0], -right_rows[k][0], 1e-4) << name << ' ' << k;
      EXPECT_NEAR(left_rows[k][1], right_rows[k][1], 1e-4) << name << ' ' << k;
    }
  }
}

// A 1-D slice holds the stored values at the nodes: equal to the exact solve of that point.
TEST_F(Plot, TableSliceMarksTheNodesWithTheSolversValues) {
  std::ofstream(dir_ / "tiny.toml") << TinyScene(
      "[table]\naxes = [\"y\", \"yaw\"]\ny = [-3.0, -1.0, 0.0, 0.5, 2.0]\nyaw = [-0.005, "
      "0.005]\n");
  ASSERT_EQ(Run("generate tiny.toml -o tiny.h5 --quiet --threads 2"), 0) << Err();
  ASSERT_EQ(Run("plot table tiny.h5 --output fy --x y --at yaw=0.005 --out out"), 0) << Err();
  ExpectPicture(dir_ / "out" / "table_fy_y.png");
  const auto nodes = Numbers(dir_ / "out" / "table_fy_y_nodes.dat");
  ASSERT_EQ(nodes.size(), 5u);
  EXPECT_EQ(nodes[3][0], 0.5);
  EXPECT_EQ(Numbers(dir_ / "out" / "table_fy_y.dat").size(), 201u);  // the default samples
  // The node y = 0.5, yaw = 0.005 solved on its own.
  std::string point = TinyScene("");
  point.replace(point.find("[state]"), 7, "[state]\ny = 0.5\nyaw = 0.005");
  std::ofstream(dir_ / "point.toml") << point;
  ASSERT_EQ(Run("solve point.toml --json"), 0) << Err();
  const double fy = nlohmann::json::parse(Out())["rail_forces_track"]["fy"].get<double>();
  // The table's solve met fz = 10 kN to 1e-6 relative from another start (warm start along the
  // axis), so its fy agrees to about 1e-6 of the load, 0.01 N; 0.5 N leaves a wide margin and
  // is still 1e-3 of this fy (~500 N) and far below a neighbouring node's difference.
  EXPECT_NEAR(nodes[3][1], fy, 0.5);
}

TEST_F(Plot, TableMapOverTwoAxes) {
  std::ofstream(dir_ / "tiny.toml") << TinyScene(
      "[table]\naxes = [\"y\", \"yaw\"]\ny = [-2.0, 0.0, 1.0]\nyaw = [-0.005, 0.005]\n");
  ASSERT_EQ(Run("generate tiny.toml -o tiny.h5 --quiet --threads 2"), 0) << Err();
  ASSERT_EQ(Run("plot table tiny.h5 --output fx --x y --y yaw --samples 21 --out out"), 0) << Err();
  ExpectPicture(dir_ / "out" / "table_fx_y_yaw.png");
  EXPECT_EQ(Numbers(dir_ / "out" / "table_fx_y_yaw_nodes.dat").size(), 6u);
  const auto map = Numbers(dir_ / "out" / "table_fx_y_yaw.dat");
  ASSERT_EQ(map.size(), 21u * 21u);
  // The map's corners are nodes: the same values as the node file's corners.
  const auto nodes = Numbers(dir_ / "out" / "table_fx_y_yaw_nodes.dat");
  EXPECT_EQ(map.front()[2], nodes.front()[2]);
  EXPECT_EQ(map.back()[2], nodes.back()[2]);

  // Bad options: a message naming the problem, exit 2.
  EXPECT_EQ(Run("plot table tiny.h5 --output fq --x y"), 2);
  EXPECT_NE(Err().find("--output fq: the table has no such output (its outputs: "),
            std::string::npos)
      << Err();
  EXPECT_EQ(Run("plot table tiny.h5 --output fy --x roll"), 2);
  EXPECT_NE(Err().find("--x roll: the table has no such axis (its axes: y, yaw)"),
            std::string::npos)
      << Err();
  EXPECT_EQ(Run("plot table tiny.h5 --output fy --x y --at yaw=1"), 2);
  EXPECT_NE(Err().find("--at yaw=1: outside the table's"), std::string::npos) << Err();
  EXPECT_EQ(Run("plot table tiny.h5 --output fy --x y --at yaw=0.001,yaw=0.002"), 2);
  EXPECT_NE(Err().find("axis yaw is given twice"), std::string::npos) << Err();
}

TEST_F(Plot, BadInputIsNamed) {
  EXPECT_EQ(Run("plot table missing.h5 --output fy --x y"), 2);
  EXPECT_NE(Err().find("missing.h5: no such table file"), std::string::npos) << Err();
  EXPECT_EQ(Run("plot patch missing.toml"), 2);
  EXPECT_NE(Err().find("missing.toml"), std::string::npos) << Err();
  EXPECT_EQ(Run("plot patch --from nowhere"), 2);
  EXPECT_NE(Err().find("nowhere/summary.json: cannot be read"), std::string::npos) << Err();
  EXPECT_EQ(Run("plot patch"), 2);
  EXPECT_NE(Err().find("give either a case file or --from DIR"), std::string::npos) << Err();
  EXPECT_EQ(Run("plot profiles hertz.toml"), 2);
  EXPECT_NE(Err().find("needs a wheel-rail case"), std::string::npos) << Err();
  EXPECT_EQ(Run("plot nothing"), 2);
}

}  // namespace
