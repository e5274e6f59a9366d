// The runtime's wheelset API against direct solves: a table made for the right wheel serves the
// left one as its mirror image (checked against `side = "left"` solves at table nodes), and a
// table made at 20 m/s serves 40 m/s when the velocities scale with the speed.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "runtime/hdf5/hdf5.h"
#include "runtime/hdf5/seal.h"
#include "tests/generator/generator_test_util.h"
#include "wrc/core/scene.h"
#include "wrc/core/wheelrail.h"
#include "wrc/generator/generator.h"
#include "wrc/runtime.hpp"

namespace wrc {
namespace {

using test::ScratchDir;

constexpr double kV0 = 20000.0;  // mm/s, the table's speed
constexpr double kRadius = 460.0;

// Generates `scene` into `path` on two threads; each node one cold solve (no warm start), as
// the direct solves the tests compare with. Returns the path.
std::string GenerateCold(const Scene& scene, const std::filesystem::path& path) {
  GenerateOptions options;
  options.output = path;
  options.threads = 2;
  options.progress = ProgressMode::kOff;
  options.warm_start = false;
  options.mpi = MpiMode::kOff;
  EXPECT_TRUE(GenerateTable(scene, options).complete);
  return path.string();
}

// y, yaw and vy symmetric about 0, so that the mirror image of a node is a node; vy = 200 is a
// node too, so that reading 40 m/s unscaled would give another node's forces.
std::string WheelsetScene(const std::string& side = "right") {
  return "[wheelset]\nside = \"" + side + "\"\n" +
         test::TinyScene(
             "axes = [\"y\", \"yaw\", \"vy\", \"spin\"]\n"
             "y = [-2.0, 0.0, 2.0]\n"
             "yaw = [-0.002, 0.002]\n"
             "vy = [-200.0, -100.0, 100.0, 200.0]\n"
             "spin = [0.0, 0.002]\n"
             "outputs = [\"fx\", \"fy\", \"fz\", \"mx\", \"my\", \"mz\", \"contact_y\", "
             "\"contact_angle\"]",
             "fz = 10000.0\nvelocity = 20000.0");
}

// One solve of the table's scene; side and speed may differ from the table's.
WheelRailResult Solve(const Scene& scene, const std::vector<double>& point, WheelSide side,
                      double velocity) {
  Case c = CaseAtPoint(scene, point);
  c.wheelset.side = side;
  const double scale = velocity / c.state.velocity;
  c.state.velocity = velocity;
  c.state.vy *= scale;
  c.state.omega = OmegaFromSpin(point[3], velocity, kRadius);
  return SolveWheelRail(c);
}

// Forces agree to the solver's tolerance: 1e-6 of the vertical load (0.01 N), moments over a
// 1 mm lever (10 N·mm) — the table's own solves use warm starts, the direct ones do not.
void ExpectSameContact(const wrc_wheel_contact& wheel, const WheelRailResult& solve) {
  constexpr double kForce = 1e-2, kMoment = 10.0;
  ASSERT_GT(solve.force_T(2), 9000.0);  // in contact, carrying the load
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(wheel.force[i], solve.force_T(i), kForce) << "force " << i;
    EXPECT_NEAR(wheel.moment[i], solve.moment_T(i), kMoment) << "moment " << i;
  }
  EXPECT_NEAR(wheel.contact_y, solve.contact_y, 1e-6);
  EXPECT_NEAR(wheel.contact_angle, solve.contact_angle, 1e-9);
}

class WheelsetTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new ScratchDir("wheelset");
    scene_ = new Scene(LoadScene(test::WriteFile(*dir_ / "scene.toml", WheelsetScene())));
    table_ = new Table(Generate(*scene_, "right.h5"));
  }
  static std::string Generate(const Scene& scene, const std::string& name) {
    return GenerateCold(scene, *dir_ / name);
  }
  static void TearDownTestSuite() {
    delete table_;
    delete scene_;
    delete dir_;
  }

  // The state at node (y, yaw, vy, spin) of the table, at speed `velocity` with vy scaled.
  static WheelsetTable::State StateAt(const std::vector<double>& node, double velocity) {
    WheelsetTable::State state;
    state.y = node[0];
    state.yaw = node[1];
    state.vy = node[2] * velocity / kV0;
    state.velocity = velocity;
    state.omega = OmegaFromSpin(node[3], velocity, kRadius);
    return state;
  }

  // Every node of the table, as (y, yaw, vy, spin).
  static std::vector<std::vector<double>> Nodes() {
    std::vector<std::vector<double>> nodes;
    for (const double y : scene_->axes[0].values) {
      for (const double yaw : scene_->axes[1].values) {
        for (const double vy : scene_->axes[2].values) {
          for (const double spin : scene_->axes[3].values) nodes.push_back({y, yaw, vy, spin});
        }
      }
    }
    return nodes;
  }
  static std::string Describe(const std::vector<double>& node) {
    return "y " + std::to_string(node[0]) + " yaw " + std::to_string(node[1]) + " vy " +
           std::to_string(node[2]) + " spin " + std::to_string(node[3]);
  }

  static inline ScratchDir* dir_ = nullptr;
  static inline Scene* scene_ = nullptr;
  static inline Table* table_ = nullptr;
};

