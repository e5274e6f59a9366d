// The vertical-force iteration on synthetic force laws, where the height that carries fz is known
// in closed form: Hertz's F = K·(z − z_c)^1.5, with a tangential part, with a jump where patches
// merge, with heights that cannot be solved, and without support.

#include "core/wheelrail/fz_iteration.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "wrc/core/errors.h"

namespace wrc::wr {
namespace {

// A force law F(z) (normal part) and a tangential share added by full solves.
class SyntheticForce : public VerticalForce {
 public:
  explicit SyntheticForce(std::function<double(double)> law, double tangential_share = 0.0)
      : law_(std::move(law)), share_(tangential_share) {}
  double Normal(double z, double /*tolerance*/) override {
    ++normal_calls;
    last_z = z;
    return law_(z);
  }
  double Full(double z, double /*tangential_tolerance*/) override {
    ++full_calls;
    last_z = z;
    return law_(z) * (1.0 + share_);
  }
  int normal_calls = 0, full_calls = 0;
  double last_z = NAN;

 private:
  std::function<double(double)> law_;
  double share_;
};

constexpr double kFirstContact = 0.1;  // mm
constexpr double kStiffness = 1.0e6;   // N/mm^1.5, about a 460 mm wheel on a UIC60 head
constexpr double kFz = 1.0e4;          // N

double Hertz(double z) {
  return z > kFirstContact ? kStiffness * std::pow(z - kFirstContact, 1.5) : 0.0;
}

// The height where Hertz's law with the share carries kFz.
double ExactHeight(double share) {
  return kFirstContact + std::pow(kFz / (kStiffness * (1.0 + share)), 2.0 / 3.0);
}

FzIterationOptions Options(bool tangential) {
  FzIterationOptions o;
  o.tangential = tangential;
  return o;
}

// Frictionless Hertz from a start 10x too shallow: the secant on F^(2/3), which is linear here,
// meets fz to its tolerance (1e-6 of fz, so z to 2/3 of that relative to the approach) in a few
// solves; the last solve is at the result's height.
TEST(FzIteration, MeetsHertzsLawInAFewSolves) {
  SyntheticForce force(Hertz);
  const double exact = ExactHeight(0.0);
  const double start = kFirstContact + 0.1 * (exact - kFirstContact);
  const FzIterationSummary s = SolveForFz(force, kFz, kFirstContact, start, Options(false));
  ASSERT_EQ(s.outcome, FzOutcome::kMet);
  EXPECT_FALSE(s.last_was_full);
  EXPECT_NEAR(s.z, exact, 1e-6 * (exact - kFirstContact));
  EXPECT_EQ(force.last_z, s.z);
  EXPECT_LE(s.solves, 4);
  EXPECT_EQ(force.full_calls, 0);
}

// With a tangential part of 2 % of the force (flange contact: fs·sin δ) the Newton steps on full
// solves find the height of the full force, not the normal one; the result is a full solve.
TEST(FzIteration, FullSolvesCorrectForTheTangentialPart) {
  constexpr double kShare = 0.02;
  SyntheticForce force(Hertz, kShare);
  const double exact = ExactHeight(kShare);
  const FzIterationSummary s = SolveForFz(force, kFz, kFirstContact, exact * 1.1, Options(true));
  ASSERT_EQ(s.outcome, FzOutcome::kMet);
  EXPECT_TRUE(s.last_was_full);
  EXPECT_NEAR(s.z, exact, 1e-6 * (exact - kFirstContact));
  EXPECT_EQ(force.last_z, s.z);
  EXPECT_GE(force.full_calls, 2);  // the first, loose, full solve never ends it
  EXPECT_LE(force.full_calls, 4);
}

// Patches that merge at z_m add a step to F. With fz inside the step no height carries it: the
// bracket closes on z_m and the iteration stops there, not met, after a bounded number of
// solves (the bracket halves at least every other step: 1e-13 mm from 1 mm in ~90 solves).
TEST(FzIteration, AJumpOverFzEndsNotMetAtTheJump) {
  constexpr double kMerge = 0.13;  // mm: F = 0.52 fz just above it without the step
  const auto law = [](double z) { return Hertz(z) + (z >= kMerge ? 2.0 * kFz : 0.0); };
  ASSERT_LT(law(kMerge - 1e-9), kFz);
  ASSERT_GT(law(kMerge), kFz);
  SyntheticForce force(law);
  const FzIterationSummary s = SolveForFz(force, kFz, kFirstContact, 0.12, Options(false));
  EXPECT_EQ(s.outcome, FzOutcome::kNotMet);
  EXPECT_NEAR(s.z, kMerge, 1e-9);
  EXPECT_LT(s.solves, 150);
}

// Below z_u the contact cannot be solved and fz lies beyond: the outcome says so with the
// reason of the failed solve; with fz above z_u the failures only bound the bracket.
TEST(FzIteration, UnsolvableHeightsBoundTheBracket) {
  const auto law = [](double limit) {
    return [limit](double z) {
      if (z > limit) throw InputError("patch too large at z = " + std::to_string(z));
      return Hertz(z);
    };
  };
  const double exact = ExactHeight(0.0);
  SyntheticForce beyond(law(kFirstContact + 0.5 * (exact - kFirstContact)));
  const FzIterationSummary s1 = SolveForFz(beyond, kFz, kFirstContact, exact, Options(false));
  EXPECT_EQ(s1.outcome, FzOutcome::kUnsolvable);
  EXPECT_NE(s1.unsolvable.find("patch too large"), std::string::npos) << s1.unsolvable;

  SyntheticForce within(law(exact + 0.01));
  const FzIterationSummary s2 =
      SolveForFz(within, kFz, kFirstContact, exact + 0.05, Options(false));
  ASSERT_EQ(s2.outcome, FzOutcome::kMet);
  EXPECT_NEAR(s2.z, exact, 1e-6 * (exact - kFirstContact));
}

// A wheel that never carries fz (the force saturates below it, as when the contact runs off the
// profiles' ends): no support, after the steps allowed, never an absurd height asked for.
TEST(FzIteration, NoSupportWhenTheForceStaysBelowFz) {
  double deepest = 0.0;
  SyntheticForce force([&deepest](double z) {
    deepest = std::max(deepest, z);
    return 0.5 * kFz * std::tanh(z - kFirstContact);
  });
  FzIterationOptions o = Options(true);
  o.max_normal_steps = 30;
  const FzIterationSummary s = SolveForFz(force, kFz, kFirstContact, 0.2, o);
  EXPECT_EQ(s.outcome, FzOutcome::kNoSupport);
  EXPECT_LE(s.solves, 31);
  EXPECT_TRUE(std::isfinite(deepest));
  EXPECT_EQ(force.full_calls, 0);
}

// A first-contact estimate above the true one: the first heights carry nothing, which gives no
// secant; the iteration goes deeper until it finds force and then meets fz.
TEST(FzIteration, StartsWithoutForceAndGoesDeeper) {
  constexpr double kTrueContact = 0.3;  // mm, 0.2 mm below the estimate
  const auto law = [](double z) {
    return z > kTrueContact ? kStiffness * std::pow(z - kTrueContact, 1.5) : 0.0;
  };
  SyntheticForce force(law);
  const FzIterationSummary s = SolveForFz(force, kFz, kFirstContact, 0.11, Options(false));
  ASSERT_EQ(s.outcome, FzOutcome::kMet);
  const double exact = kTrueContact + std::pow(kFz / kStiffness, 2.0 / 3.0);
  EXPECT_NEAR(s.z, exact, 1e-6 * (exact - kTrueContact));
}

}  // namespace
}  // namespace wrc::wr
