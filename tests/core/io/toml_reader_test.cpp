// Name suggestions for unknown keys.

#include <gtest/gtest.h>

#include <string>

#include "wrc/core/errors.h"
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

TEST(Section, AStringWithNulIsRefusedNamingTheKey) {
  // A path cut at the NUL by the C library would open another file, and report success.
  const SourceFile file("case.toml");
  const toml::table root = file.Parse("[rail]\nprofile = \"rail.prr\\u0000junk\"\n");
  const Section rail(file, root, "rail");
  try {
    rail.OptionalString("profile");
    FAIL() << "accepted a NUL";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("case.toml:2"), std::string::npos) << message;
    EXPECT_NE(message.find("rail.profile"), std::string::npos) << message;
    EXPECT_NE(message.find("NUL"), std::string::npos) << message;
  }
  const toml::table plain = file.Parse("[rail]\nprofile = \"rail.prr\"\n");
  EXPECT_EQ(Section(file, plain, "rail").OptionalString("profile"), "rail.prr");
}

}  // namespace
}  // namespace wrc::io