// At every node the right wheel reads the node and the left wheel its mirror image, which is a
// node too: both must be the direct solves of their sides.
TEST_F(WheelsetTest, BothWheelsEqualDirectSolvesAtNodes) {
  const WheelsetTable wheelset(*table_);
  int asymmetric = 0;
  for (const std::vector<double>& node : Nodes()) {
    SCOPED_TRACE(Describe(node));
    int flags = -1;
    const wrc_wheelset_result result = wheelset.eval(StateAt(node, kV0), &flags);
    EXPECT_EQ(flags, 0);
    ExpectSameContact(result.wheel[WRC_RIGHT], Solve(*scene_, node, WheelSide::kRight, kV0));
    ExpectSameContact(result.wheel[WRC_LEFT], Solve(*scene_, node, WheelSide::kLeft, kV0));
    const double fy_left = result.wheel[WRC_LEFT].force[1];
    asymmetric += std::fabs(fy_left - result.wheel[WRC_RIGHT].force[1]) > 1.0;
  }
  // The mirror is not trivial: away from the symmetric pose the two wheels differ.
  EXPECT_GT(asymmetric, 30);
}

// At 40 m/s the velocities scale to the table's nodes at 20 m/s (vy 200 mm/s → 100 mm/s).
TEST_F(WheelsetTest, TableAtTwentyServesForty) {
  const WheelsetTable wheelset(*table_);
  const double v = 2.0 * kV0;
  for (const std::vector<double>& node : Nodes()) {
    if (std::fabs(node[2]) > 100.0) continue;  // 400 mm/s at 40 m/s: beyond the axis
    SCOPED_TRACE(Describe(node));
    int flags = -1;
    const wrc_wheelset_result result = wheelset.eval(StateAt(node, v), &flags);
    EXPECT_EQ(flags, 0);
    ExpectSameContact(result.wheel[WRC_RIGHT], Solve(*scene_, node, WheelSide::kRight, v));
    ExpectSameContact(result.wheel[WRC_LEFT], Solve(*scene_, node, WheelSide::kLeft, v));
  }
}

// A table made for the left wheel serves the right one mirrored, just as the right table serves
// the left: both wheelsets agree.
TEST_F(WheelsetTest, LeftTableServesBothSides) {
  const Scene left_scene = LoadScene(test::WriteFile(*dir_ / "left.toml", WheelsetScene("left")));
  const Table left_table(Generate(left_scene, "left.h5"));
  const WheelsetTable from_left(left_table), from_right(*table_);
  const WheelsetTable both(left_table, *table_);
  const wrc_wheelset_state state = StateAt({2.0, 0.002, 100.0, 0.002}, kV0);
  const wrc_wheelset_result a = from_left.eval(state), b = from_right.eval(state);
  const wrc_wheelset_result c = both.eval(state);
  for (int side = 0; side < 2; ++side) {
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(a.wheel[side].force[i], b.wheel[side].force[i], 1e-2) << side << " " << i;
      EXPECT_NEAR(a.wheel[side].moment[i], b.wheel[side].moment[i], 10.0) << side << " " << i;
      EXPECT_NEAR(c.wheel[side].force[i], b.wheel[side].force[i], 1e-2) << side << " " << i;
    }
  }
}

