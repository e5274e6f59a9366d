// Properties of the wheel–rail solver that need no reference: no contact, bad input,
// left/right mirror symmetry, only the requested effects.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "wrc/case.h"
#include "wrc/errors.h"
#include "wrc/wheelrail.h"

namespace wrc {
namespace {

namespace fs = std::filesystem;

Case Manchester(double y, ReferenceSurface reference) {
  Case c = LoadCase(fs::path(WRC_SHARED_DIR) / "reference" / "cases" / "mbench_planar" /
                    "mbench_planar_y0.toml");
  c.state.y = y;
  c.method.reference = reference;
  return c;
}

TEST(WheelRail, WheelAboveTheRailIsNoContact) {
  Case c = Manchester(0.0, ReferenceSurface::kCurved);
  c.state.fz.reset();
  c.state.z = -1.0;  // 1 mm above the rail
  const WheelRailResult r = SolveWheelRail(c);
  EXPECT_EQ(r.status, SolverStatus::kNoContact);
  EXPECT_TRUE(r.patches.empty());
  EXPECT_EQ(r.force_T.norm(), 0.0);
}

TEST(WheelRail, PoseFarOffTheRailIsBadInput) {
  Case c = Manchester(0.0, ReferenceSurface::kPlanar);
  c.state.y = 500.0;
  EXPECT_THROW(SolveWheelRail(c), InputError);
  c.state.y = 0.0;
  c.state.yaw = 1.0;
  EXPECT_THROW(SolveWheelRail(c), InputError);
  c.state.yaw = std::nan("");
  EXPECT_THROW(SolveWheelRail(c), InputError);
}

// Mirror symmetry: a left wheel at −y, −yaw equals the right wheel at +y, +yaw mirrored (the
// same profiles serve both sides, as in CONTACT).
TEST(WheelRail, LeftSideMirrorsRightSide) {
  for (ReferenceSurface ref : {ReferenceSurface::kPlanar, ReferenceSurface::kCurved}) {
    Case right = Manchester(4.0, ref);
    right.state.yaw = 0.004;
    Case left = right;
    left.wheelset.side = WheelSide::kLeft;
    left.state.y = -4.0;
    left.state.yaw = -0.004;
    const WheelRailResult a = SolveWheelRail(right);
    const WheelRailResult b = SolveWheelRail(left);
    ASSERT_EQ(a.patches.size(), b.patches.size());
    // Identical arithmetic up to the order of operations: 1e-9 of the load.
    const double tol = 1e-9 * a.force_T(2);
    EXPECT_NEAR(b.force_T(0), a.force_T(0), tol);
    EXPECT_NEAR(b.force_T(1), -a.force_T(1), tol);
    EXPECT_NEAR(b.force_T(2), a.force_T(2), tol);
    EXPECT_NEAR(b.z, a.z, 1e-9);
    EXPECT_NEAR(b.patches[0].reference_T(1), -a.patches[0].reference_T(1), 1e-9);
  }
}

// A frictionless scene solves no tangential problem: no tangential iterations, zero longitudinal
// force, and in the planar method zero lateral force. (With the curved reference, fs in the
// reference frame also holds the normal pressure acting on the inclined parts of the surface.)
TEST(WheelRail, FrictionlessSceneSkipsTangentialSolve) {
  for (ReferenceSurface ref : {ReferenceSurface::kPlanar, ReferenceSurface::kCurved}) {
    Case c = Manchester(2.0, ref);
    c.effects.tangential = false;
    const WheelRailResult r = SolveWheelRail(c);
    ASSERT_FALSE(r.patches.empty());
    for (const PatchResult& p : r.patches) {
      EXPECT_EQ(p.fx, 0.0);
      if (ref == ReferenceSurface::kPlanar) EXPECT_EQ(p.fs, 0.0);
      EXPECT_EQ(p.tangential_iterations, 0);
    }
    EXPECT_NEAR(r.force_T(2), 10000.0, 1e-6 * 10000.0);
  }
}

}  // namespace
}  // namespace wrc
