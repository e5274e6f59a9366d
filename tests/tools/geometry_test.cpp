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

}  // namespace
