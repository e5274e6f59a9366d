// The table outputs of a solve: every output of the registry has its value, taken from the
// result's own fields, and the registry's rule at no contact.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "wrc/core/case.h"
#include "wrc/core/profile_placement.h"
#include "wrc/core/wheelrail.h"
#include "wrc/quantities.h"

namespace wrc {
namespace {

// A two-patch result with distinct numbers in every field an output reads.
WheelRailResult TwoPatches() {
  WheelRailResult r;
  r.force_T = {1.0, 2.0, 3.0};
  r.moment_T = {4.0, 5.0, 6.0};
  r.force_W = {7.0, 8.0, 9.0};
  r.z = 0.25;
  r.velocity = 2.0e4;
  r.has_force_location = true;
  r.contact_y = -3.5;
  r.contact_angle = 0.02;
  PatchResult a, b;
  a.fn = 2.0e4, a.fx = 100.0, a.fs = -50.0, a.pmax = 900.0, a.t_gamma_slip = 3.0;
  a.cksi = -1e-3, a.ceta = 2e-3, a.cphi = 1e-5, a.mn = 40.0;
  a.fi_surf_rail = -0.2, a.fi_surf_wheel = -0.4;
  b.fn = 5.0e4, b.fx = 300.0, b.fs = 20.0, b.pmax = 1200.0, b.t_gamma_slip = 4.0;
  b.fi_surf_rail = 0.1;  // the wheel's index unknown on this patch
  r.patches = {a, b};
  return r;
}

TEST(Outputs, EveryRegistryOutputHasItsValue) {
  const WheelRailResult r = TwoPatches();
  for (const OutputQuantity& q : kOutputQuantities) {
    EXPECT_NO_THROW(OutputValue(q.name, r)) << q.name;
  }
  EXPECT_EQ(OutputValue("fx", r), 1.0);
  EXPECT_EQ(OutputValue("fy", r), 2.0);
  EXPECT_EQ(OutputValue("mz", r), 6.0);
  EXPECT_EQ(OutputValue("fz_ws", r), 9.0);
  EXPECT_EQ(OutputValue("n_patches", r), 2.0);
  EXPECT_EQ(OutputValue("pmax", r), 1200.0);
  EXPECT_EQ(OutputValue("z", r), 0.25);
  EXPECT_EQ(OutputValue("contact_y", r), -3.5);
  EXPECT_EQ(OutputValue("t_gamma_slip", r), 7.0);
  EXPECT_DOUBLE_EQ(OutputValue("frictional_power", r), -1e-3 * 2.0e4 * 7.0);
  EXPECT_DOUBLE_EQ(OutputValue("t_gamma", r), TGamma(r.patches[0]) + TGamma(r.patches[1]));
  EXPECT_EQ(OutputValue("fi_surf_rail", r), 0.1);    // the patch furthest beyond the limit
  EXPECT_EQ(OutputValue("fi_surf_wheel", r), -0.4);  // the one patch that has it
}

TEST(Outputs, NoContactFollowsTheRegistry) {
  WheelRailResult r;
  r.status = SolverStatus::kNoContact;
  r.z = -1.5;  // where a prescribed-fz solve found no contact
  for (const OutputQuantity& q : kOutputQuantities) {
    const double value = OutputValue(q.name, r);
    switch (q.at_no_contact) {
      case AtNoContact::kZero:
        EXPECT_EQ(value, 0.0) << q.name;
        break;
      case AtNoContact::kUndefined:
        EXPECT_TRUE(std::isnan(value)) << q.name;
        break;
      case AtNoContact::kSolved:
        EXPECT_EQ(value, q.name == "z" ? -1.5 : 0.0) << q.name;
        break;
    }
  }
}

TEST(Outputs, UnknownNameIsABug) {
  EXPECT_THROW(OutputValue("fq", TwoPatches()), std::logic_error);
}

TEST(Outputs, LocationFallsBackToTheMainPatch) {
  WheelRailResult r = TwoPatches();
  r.has_force_location = false;
  r.patches[1].reference_rail = {12.0, 0.1};
  r.patches[1].contact_angle = 0.5;
  EXPECT_EQ(OutputValue("contact_y", r), 12.0);
  EXPECT_EQ(OutputValue("contact_angle", r), 0.5);
}

// The wheel's side of the contact geometry as a table stores it (rolling_radius,
// wheel_contact_y) against the rigid contact of the undeformed profiles (RigidContactAt, an
// independent search along the rail). At 500 N on the Manchester pair's tread the patch is a few
// millimetres wide and nearly symmetric about the first touch: its reference lies within
// 0.1 mm of it laterally (measured 0.007–0.02 mm), and its radius within 0.01 mm (measured
// 3–4 µm, the elastic approach's share).
TEST(Outputs, WheelContactAgreesWithTheRigidGeometry) {
  Case c = LoadCase(std::string(WRC_TEST_DATA_DIR) +
                    "/reference/cases/mbench_curved/mbench_curved_y4.toml");
  c.state.fz = 500.0;
  c.grid.dx = c.grid.ds = 0.5;  // the reference point, not the field, is compared
  for (const double y : {-2.0, 0.0, 2.0, 4.0}) {
    c.state.y = y;
    const WheelRailResult r = SolveWheelRail(c);
    ASSERT_EQ(r.status, SolverStatus::kConverged) << y;
    ASSERT_EQ(r.patches.size(), 1u) << y;
    const RigidContact rigid = RigidContactAt(c, {y, 0.0, 0.0, 0.0}, 0.01);
    ASSERT_TRUE(rigid.found) << y;
    EXPECT_NEAR(OutputValue("rolling_radius", r), rigid.rolling_radius, 0.01) << y;
    EXPECT_NEAR(OutputValue("wheel_contact_y", r), rigid.wheel_y, 0.1) << y;
  }
}

}  // namespace
}  // namespace wrc
