// `wrc geometry` as a user runs it, on EN 15302's case E3 (wheel H on rail S-A, a 1:40 tread
// with a contact jump at ±2.45 mm) written as a case file in a directory of the user's: the
// files it writes, the jumps it names, and the equivalent conicity against the standard's
// reference inside the band (the wider band next to the jump, docs/conicity.md).

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/number_table.h"
#include "tests/tools/tool_test_util.h"

namespace {

namespace fs = std::filesystem;
using wrc::tool_test::kSource;
using wrc::tool_test::ReadFile;
using wrc::tool_test::RunWrcIn;

class Geometry : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("wrc_geometry_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    const fs::path profiles = kSource / "tests" / "data" / "en15302" / "profiles";
    for (const char* name : {"SUIC519A.dat", "RUIC519H.dat", "RUIC519A.dat"}) {
      fs::copy_file(profiles / name, dir_ / name);
    }
    std::ofstream(dir_ / "e3.toml")
        << "[problem]\ntype = \"wheel-rail\"\n[rail]\nprofile = \"SUIC519A.dat\"\n"
           "[wheel]\nprofile = \"RUIC519H.dat\"\n"
           "[track]\ngauge_height = 0.0\nrail_y = 750.0\nrail_z = 0.0\ncant = 0.0\n"
           "[wheelset]\nflange_back_distance = 1360.0\nflange_back_position = -70.0\n"
           "nominal_radius = 460.0\n[state]\nfz = 10000.0\nvelocity = 2000.0\n"
           "[grid]\ndx = 0.5\nds = 0.5\n";
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

std::vector<std::vector<double>> Csv(const fs::path& path) {
  return wrc::test_support::NumberRows(path.string(), ',');
}

TEST_F(Geometry, GivesEN15302sConicityAndNamesTheJumps) {
  ASSERT_EQ(RunWrcIn(dir_, "geometry e3.toml --y-max 6.8 --out out --json", 300), 0)
      << ReadFile(dir_ / "stderr.txt");
  const auto summary = nlohmann::json::parse(ReadFile(dir_ / "stdout.txt"));
  // The tread jump of wheel H at about ±2.45 mm, on either side.
  bool left_jump = false, right_jump = false;
  for (double y : summary["jumps_y_mm"]) {
    left_jump |= std::fabs(y + 2.45) < 0.1;
    right_jump |= std::fabs(y - 2.45) < 0.1;
  }
  EXPECT_TRUE(left_jump && right_jump) << summary["jumps_y_mm"];
  const auto geometry = Csv(dir_ / "out" / "geometry.csv");
  ASSERT_EQ(geometry.size(), 137u);  // -6.8 ... 6.8
  const auto& centre = geometry[68];
  EXPECT_EQ(centre[0], 0.0);
  EXPECT_NEAR(centre[1], 0.0, 1e-9);               // Δr of a symmetric pair
  EXPECT_NEAR(centre[4], centre[5], 1e-12);        // equal contact angles
  EXPECT_NEAR(centre[4], std::atan(0.025), 2e-3);  // on the 1:40 tread
  // tan γe against the standard's reference, every 0.1 mm from 1 mm (its table's amplitudes).
  const auto bands = Csv(kSource / "tests" / "data" / "en15302" / "tables" / "conicity_E3.csv");
  int compared = 0;
  for (const auto& c : Csv(dir_ / "out" / "conicity.csv")) {
    for (const auto& band : bands) {
      if (std::fabs(band[0] - c[0]) > 1e-6) continue;
      ++compared;
      EXPECT_LE(c[1], band[4]) << c[0];  // the wider band everywhere
      EXPECT_GE(c[1], band[5]) << c[0];
      const bool next_to_jump = std::fabs(c[0] - 2.45) <= 0.3 || c[0] >= 6.4;
      if (!next_to_jump) {
        EXPECT_LE(c[1], band[2]) << c[0];
        EXPECT_GE(c[1], band[3]) << c[0];
      }
    }
  }
  EXPECT_GE(compared, 50);
  EXPECT_TRUE(summary["tan_gamma_e_3mm"].is_number());
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    EXPECT_EQ(ReadFile(dir_ / "out" / "geometry.png").substr(1, 3), "PNG");
  }
}

// A left wheel of its own (H right, A left): the pair is no longer symmetric, and Δr at y = 0
// is the difference of the radii at their contact points.
TEST_F(Geometry, TakesALeftWheelOfItsOwnAndRefusesWhatDoesNotFit) {
  ASSERT_EQ(RunWrcIn(dir_, "geometry e3.toml --y-max 3 --left-wheel RUIC519A.dat --out out", 300),
            0)
      << ReadFile(dir_ / "stderr.txt");
  const auto geometry = Csv(dir_ / "out" / "geometry.csv");
  EXPECT_GT(std::fabs(geometry[30][1]), 1e-3);  // y = 0
  // The roll solved: odd in y, and the output says which.
  ASSERT_EQ(
      RunWrcIn(dir_, "geometry e3.toml --y-max 3 --y-step 0.5 --roll solved --out rolled", 300), 0)
      << ReadFile(dir_ / "stderr.txt");
  EXPECT_NE(ReadFile(dir_ / "stdout.txt").find("wheelset roll: solved"), std::string::npos);
  const auto rolled = Csv(dir_ / "rolled" / "geometry.csv");
  ASSERT_EQ(rolled.size(), 13u);
  EXPECT_NEAR(rolled[0][11], -rolled[12][11], 1e-8);
  EXPECT_NE(rolled[0][11], 0.0);
  EXPECT_EQ(RunWrcIn(dir_, "geometry e3.toml --roll sometimes", 60), 2);
  EXPECT_EQ(RunWrcIn(dir_, "geometry e3.toml --y-max 6", 300), 0);
  EXPECT_EQ(ReadFile(dir_ / "stderr.txt"), "");  // every contact within the profiles
  EXPECT_EQ(RunWrcIn(dir_, "geometry missing.toml", 60), 2);
}

// The shipped Manchester case (S1002 on UIC60 at 1:40) at a light load, without its pose: the
// case for `wrc geometry` and, with a [table] over y, the scene of a table. Profiles by absolute
// path, so that both run in the test's directory.
std::string LightManchester() {
  std::istringstream in(ReadFile(kSource / "tables" / "mbench_case.toml"));
  std::string text, line;
  while (std::getline(in, line)) {
    if (line.rfind("y = ", 0) == 0 || line.rfind("yaw = ", 0) == 0) continue;  // the pose
    if (line.rfind("fz = ", 0) == 0) line = "fz = 500.0";
    const auto at = line.find("\"profiles/");
    if (at != std::string::npos) line.insert(at + 1, (kSource / "tables").string() + "/");
    text += line + "\n";
  }
  return text;
}

// `--table`: a right wheel's table over y at a light load (500 N) stores the rolling radius
// under load; its Δr lies on the rigid one to the elastic approach, at the table's nodes within
// 0.01 mm (measured: 3 µm at most), and its conicity, Δr interpolated between nodes 0.5 mm
// apart, within 0.01 of the rigid one from 2 mm on (measured 0.0006 at 2 mm).
TEST_F(Geometry, ATablesDrUnderLightLoadLiesOnTheRigidOne) {
  std::ofstream(dir_ / "m.toml") << LightManchester();
  std::ofstream(dir_ / "m_table.toml")
      << LightManchester() << "[table]\naxes = [\"y\"]\ny = {from = -4.0, to = 4.0, step = 0.5}\n"
      << "outputs = [\"rolling_radius\", \"fz\"]\n";
  ASSERT_EQ(RunWrcIn(dir_, "generate m_table.toml -o m.h5 --threads 2 --quiet", 300), 0)
      << ReadFile(dir_ / "stderr.txt");
  ASSERT_EQ(RunWrcIn(dir_, "geometry m.toml --y-max 4 --table m.h5 --out out --json", 300), 0)
      << ReadFile(dir_ / "stderr.txt");
  int nodes = 0;
  for (const auto& row : Csv(dir_ / "out" / "geometry.csv")) {
    const double y = row.at(0), rigid = row.at(1), table = row.at(12);
    ASSERT_TRUE(std::isfinite(table)) << y;
    if (std::fabs(y / 0.5 - std::round(y / 0.5)) > 1e-9) continue;
    ++nodes;
    EXPECT_NEAR(table, rigid, 0.01) << "y = " << y;
  }
  EXPECT_EQ(nodes, 17);
  const auto summary = nlohmann::json::parse(ReadFile(dir_ / "stdout.txt"));
  int compared = 0;
  for (const auto& c : summary["conicity"]) {
    if (c["amplitude_mm"].get<double>() < 2.0 - 1e-9 || c["tan_gamma_e_table"].is_null()) continue;
    ++compared;
    EXPECT_NEAR(c["tan_gamma_e_table"].get<double>(), c["tan_gamma_e"].get<double>(), 0.01)
        << c["amplitude_mm"];
  }
  EXPECT_GE(compared, 10);
  // A file that is no table, or a table without the rolling radius, is refused by name.
  EXPECT_EQ(RunWrcIn(dir_, "geometry m.toml --y-max 4 --table m.toml", 60), 2);
  std::ofstream(dir_ / "no_radius.toml")
      << LightManchester() << "[table]\naxes = [\"y\"]\ny = [-1.0, 1.0]\noutputs = [\"fy\"]\n";
  ASSERT_EQ(RunWrcIn(dir_, "generate no_radius.toml -o n.h5 --quiet", 300), 0);
  EXPECT_EQ(RunWrcIn(dir_, "geometry m.toml --y-max 1 --table n.h5", 60), 2);
  EXPECT_NE(ReadFile(dir_ / "stderr.txt").find("rolling_radius"), std::string::npos);
}

}  // namespace
