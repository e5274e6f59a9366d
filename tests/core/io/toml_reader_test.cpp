// Name suggestions for unknown keys.

#include <gtest/gtest.h>

#include "wrc/core/toml_reader.h"

namespace wrc::io {
namespace {

TEST(SuggestName, CapitalsCostNothing) {
  // Users write quantities as in print: Fz is fz, not one edit away from z.
  EXPECT_EQ(SuggestName("Fz", {"z", "fz", "y"}), "fz");
  EXPECT_EQ(SuggestName("Y_Wheel", {"y", "y_wheel", "yaw"}), "y_wheel");
}

TEST(SuggestName, OneOrTwoEditsByLength) {
  EXPECT_EQ(SuggestName("dxx", {"dx", "dy"}), "dx");
  EXPECT_EQ(SuggestName("grdi", {"grid", "track"}), "grid");  // a swap is one edit
  EXPECT_EQ(SuggestName("veloicty", {"velocity", "y"}), "velocity");
  EXPECT_EQ(SuggestName("abc", {"xyz"}), "");  // nothing near
  EXPECT_EQ(SuggestName("spinn", {"roll", "yaw"}), "");
}

}  // namespace
}  // namespace wrc::io
