// Hard cases stay stable, on a coarse grid so the suite stays fast; the fine sweeps
// with plots are `wrc study stability` (docs/stability/).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "wrc/core/case.h"
#include "wrc/core/wheelrail.h"

namespace wrc {
namespace {

namespace fs = std::filesystem;

Case Manchester(ReferenceSurface reference) {
  Case c = LoadCase(fs::path(WRC_TEST_DATA_DIR) / "reference" / "cases" / "mbench_planar" /
                    "mbench_planar_y0.toml");
  c.method.reference = reference;
  c.grid.dx = c.grid.ds = 0.5;
  return c;
}

// Converged (or no contact) with finite results, the prescribed load met, and bounded solver
// iterations: the normal solver needs ~30–80, the tangential ~10–80 sweeps on such grids;
// 1000 would mean a stall.
void ExpectHealthy(const WheelRailResult& r, double fz, const std::string& what) {
  ASSERT_TRUE(r.status == SolverStatus::kConverged || r.status == SolverStatus::kNoContact)
      << what << ": " << ToString(r.status) << " " << r.message;
  EXPECT_TRUE(r.force_T.allFinite() && r.moment_T.allFinite()) << what;
  if (r.status == SolverStatus::kConverged) {
    EXPECT_NEAR(r.force_T(2), fz, 1e-6 * fz) << what;
  }
  for (const PatchResult& p : r.patches) {
    EXPECT_LT(p.normal_iterations, 1000) << what;
    EXPECT_LT(p.tangential_iterations, 1000) << what;
    // Coulomb holds per element (|p_t| <= μ p_n); for the totals of a patch that gives
    // |fx| <= μ·Σ p_n dA. With the curved reference, fn is the sum of pressures projected on
    // the reference normal (local normals here within 8° of it, cos >= 0.99), hence 1 %.
    EXPECT_LE(std::fabs(p.fx), 0.3 * p.fn * 1.01 + 1e-9) << what;
  }
}

TEST(Stability, ManchesterLateralSweepBothMethods) {
  for (ReferenceSurface ref : {ReferenceSurface::kPlanar, ReferenceSurface::kCurved}) {
    Case c = Manchester(ref);
    for (double y = 0.0; y <= 10.0; y += 1.0) {
      c.state.y = y;
      ExpectHealthy(SolveWheelRail(c), 10000.0, "y = " + std::to_string(y));
    }
  }
}

TEST(Stability, LoadsFromOneNewtonToThreeHundredKilonewtons) {
  Case c = Manchester(ReferenceSurface::kCurved);
  c.state.y = 0.0;
  for (double fz : {1.0, 100.0, 1e4, 1e5, 3e5}) {
    c.state.fz = fz;
    ExpectHealthy(SolveWheelRail(c), fz, "fz = " + std::to_string(fz));
  }
}

TEST(Stability, YawAndSpinToFullSlip) {
  Case c = Manchester(ReferenceSurface::kCurved);
  c.state.y = 4.0;
  for (double yaw : {-0.03, -0.01, 0.01, 0.03}) {
    c.state.yaw = yaw;
    ExpectHealthy(SolveWheelRail(c), 1e4, "yaw = " + std::to_string(yaw));
  }
  c.state.yaw = 0.0;
  double previous = 0.0;
  for (double spin : {0.001, 0.005, 0.02, 0.05}) {
    c.state.omega = OmegaFromSpin(spin, c.state.velocity, c.wheelset.nominal_radius);
    const WheelRailResult r = SolveWheelRail(c);
    ExpectHealthy(r, 1e4, "spin = " + std::to_string(spin));
    // The longitudinal force grows with spin towards saturation at μ·F_z.
    EXPECT_GE(std::fabs(r.force_T(0)), previous - 1e-6);
    previous = std::fabs(r.force_T(0));
  }
  EXPECT_GT(previous, 0.95 * 0.3 * 1e4);  // at 5 % spin the patch slides almost entirely
}

// Flange contact with roll, yaw and spin: here the tangential part of FZ(TR) (fs·sin δ at
// ~70°) changes with z as much as the normal part; the vertical force iteration must still
// meet fz (it once stalled at up to 8 N off on the Manchester table, points at y >= 5.5 mm).
TEST(Stability, FlangeContactWithRollYawSpinMeetsFz) {
  Case c = Manchester(ReferenceSurface::kCurved);
  c.state.y = 7.0;
  c.state.roll = -0.002;
  c.state.yaw = -0.01;
  c.state.omega = OmegaFromSpin(-0.01, c.state.velocity, c.wheelset.nominal_radius);
  ExpectHealthy(SolveWheelRail(c), 1e4, "y = 7, roll, yaw, spin");
}

TEST(Stability, FrictionlessSweepHasNoTangentialForce) {
  Case c = Manchester(ReferenceSurface::kCurved);
  c.friction = Friction::Constant(0.0);
  for (double y : {0.0, 5.0, 8.0}) {
    c.state.y = y;
    const WheelRailResult r = SolveWheelRail(c);
    ExpectHealthy(r, 1e4, "mu = 0, y = " + std::to_string(y));
    for (const PatchResult& p : r.patches) EXPECT_EQ(p.fx, 0.0);
  }
}

}  // namespace
}  // namespace wrc
