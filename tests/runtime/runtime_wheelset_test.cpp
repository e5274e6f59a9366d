// The wheelset API on a synthetic table whose values are known in closed form: the sign
// conventions of the mirrored wheel, the speed-independent velocities, the flags, threads. (The
// agreement with real solves of both sides is tests/generator/wheelset_test.cpp.)

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "runtime/scene_values.h"
#include "tests/runtime/wheelset_table.h"
#include "wrc/runtime.hpp"

namespace {

using wrc::WheelsetTable;
using wrc::test::WheelsetFunction;

constexpr double kRadius = 460.0, kV0 = 20000.0;
// Sign of fx fy fz mx my mz contact_y contact_angle t_gamma under the mirror image in the x–z
// plane.
constexpr double kOutputMirror[9] = {1, -1, 1, -1, 1, -1, -1, -1, 1};
constexpr int kOutputs = 9;
// Exact up to the rounding of multilinear weights.
constexpr double kTolerance = 1e-9;

class RuntimeWheelset : public ::testing::Test {
 protected:
  RuntimeWheelset() : scratch_("wheelset"), table_((Write(scratch_.path()), scratch_.path())) {}
  static void Write(const std::string& path) { wrc::test::WriteWheelsetTable(path); }

  static WheelsetTable::State State(double y, double roll, double yaw, double spin, double v) {
    WheelsetTable::State s;
    s.y = y;
    s.roll = roll;
    s.yaw = yaw;
    s.velocity = v;
    s.omega = -(v / kRadius) * (1.0 + spin);
    return s;
  }
  // Output k of one wheel as result fields.
  static double Output(const wrc_wheel_contact& c, int k) {
    if (k < 3) return c.force[k];
    if (k < 6) return c.moment[k - 3];
    return k == 6 ? c.contact_y : k == 7 ? c.contact_angle : c.t_gamma;
  }