TEST_F(WheelsetTest, TotalsAreTheReactionsMovedToTheTrackOrigin) {
  WheelsetTable wheelset(*table_);
  const wrc_wheelset_state state = StateAt({2.0, 0.002, 100.0, 0.002}, kV0);
  wrc_wheelset_result result = wheelset.eval(state);
  EXPECT_TRUE(std::isnan(result.moment[0]));  // rail origins not set
  wheelset.set_rail_origin(WRC_LEFT, -750.0, 0.0);
  wheelset.set_rail_origin(WRC_RIGHT, 750.0, 0.0);
  result = wheelset.eval(state);
  const wrc_wheel_contact& l = result.wheel[WRC_LEFT];
  const wrc_wheel_contact& r = result.wheel[WRC_RIGHT];
  for (int i = 0; i < 3; ++i) EXPECT_EQ(result.force[i], -(l.force[i] + r.force[i]));
  // About x: each rail's moment plus y·fz of its force, the lever 750 mm either side.
  EXPECT_NEAR(result.moment[0],
              -(l.moment[0] - 750.0 * l.force[2] + r.moment[0] + 750.0 * r.force[2]), 1e-6);
  EXPECT_NEAR(result.moment[2],
              -(l.moment[2] + 750.0 * l.force[0] + r.moment[2] - 750.0 * r.force[0]), 1e-6);
}

TEST_F(WheelsetTest, FlagsSayWhereTheTableCannotServe) {
  const WheelsetTable wheelset(*table_);
  WheelsetTable::State state = StateAt({1.0, 0.0, 0.0, 0.001}, kV0);
  EXPECT_EQ(wheelset.eval(state).wheel[WRC_RIGHT].flags, 0);
  state.vroll = 0.01;  // no vroll axis, the table was made at vroll = 0
  EXPECT_EQ(wheelset.eval(state).wheel[WRC_RIGHT].flags, WRC_FLAG_FIXED);
  state.vroll = 0.0;
  state.y = 3.0;  // beyond the y axis for the right wheel; the left one reads y = -3
  int flags = 0;
  const wrc_wheelset_result result = wheelset.eval(state, &flags);
  EXPECT_EQ(result.wheel[WRC_RIGHT].flags, WRC_FLAG_CLAMPED);
  EXPECT_EQ(result.wheel[WRC_LEFT].flags, WRC_FLAG_CLAMPED);
  EXPECT_EQ(flags, WRC_FLAG_CLAMPED);
  state.velocity = 0.0;
  wrc_wheelset_result ignored;
  EXPECT_EQ(wheelset.try_eval(state, ignored), WRC_ERR_INVALID_ARGUMENT);
  state.velocity = kV0;
  state.yaw = NAN;
  EXPECT_EQ(wheelset.try_eval(state, ignored), WRC_ERR_NAN_INPUT);
}

