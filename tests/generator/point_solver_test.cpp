// One grid point of a scene: the retry of a failed solve from a cold start, and which
// exceptions a point stores and which stop the run.

#include <gtest/gtest.h>

#include <cstring>
#include <exception>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>

#include "tests/generator/generator_test_util.h"
#include "wrc/core/errors.h"
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

// A warm start so far off (1e300 mm below first contact, the wheel sunk through the rail) that
// no contact geometry exists there: the point is solved from the cold start, and stored exactly
// as a cold solve.
TEST(SolveScenePoint, AWarmStartThroughTheRailGivesTheColdSolve) {
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

// A call that breaks SolveScenePoint's own contract (one index per axis) reaches CaseAtIndex's
// std::out_of_range, a std::logic_error: a bug, which must stop the run, not become a point.
TEST(SolveScenePoint, ABugIsNotStoredAsAFailedPoint) {
  test::ScratchDir dir("point-bug");
  const Scene scene = TinyYScene(dir);
  EXPECT_THROW(SolveScenePoint(scene, {1, 0}), std::logic_error);
}

TEST(PointFailureMessage, InputAndNumericalFailuresAreStoredWithTheirMessage) {
  EXPECT_EQ(PointFailureMessage(std::make_exception_ptr(InputError("scene.toml: no contact"))),
            "scene.toml: no contact");
  EXPECT_EQ(PointFailureMessage(std::make_exception_ptr(NumericalError("gsl: diverged"))),
            "gsl: diverged");
}

TEST(PointFailureMessage, BugsAndTheMachinesLimitsPropagate) {
  EXPECT_THROW(PointFailureMessage(std::make_exception_ptr(std::logic_error("invariant"))),
               std::logic_error);
  EXPECT_THROW(PointFailureMessage(std::make_exception_ptr(std::runtime_error("unknown"))),
               std::runtime_error);
  EXPECT_THROW(PointFailureMessage(std::make_exception_ptr(ResourceError("threads"))),
               ResourceError);
  try {
    PointFailureMessage(std::make_exception_ptr(std::bad_alloc()));
    FAIL() << "out of memory was stored as a point";
  } catch (const ResourceError& e) {
    EXPECT_NE(std::string(e.what()).find("the points solved so far are kept"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace wrc