  wrc::test::ScratchFile scratch_;
  wrc::Table table_;
};

TEST_F(RuntimeWheelset, RightReadsTheTableLeftItsMirrorImage) {
  const WheelsetTable wheelset(table_);
  const double y = 3.3, roll = 0.0011, yaw = -0.004, spin = 0.0025;
  int flags = -1;
  const wrc_wheelset_result r = wheelset.eval(State(y, roll, yaw, spin, kV0), &flags);
  EXPECT_EQ(flags, 0);
  for (int k = 0; k < kOutputs; ++k) {
    const double right = WheelsetFunction(k, {y, roll, yaw, spin});
    const double left = kOutputMirror[k] * WheelsetFunction(k, {-y, -roll, -yaw, spin});
    EXPECT_NEAR(Output(r.wheel[WRC_RIGHT], k), right, kTolerance * std::fabs(right)) << k;
    EXPECT_NEAR(Output(r.wheel[WRC_LEFT], k), left, kTolerance * std::fabs(left)) << k;
  }
}

// spin is relative to free rolling, so any speed reads the same table point.
TEST_F(RuntimeWheelset, SpinFromOmegaIsIndependentOfSpeed) {
  const WheelsetTable wheelset(table_);
  const wrc_wheelset_result slow = wheelset.eval(State(1.0, 0.0, 0.002, -0.006, kV0));
  const wrc_wheelset_result fast = wheelset.eval(State(1.0, 0.0, 0.002, -0.006, 3.7 * kV0));
  for (int side = 0; side < 2; ++side) {
    for (int k = 0; k < kOutputs; ++k) {
      EXPECT_NEAR(Output(fast.wheel[side], k), Output(slow.wheel[side], k), 1e-9) << k;
    }
  }
}

TEST_F(RuntimeWheelset, QuantitiesWithoutAxisAreChecked) {
  const WheelsetTable wheelset(table_);
  WheelsetTable::State s = State(1.0, 0.0, 0.002, 0.0, kV0);
  EXPECT_EQ(wheelset.eval(s).wheel[WRC_RIGHT].flags, 0);
  s.fz[WRC_RIGHT] = 10000.0;  // the table's load
  EXPECT_EQ(wheelset.eval(s).wheel[WRC_RIGHT].flags, 0);
  s.fz[WRC_LEFT] = 12000.0;  // another load: the table cannot serve it
  const wrc_wheelset_result r = wheelset.eval(s);
  EXPECT_EQ(r.wheel[WRC_LEFT].flags, WRC_FLAG_FIXED);
  EXPECT_EQ(r.wheel[WRC_RIGHT].flags, 0);
  s.fz[WRC_LEFT] = NAN;
  s.roll = 0.01;  // beyond the roll axis
  int flags = 0;
  wheelset.eval(s, &flags);
  EXPECT_EQ(flags, WRC_FLAG_CLAMPED);
}

// An infinite value would compare equal to no fixed value and pass unflagged, or be clamped to
// the table: refused, naming the field. NaN fz and mu mean "not known" and stay allowed.
TEST_F(RuntimeWheelset, InfiniteStateValuesAreRefused) {
  const WheelsetTable wheelset(table_);
  const WheelsetTable::State ok = State(1.0, 0.0, 0.002, 0.0, kV0);
  wrc_wheelset_result r;
  const std::vector<std::pair<double WheelsetTable::State::*, const char*>> pose = {
      {&WheelsetTable::State::y, "state.y"},
      {&WheelsetTable::State::omega, "state.omega"},
      {&WheelsetTable::State::vyaw, "state.vyaw"},
      {&WheelsetTable::State::vy, "state.vy"},
      {&WheelsetTable::State::roll, "state.roll"}};
  for (const auto& [field, name] : pose) {
    for (const double bad : {INFINITY, -INFINITY}) {
      WheelsetTable::State s = ok;
      s.*field = bad;
      EXPECT_EQ(wheelset.try_eval(s, r), WRC_ERR_INVALID_ARGUMENT) << name;
      EXPECT_NE(std::string(wrc_last_error()).find(name), std::string::npos) << wrc_last_error();
    }
  }
  for (int side = 0; side < 2; ++side) {
    WheelsetTable::State s = ok;
    s.fz[side] = INFINITY;
    EXPECT_EQ(wheelset.try_eval(s, r), WRC_ERR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(wrc_last_error()).find("fz[" + std::to_string(side) + "]"),
              std::string::npos);
    s = ok;
    s.mu[side] = -INFINITY;
    EXPECT_EQ(wheelset.try_eval(s, r), WRC_ERR_INVALID_ARGUMENT);
  }
  EXPECT_GE(wheelset.try_eval(ok, r), 0);  // NaN fz and mu: not known
  // The velocity within the case file's bounds: 1e-200 mm/s made the solver's creepages
  // underflow, and the runtime's state takes the same bounds.
  for (const double bad :
       {0.0, -kV0, 1e-200, 0.999 * WRC_VELOCITY_MIN, 1.001 * WRC_VELOCITY_MAX, double{INFINITY}}) {
    WheelsetTable::State s = ok;
    s.velocity = bad;
    EXPECT_EQ(wheelset.try_eval(s, r), WRC_ERR_INVALID_ARGUMENT) << bad;
    EXPECT_NE(std::string(wrc_last_error()).find("velocity"), std::string::npos);
  }
  for (const double fine : {WRC_VELOCITY_MIN, WRC_VELOCITY_MAX}) {
    WheelsetTable::State s = ok;
    s.velocity = fine;
    EXPECT_GE(wheelset.try_eval(s, r), 0) << fine << ": " << wrc_last_error();
  }
}

// Without vy, vroll and vyaw axes the velocities enter as the yaw and spin of equal creepage:
// yaw − vy/V + vroll·r0/V, and spin + vyaw·y_c/V with y_c = ±(1360/2 + 70) mm, the default
// wheelset geometry (the synthetic table is affine, so the comparison is exact).
TEST_F(RuntimeWheelset, VelocitiesWithoutAxisFoldIntoYawAndSpin) {
  const WheelsetTable wheelset(table_);
  const double v = 2.0 * kV0, lever = 750.0;
  WheelsetTable::State s = State(1.0, 0.001, 0.002, 0.001, v);
  s.vy = 30.0;
  s.vroll = 0.02;
  s.vyaw = 0.05;
  int flags = -1;
  const wrc_wheelset_result r = wheelset.eval(s, &flags);
  EXPECT_EQ(flags, 0);
  const double yaw = 0.002 - s.vy / v + s.vroll * kRadius / v;
  const double d_spin = s.vyaw * lever / v;
  for (int k = 0; k < kOutputs; ++k) {
    const double right = WheelsetFunction(k, {1.0, 0.001, yaw, 0.001 + d_spin});
    const double left =
        kOutputMirror[k] * WheelsetFunction(k, {-1.0, -0.001, -yaw, 0.001 - d_spin});
    EXPECT_NEAR(Output(r.wheel[WRC_RIGHT], k), right, kTolerance * std::fabs(right)) << k;
    EXPECT_NEAR(Output(r.wheel[WRC_LEFT], k), left, kTolerance * std::fabs(left)) << k;
  }
}

TEST_F(RuntimeWheelset, RejectsWhatItCannotRead) {
  wrc_wheelset* handle = nullptr;
  EXPECT_EQ(wrc_wheelset_create(nullptr, nullptr, &handle), WRC_ERR_NULL_POINTER);
  wrc::test::TableContent content;
  content.axes = {{"y", {0.0, 1.0}}, {"speed", {1.0, 2.0}}};
  content.outputs = {"fy"};
  content.function = [](int, const std::vector<double>& x) { return x[0]; };
  content.scene = "[state]\nvelocity = 1000.0\n";
  wrc::test::ScratchFile other("wheelset-other");
  wrc::test::WriteTable(other.path(), content);
  const wrc::Table unknown_axis(other.path());
  EXPECT_EQ(wrc_wheelset_create(unknown_axis.get(), nullptr, &handle), WRC_ERR_FORMAT);
  content.axes[1].name = "yaw";
  content.scene = "[state]\nfz = 1.0\n";  // no velocity
  wrc::test::WriteTable(other.path(), content);
  const wrc::Table no_velocity(other.path());
  EXPECT_EQ(wrc_wheelset_create(no_velocity.get(), nullptr, &handle), WRC_ERR_FORMAT);
  EXPECT_EQ(handle, nullptr);
}

TEST_F(RuntimeWheelset, ConcurrentEvaluationMatchesSerial) {
  const WheelsetTable wheelset(table_);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.2, 1.2);
  std::vector<WheelsetTable::State> states(2000);
  for (auto& s : states) {
    s = State(10.0 * unit(random), 0.002 * unit(random), 0.01 * unit(random), 0.01 * unit(random),
              kV0 * (2.0 + unit(random)));
  }
  std::vector<wrc_wheelset_result> serial(states.size());
  for (std::size_t i = 0; i < states.size(); ++i) wheelset.eval(states[i], serial[i]);
  int mismatches[4] = {0, 0, 0, 0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (std::size_t i = 0; i < states.size(); ++i) {
        const std::size_t j = (i + 500 * t) % states.size();
        wrc_wheelset_result r;
        wheelset.eval(states[j], r);
        for (int side = 0; side < 2; ++side) {
          for (int k = 0; k < 3; ++k) {
            mismatches[t] += r.wheel[side].force[k] != serial[j].wheel[side].force[k];
          }
        }
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (int t = 0; t < 4; ++t) EXPECT_EQ(mismatches[t], 0) << "thread " << t;
}

TEST(RuntimeSceneValues, ReadsKeysOfTheirSection) {
  const char* scene =
      "velocity = 1.0  # not in a section\n"
      "[state]\n  velocity = 2_000.5 # mm/s\nname = \"a # b\"  # comment\nbad = 1.0x\n"
      "[[array]]\nvelocity = 3.0\n[wheelset]\nside = \"left\"\n";
  using wrc::runtime::SceneNumber;
  using wrc::runtime::SceneString;
  EXPECT_EQ(SceneNumber(scene, "state", "velocity"), 2000.5);
  EXPECT_EQ(SceneString(scene, "state", "name"), "a # b");
  EXPECT_FALSE(SceneNumber(scene, "state", "bad"));
  EXPECT_FALSE(SceneNumber(scene, "state", "missing"));
  EXPECT_EQ(SceneString(scene, "wheelset", "side"), "left");
  EXPECT_FALSE(SceneNumber(scene, "wheelset", "velocity"));
}

}  // namespace
