// Segments of the sweep: they cover every point exactly once, whole lines when there are
// enough of them, and their encoding for other ranks round-trips.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "generator/sweep.h"

namespace wrc::gen {
namespace {

void ExpectPartition(const SegmentLayout& layout) {
  std::vector<int> seen(layout.point_count(), 0);
  for (std::uint64_t s = 0; s < layout.segment_count(); ++s) {
    const std::uint64_t first = layout.SegmentFirstPoint(s);
    const std::size_t size = layout.SegmentSize(s);
    ASSERT_GE(size, 1u);
    ASSERT_LE(size, layout.segment_length());
    // A segment never crosses a line: warm starts chain only along the last axis.
    EXPECT_EQ(first / layout.line_length(), (first + size - 1) / layout.line_length());
    for (std::size_t k = 0; k < size; ++k) ++seen[first + k];
  }
  for (std::size_t p = 0; p < seen.size(); ++p) EXPECT_EQ(seen[p], 1) << "point " << p;
}

TEST(SegmentLayout, WholeLinesWhenThereAreEnough) {
  const SegmentLayout layout({41, 3, 5, 9}, 64);  // tables/mbench.toml
  EXPECT_EQ(layout.segment_length(), 9u);
  EXPECT_EQ(layout.segment_count(), 41u * 3 * 5);
  ExpectPartition(layout);
}

TEST(SegmentLayout, FewLinesAreCutSoThatAllCoresGetWork) {
  const SegmentLayout single_line({401}, 64);  // a 1-D sweep
  EXPECT_EQ(single_line.segment_length(), 6u);
  EXPECT_GE(single_line.segment_count(), 64u);
  ExpectPartition(single_line);
  const SegmentLayout small({9, 3}, 64);  // tables/demo.toml: every point on its own
  EXPECT_EQ(small.segment_length(), 1u);
  ExpectPartition(small);
  const SegmentLayout uneven({3, 50}, 16);
  ExpectPartition(uneven);
  EXPECT_EQ(SegmentLayout({2, 6}, 1).segment_length(), 6u);
}

TEST(SegmentLayout, IndicesAreRowMajor) {
  const SegmentLayout layout({2, 3, 4}, 1);
  EXPECT_EQ(layout.Indices(0), (std::vector<std::size_t>{0, 0, 0}));
  EXPECT_EQ(layout.Indices(23), (std::vector<std::size_t>{1, 2, 3}));
  EXPECT_EQ(layout.Indices(13), (std::vector<std::size_t>{1, 0, 1}));
}

TEST(SegmentTasks, EncodingRoundTrips) {
  std::vector<SegmentTask> tasks(3);
  tasks[0].segment = 5;
  tasks[1].segment = 1ull << 40;
  tasks[1].done = {1, 0, 1};
  tasks[1].known_z = {0.25, std::numeric_limits<double>::quiet_NaN(), -1e-300};
  tasks[2].segment = 0;
  const std::vector<SegmentTask> decoded = DecodeTasks(EncodeTasks(tasks));
  ASSERT_EQ(decoded.size(), 3u);
  EXPECT_EQ(decoded[0].segment, 5u);
  EXPECT_TRUE(decoded[0].done.empty());
  EXPECT_EQ(decoded[1].segment, 1ull << 40);
  EXPECT_EQ(decoded[1].done, tasks[1].done);
  EXPECT_EQ(decoded[1].known_z[0], 0.25);
  EXPECT_TRUE(std::isnan(decoded[1].known_z[1]));
  EXPECT_EQ(decoded[1].known_z[2], -1e-300);
  EXPECT_TRUE(DecodeTasks(EncodeTasks({})).empty());
  EXPECT_THROW(DecodeTasks("\x01"), std::runtime_error);
}

}  // namespace
}  // namespace wrc::gen