// The fixed state is stored typed: the scene's own values, NaN for what the axes vary.
TEST_F(WheelsetTest, TheFixedStateIsStoredTyped) {
  EXPECT_EQ(table_->number_attribute("wheelset_velocity"), kV0);
  EXPECT_EQ(table_->number_attribute("wheelset_nominal_radius"), kRadius);
  EXPECT_EQ(table_->number_attribute("wheel_profile_offset"), 0.5 * 1360.0 + 70.0);  // defaults
  EXPECT_EQ(table_->attribute("wheelset_side"), "right");
  EXPECT_EQ(table_->number_attribute("fixed_fz"), 10000.0);
  EXPECT_EQ(table_->number_attribute("fixed_roll"), 0.0);
  EXPECT_EQ(table_->number_attribute("fixed_mu"), 0.3);  // the solver's default friction
  for (const char* varied : {"fixed_y", "fixed_yaw", "fixed_vy", "fixed_spin", "fixed_omega",
                             "fixed_z", "fixed_y_wheel"}) {
    EXPECT_TRUE(std::isnan(table_->number_attribute(varied))) << varied;
  }
  for (const StateQuantity& q : kStateQuantities) {
    EXPECT_NO_THROW(table_->number_attribute("fixed_" + std::string(q.name))) << q.name;
  }
}

// A table written before the typed fixed state (the same table without those attributes) is
// read from its scene text; both give the same contact, bit for bit, flags included.
TEST_F(WheelsetTest, TablesWithoutTheTypedStateReadTheirScene) {
  const std::filesystem::path legacy = *dir_ / "legacy.h5";
  std::filesystem::copy_file(*dir_ / "right.h5", legacy,
                             std::filesystem::copy_options::overwrite_existing);
  {
    const auto lock = h5::LibraryLock();
    h5::File file = h5::File::Open(legacy.string(), h5::File::Mode::kReadWrite);
    for (const std::string& name : file.AttributeNames()) {
      if (name.rfind("fixed_", 0) == 0 || name.rfind("wheelset_", 0) == 0 ||
          name == "wheel_profile_offset") {
        file.RemoveAttribute(name);
      }
    }
  }
  h5::SealFile(legacy.string());
  const Table old_table(legacy.string());
  EXPECT_THROW(old_table.number_attribute("wheelset_velocity"), TableError);
  const WheelsetTable typed(*table_), from_scene(old_table);
  for (const std::vector<double>& at :
       {std::vector<double>{0.7, 0.001, 50.0, 0.0013}, {-1.5, -0.0015, -150.0, 0.0}}) {
    WheelsetTable::State state = StateAt(at, kV0);
    for (const double vroll : {0.0, 0.01}) {  // 0.01: the table's fixed vroll is 0, flagged
      state.vroll = vroll;
      const wrc_wheelset_result a = typed.eval(state), b = from_scene.eval(state);
      for (const int side : {WRC_LEFT, WRC_RIGHT}) {
        for (int i = 0; i < 3; ++i) EXPECT_EQ(a.wheel[side].force[i], b.wheel[side].force[i]);
        EXPECT_EQ(a.wheel[side].contact_y, b.wheel[side].contact_y);
        EXPECT_EQ(a.wheel[side].flags, b.wheel[side].flags);
      }
    }
  }
}

}  // namespace
}  // namespace wrc

namespace wrc {
namespace {

// A table over y_wheel = y − r0·roll and roll: the wheelset API takes the pose (y, roll) and
// the wheel must read its own y_wheel, checked at every node against direct solves.
TEST(WheelsetYWheel, PoseMapsToTheWheelsLateralPosition) {
  ScratchDir dir("wheelset_y_wheel");
  const Scene scene = LoadScene(test::WriteFile(
      dir / "scene.toml",
      test::TinyScene("axes = [\"y_wheel\", \"roll\"]\ny_wheel = [-2.0, 0.0, 2.0]\n"
                      "roll = [-0.002, 0.002]\noutputs = [\"fx\", \"fy\", \"fz\", \"mx\", "
                      "\"my\", \"mz\", \"contact_y\", \"contact_angle\"]",
                      "fz = 10000.0\nvelocity = 20000.0")));
  const Table table(GenerateCold(scene, dir / "table.h5"));
  const WheelsetTable wheelset(table);
  for (const double y_wheel : scene.axes[0].values) {
    for (const double roll : scene.axes[1].values) {
      SCOPED_TRACE("y_wheel " + std::to_string(y_wheel) + " roll " + std::to_string(roll));
      WheelsetTable::State state;
      state.y = y_wheel + kRadius * roll;
      state.roll = roll;
      state.velocity = kV0;
      state.omega = OmegaFromSpin(0.0, kV0, kRadius);
      int flags = -1;
      const wrc_wheelset_result result = wheelset.eval(state, &flags);
      EXPECT_EQ(flags, 0);
      const Case c = CaseAtPoint(scene, {y_wheel, roll});
      EXPECT_DOUBLE_EQ(c.state.y, state.y);
      ExpectSameContact(result.wheel[WRC_RIGHT], SolveWheelRail(c));
    }
  }
}

}  // namespace
}  // namespace wrc

