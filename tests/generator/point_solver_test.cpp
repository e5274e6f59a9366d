// One grid point of a scene: the retry of a failed solve from a cold start.

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <string>

#include "tests/generator/generator_test_util.h"
#include "wrc/core/scene.h"
#include "wrc/generator/generator.h"

namespace wrc {
namespace {

namespace fs = std::filesystem;

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

Scene TinyYScene(const test::ScratchDir& dir) {
  return LoadScene(test::WriteFile(
      dir / "retry.toml",
      test::TinyScene("axes = [\"y\"]\ny = [-200.0, 0.0, 1.0]\noutputs = [\"fy\", \"z\"]")));
}

// A warm start so far off (1e300 mm below first contact) that the vertical force iteration
// bisects its whole iteration budget away without reaching the contact: the point is solved
// again from the cold start, and stored exactly as a cold solve.
TEST(SolveScenePoint, AFailedWarmStartIsRetriedCold) {
  test::ScratchDir dir("retry");
  const Scene scene = TinyYScene(dir);
  const PointResult cold = SolveScenePoint(scene, {1});
  ASSERT_EQ(cold.status, PointStatus::kOk) << cold.message;
  const PointResult retried = SolveScenePoint(scene, {1}, 1e300);
  ASSERT_EQ(retried.status, PointStatus::kOk) << retried.message;
  ASSERT_EQ(retried.values.size(), cold.values.size());
  for (std::size_t k = 0; k < cold.values.size(); ++k) {
    EXPECT_TRUE(SameBits(retried.values[k], cold.values[k])) << "output " << k;
  }
  EXPECT_TRUE(SameBits(retried.z, cold.z));
}

// Bad input fails from either start: the point keeps the reason, once.
TEST(SolveScenePoint, WhatStillFailsKeepsItsReason) {
  test::ScratchDir dir("retry-fails");
  const Scene scene = TinyYScene(dir);
  const PointResult failed = SolveScenePoint(scene, {0}, 0.1);
  EXPECT_EQ(failed.status, PointStatus::kError);
  const std::string reason = "nowhere above the rail";
  const std::size_t at = failed.message.find(reason);
  ASSERT_NE(at, std::string::npos) << failed.message;
  EXPECT_EQ(failed.message.find(reason, at + 1), std::string::npos) << failed.message;
  EXPECT_EQ(failed.message, SolveScenePoint(scene, {0}).message);
}

}  // namespace
}  // namespace wrc
