// The contact search's levels (coarse, middle, fine) against locating every sample: the samples
// that can interpenetrate at any z asked for must come out as if all were located.

#include "core/wheelrail/contact_search.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "wrc/core/case.h"

namespace wrc::wr {
namespace {

namespace fs = std::filesystem;

constexpr double kStep = 0.05;  // mm, the solver's search step
constexpr double kReach = 1.0;  // mm, the solver's first search reach
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Pair {
  Case c;
  PlacedRail rail;
  PlacedWheel wheel;
};

// The rail and the wheel of a reference case, placed as the solver places them (right side).
Pair PlacedPair(const std::string& group, const std::string& name) {
  Case c = LoadCase(fs::path(WRC_TEST_DATA_DIR) / "reference" / "cases" / group / (name + ".toml"));
  WheelsetKinematics kin;
  kin.y = c.state.y;
  kin.roll = c.state.roll;
  kin.yaw = c.state.yaw;
  PlacedRail rail(c.rail.spline, c.track);
  PlacedWheel wheel(c.wheel.spline, c.wheelset, kin);
  return {std::move(c), std::move(rail), std::move(wheel)};
}

double SmallestGap(const ContactSearch& search) {
  double smallest = kInf;
  for (const LocusSample& s : search.samples) {
    if (s.valid) smallest = std::min(smallest, s.gap);
  }
  return smallest;
}

// Every sample whose gap lies below `needed` in the search of all samples (smallest gap
// `smallest`) is valid in `levels` with the same gap (to the locus fit's round-off: the fits
// start from other guesses) and locus; nothing far beyond it is valid. Returns how many samples
// lie below `needed`.
int ExpectSameWhereNeeded(const ContactSearch& all, const ContactSearch& levels, double smallest,
                          double needed) {
  EXPECT_EQ(all.samples.size(), levels.samples.size());
  int below = 0;
  for (std::size_t k = 0; k < all.samples.size() && k < levels.samples.size(); ++k) {
    const LocusSample& a = all.samples[k];
    const LocusSample& b = levels.samples[k];
    EXPECT_EQ(a.s, b.s);
    if (a.valid && a.gap < needed) {
      ++below;
      EXPECT_TRUE(b.valid) << "sample " << k << " at s = " << a.s << " mm, gap " << a.gap;
      if (!b.valid) continue;
      EXPECT_NEAR(b.gap, a.gap, 1e-9) << "sample " << k;
      EXPECT_NEAR(b.x, a.x, 1e-3) << "sample " << k;
      EXPECT_NEAR(b.curvature, a.curvature, 1e-6 * a.curvature) << "sample " << k;
    }
    // The search's own margin beyond what it needs is 0.5 mm (kDipMargin at 1 mm intervals);
    // it needs at least the smallest gap of its coarse samples, within 0.5 mm of the true one.
    if (a.valid && a.gap >= std::max(needed, smallest + 0.5) + 0.5) {
      EXPECT_FALSE(b.valid) << "sample " << k << " at s = " << a.s << " mm";
    }
    // At the wheel's edge the locus fit may fail from one guess and converge from another;
    // such a sample never lies within reach.
    if (!a.valid && b.valid) {
      EXPECT_GE(b.gap, needed) << "sample " << k;
    }
  }
  return below;
}

// Conformal heavy-haul contact: the gap stays within 0.5 mm of the interpenetration over tens
// of mm, where the middle level does its work; z prescribed (only gaps below z matter).
TEST(ContactSearch, LevelsMatchAllSamplesOnHeavyHaul) {
  const Pair pair = PlacedPair("heavy_haul", "heavy_haul_z1.087");
  const ContactSearch all = SearchContact(pair.rail, pair.wheel, kStep, kInf, kInf);
  const double smallest = SmallestGap(all);
  ASSERT_TRUE(std::isfinite(smallest));
  // The reference cases' z, and z just past first contact, where only the samples next to the
  // deepest one interpenetrate: a level that skipped an interval around it for want of a dip
  // margin would lose them.
  for (const double z : {1.087, 1.194, smallest + 1e-2, smallest + 1e-3, smallest + 1e-5}) {
    const ContactSearch levels = SearchContact(pair.rail, pair.wheel, kStep, kReach, z);
    EXPECT_EQ(SmallestGap(levels), smallest);
    const int below = ExpectSameWhereNeeded(all, levels, smallest, z);
    EXPECT_GT(below, z > 1.0 ? 100 : 0) << "z = " << z;  // > 5 mm of interpenetration at 1.087
  }
}

// Vertical force prescribed (z unknown, up to kReach below first contact), on the Manchester
// pair with flange contact: steep, strongly curved gap.
TEST(ContactSearch, LevelsMatchAllSamplesOnFlangeContact) {
  const Pair pair = PlacedPair("mbench_curved", "mbench_curved_y6");
  const ContactSearch all = SearchContact(pair.rail, pair.wheel, kStep, kInf, kInf);
  const ContactSearch levels = SearchContact(pair.rail, pair.wheel, kStep, kReach, kInf);
  const double smallest = SmallestGap(all);
  EXPECT_EQ(SmallestGap(levels), smallest);
  EXPECT_GT(ExpectSameWhereNeeded(all, levels, smallest, smallest + kReach), 100);
  // z prescribed just past first contact (see above).
  for (const double depth : {1e-6, 1e-4, 1e-3, 1e-2, 0.1}) {
    const double z = smallest + depth;
    const ContactSearch at_z = SearchContact(pair.rail, pair.wheel, kStep, kReach, z);
    EXPECT_GT(ExpectSameWhereNeeded(all, at_z, smallest, z), 0) << "z = " << z;
  }
}

}  // namespace
}  // namespace wrc::wr
