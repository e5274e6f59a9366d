// A prescribed vertical force where the first contact estimate lies above the true first
// contact: the worn MiniProf pair whl_left_iter795.whl on rail_left_iter795.ban (tables/
// profiles), curved reference at the initial contact point. Its first two heights carry no
// force, which gives the force iteration no secant; it must go deeper from there, not ask for
// an absurd height (it asked for z = 5e299 mm and gave up with "a contact patch needs
// 1.6e137 x 237 elements").

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "wrc/core/case.h"
#include "wrc/core/wheelrail.h"

namespace wrc {
namespace {

Case WornPair(const std::string& state) {
  const std::string text = R"([problem]
type = "wheel-rail"
[rail]
profile = "rail_left_iter795.ban"
mirror_y = true
[wheel]
profile = "whl_left_iter795.whl"
[track]
gauge_height = 14.0
gauge_width = 1435.0
cant = 0.025
[wheelset]
flange_back_distance = 1360.0
flange_back_position = 0.0
nominal_radius = 460.0
[friction]
alpha_deg = [-30.0, -20.0]
mu = [0.2, 0.35]
[grid]
dx = 0.5
ds = 0.5
[method]
reference = "curved"
position = "initial"
angle = "sampled"
[state]
y = 0.0
velocity = 15000.0
)" + state;
  return ParseCase(text, std::filesystem::path(WRC_SOURCE_DIR) / "tables" / "profiles",
                   "worn_pair.toml");
}

TEST(ForceIteration, GoesDeeperWhenTheFirstHeightsCarryNoForce) {
  const WheelRailResult r = SolveWheelRail(WornPair("fz = 100000.0\n"));
  ASSERT_EQ(r.status, SolverStatus::kConverged) << r.message;
  // Met to the default tolerance, 1e-6 relative (WheelRailOptions::fz_tolerance).
  EXPECT_NEAR(r.force_T(2), 1e5, 1e-6 * 1e5 + 1e-9);
  // The height is the one a z sweep of the same case brackets: 100 kN lies between the forces
  // at z = 1.194 mm (99.2 kN) and 1.195 mm (101.1 kN).
  EXPECT_GT(r.z, 1.194);
  EXPECT_LT(r.z, 1.195);
}

TEST(ForceIteration, TheHeightFoundCarriesTheForceWhenPrescribed) {
  // The same contact with z prescribed at the height found: an independent solve of the force.
  const WheelRailResult by_force = SolveWheelRail(WornPair("fz = 100000.0\n"));
  const WheelRailResult by_height =
      SolveWheelRail(WornPair("z = " + std::to_string(by_force.z) + "\n"));
  // std::to_string keeps 6 decimals: 5e-7 mm of z at a stiffness of ~1.9e6 N/mm is ~1 N.
  EXPECT_NEAR(by_height.force_T(2), 1e5, 2.0);
}

}  // namespace
}  // namespace wrc