namespace wrc {
namespace {

// A table without velocity axes serves a state with vy, vroll and vyaw through the pose of
// equal creepage (yaw − vy/V + vroll·r0/V, spin + vyaw·y_c/V). The reference is the solver's
// own kinematics of the same state; they differ by the 1 mrad of yaw geometry the fold leaves
// out and the lever of the yaw rate (the profile origin, not the contact point): 32 N here,
// while the velocities move the forces by more than 1.3 kN.
TEST(WheelsetVelocities, FoldIntoYawAndSpinWhereTheTableHasNoAxis) {
  ScratchDir dir("wheelset_fold");
  const Scene scene = LoadScene(test::WriteFile(
      dir / "scene.toml",
      test::TinyScene("axes = [\"y\", \"yaw\", \"spin\"]\ny = [-2.0, 2.0]\n"
                      "yaw = [-0.002, 0.002]\nspin = [0.0, 0.002]\noutputs = [\"fx\", \"fy\", "
                      "\"fz\", \"mx\", \"my\", \"mz\", \"contact_y\", \"contact_angle\"]",
                      "fz = 10000.0\nvelocity = 20000.0")));
  const Table table(GenerateCold(scene, dir / "table.h5"));
  const WheelsetTable wheelset(table);

  // Folded: yaw 0.002 and spin 0.001 ± 0.001 (right +, left −) are nodes on both sides.
  const double lever = 0.5 * 1360.0 + 70.0;  // the scene's default wheelset geometry
  WheelsetTable::State state;
  state.y = 2.0;
  state.vy = 20.0;  // lateral creepage 0.001
  state.vroll = 0.01;
  state.yaw = 0.002 + state.vy / kV0 - state.vroll * kRadius / kV0;
  state.vyaw = 0.001 * kV0 / lever;
  state.velocity = kV0;
  state.omega = OmegaFromSpin(0.001, kV0, kRadius);
  int flags = -1;
  const wrc_wheelset_result result = wheelset.eval(state, &flags);
  EXPECT_EQ(flags, 0);  // nothing fixed, nothing clamped

  for (const WheelSide side : {WheelSide::kRight, WheelSide::kLeft}) {
    SCOPED_TRACE(side == WheelSide::kRight ? "right" : "left");
    Case c = CaseAtPoint(scene, {2.0, 0.0, 0.0});
    c.wheelset.side = side;
    c.state.yaw = state.yaw;
    c.state.omega = state.omega;
    const WheelRailResult rolling = SolveWheelRail(c);
    c.state.vy = state.vy;
    c.state.vroll = state.vroll;
    c.state.vyaw = state.vyaw;
    const WheelRailResult moving = SolveWheelRail(c);
    const wrc_wheel_contact& wheel = result.wheel[side == WheelSide::kRight ? WRC_RIGHT : WRC_LEFT];
    constexpr double kTolerance = 50.0;  // N, 0.5 % of the 10 kN load
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(wheel.force[i], moving.force_T(i), kTolerance) << i;
    // The velocities matter: vyaw turns fx around on each side, vy moves fy.
    EXPECT_GT(
        std::hypot(moving.force_T(0) - rolling.force_T(0), moving.force_T(1) - rolling.force_T(1)),
        10.0 * kTolerance);
  }
}

}  // namespace
}  // namespace wrc
