#pragma once
// Comparing arrays of numbers with a stated tolerance, reporting the worst entry.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <vector>

namespace wrc::test_support {

/// Success when |actual[i] − expected[i]| <= tolerance for every i (NaN never passes); otherwise
/// a message with the sizes, or with the worst entry (index, both values, difference) and how
/// many entries are outside the tolerance. Use as EXPECT_TRUE(AllNear(a, b, 1e-12)).
inline ::testing::AssertionResult AllNear(const std::vector<double>& actual,
                                          const std::vector<double>& expected, double tolerance) {
  if (actual.size() != expected.size()) {
    return ::testing::AssertionFailure()
           << "sizes differ: " << actual.size() << " values against " << expected.size();
  }
  std::size_t worst = 0, outside = 0;
  double worst_difference = -1.0;
  for (std::size_t i = 0; i < actual.size(); ++i) {
    double difference = std::fabs(actual[i] - expected[i]);
    if (std::isnan(difference)) difference = INFINITY;
    if (!(difference <= tolerance)) ++outside;
    if (difference > worst_difference) {
      worst_difference = difference;
      worst = i;
    }
  }
  if (outside == 0) return ::testing::AssertionSuccess();
  std::ostringstream text;
  text.precision(17);
  text << outside << " of " << actual.size() << " values differ by more than " << tolerance
       << "; the worst, at index " << worst << ": " << actual[worst] << " against "
       << expected[worst] << " (difference " << worst_difference << ")";
  return ::testing::AssertionFailure() << text.str();
}

/// The largest |a[i]|, 0 for an empty array: the scale for a relative tolerance.
inline double LargestMagnitude(const std::vector<double>& a) {
  double m = 0.0;
  for (const double v : a) m = std::max(m, std::fabs(v));
  return m;
}

}  // namespace wrc::test_support
