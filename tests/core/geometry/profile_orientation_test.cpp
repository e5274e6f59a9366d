// Orientation checks of profiles (which way up, which side is which, units) and the wheel's
// flange back, on the shipped profiles in tables/profiles.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "wrc/core/errors.h"
#include "wrc/core/profile.h"

namespace wrc {
namespace {

std::string Shipped(const std::string& name) {
  return std::string(WRC_SOURCE_DIR) + "/tables/profiles/" + name;
}

bool AnyWarningHas(const Profile& profile, const std::string& text) {
  for (const std::string& w : profile.warnings) {
    if (w.find(text) != std::string::npos) return true;
  }
  return false;
}

std::string Joined(const std::vector<std::string>& lines) {
  std::string all;
  for (const std::string& line : lines) all += line + "\n";
  return all;
}

TEST(ProfileOrientation, MiniProfRailWithoutMirrorYIsCalledMirrored) {
  const Profile rail = ReadProfile(Shipped("avg_HR.BAN"), ProfileKind::kRail);
  EXPECT_EQ(JudgeLateralOrientation(rail.y, rail.z, ProfileKind::kRail).verdict,
            LateralVerdict::kMirrored);
  EXPECT_TRUE(AnyWarningHas(rail, "looks mirrored in y")) << Joined(rail.warnings);
  EXPECT_TRUE(AnyWarningHas(rail, "set mirror_y = true")) << Joined(rail.warnings);
  EXPECT_EQ(rail.orientation_doubts.size(), 1u);
}

TEST(ProfileOrientation, MiniProfRailWithMirrorYHasNoDoubt) {
  ProfileOptions options;
  options.mirror_y = true;
  const Profile rail = ReadProfile(Shipped("avg_HR.BAN"), ProfileKind::kRail, options);
  EXPECT_EQ(JudgeLateralOrientation(rail.y, rail.z, ProfileKind::kRail).verdict,
            LateralVerdict::kAsExpected);
  EXPECT_TRUE(rail.orientation_doubts.empty()) << Joined(rail.orientation_doubts);
}

TEST(ProfileOrientation, AutoMirrorYDecidesAsTheExplicitValueAndSaysSo) {
  ProfileOptions explicit_options;
  explicit_options.mirror_y = true;
  const Profile expected = ReadProfile(Shipped("avg_HR.BAN"), ProfileKind::kRail, explicit_options);
  ProfileOptions automatic;
  automatic.detect_mirror_y = true;
  automatic.report_orientation = true;
  const Profile decided = ReadProfile(Shipped("avg_HR.BAN"), ProfileKind::kRail, automatic);
  EXPECT_TRUE(decided.mirrored_y);
  EXPECT_EQ(decided.y, expected.y);
  EXPECT_EQ(decided.z, expected.z);
  EXPECT_TRUE(AnyWarningHas(decided, "mirror_y = \"auto\": y mirrored"))
      << Joined(decided.warnings);
  EXPECT_TRUE(AnyWarningHas(decided, "mirror_z = \"auto\": z mirrored"))
      << Joined(decided.warnings);

  // A wheel that is the right way round is kept, and that is reported too.
  const Profile wheel = ReadProfile(Shipped("avg_wheel.whl"), ProfileKind::kWheel, automatic);
  EXPECT_FALSE(wheel.mirrored_y);
  EXPECT_TRUE(AnyWarningHas(wheel, "mirror_y = \"auto\": y used as given"))
      << Joined(wheel.warnings);
}

TEST(ProfileOrientation, MirroredWheelIsNamed) {
  ProfileOptions options;
  options.mirror_y = true;
  const Profile wheel = ReadProfile(Shipped("avg_wheel.whl"), ProfileKind::kWheel, options);
  EXPECT_TRUE(AnyWarningHas(wheel, "flange")) << Joined(wheel.warnings);
  EXPECT_TRUE(AnyWarningHas(wheel, "set mirror_y = false")) << Joined(wheel.warnings);
  // Simpack S1002 (mirrored by its own header) is the right way round.
  const Profile s1002 = ReadProfile(Shipped("MBench_S1002_v3.prw"), ProfileKind::kWheel);
  EXPECT_EQ(JudgeLateralOrientation(s1002.y, s1002.z, ProfileKind::kWheel).verdict,
            LateralVerdict::kAsExpected);
  EXPECT_TRUE(s1002.orientation_doubts.empty()) << Joined(s1002.orientation_doubts);
}

TEST(ProfileOrientation, UpsideDownIsNamedWhenMirrorZIsGiven) {
  ProfileOptions options;
  options.mirror_y = true;
  options.mirror_z = MirrorZ::kNo;  // MiniProf rails have z upwards: this is wrong
  const Profile rail = ReadProfile(Shipped("avg_HR.BAN"), ProfileKind::kRail, options);
  EXPECT_TRUE(AnyWarningHas(rail, "looks upside down")) << Joined(rail.warnings);
  EXPECT_TRUE(AnyWarningHas(rail, "set mirror_z = true")) << Joined(rail.warnings);
  options.mirror_z = MirrorZ::kYes;
  const Profile right = ReadProfile(Shipped("avg_HR.BAN"), ProfileKind::kRail, options);
  EXPECT_TRUE(right.orientation_doubts.empty()) << Joined(right.orientation_doubts);
}

TEST(ProfileOrientation, SymmetricAndFlangelessProfilesAreUndecided) {
  // A circle of radius 50 mm (a roller) has neither a gauge face nor a flange.
  std::vector<double> y, z;
  for (int i = 0; i <= 60; ++i) {
    const double angle = -1.0 + 2.0 * i / 60.0;
    y.push_back(50.0 * std::sin(angle));
    z.push_back(50.0 * std::cos(angle) - 50.0);  // z down: lowest in the middle
  }
  EXPECT_EQ(JudgeLateralOrientation(y, z, ProfileKind::kWheel).verdict, LateralVerdict::kUndecided);
  for (double& value : z) value = -value;  // a rail head, both sides equally deep
  EXPECT_EQ(JudgeLateralOrientation(y, z, ProfileKind::kRail).verdict, LateralVerdict::kUndecided);
  // The same curve as a wheel has its lowest points at the ends: no flange either.
  EXPECT_EQ(JudgeLateralOrientation(y, z, ProfileKind::kWheel).verdict, LateralVerdict::kUndecided);
}

TEST(ProfileOrientation, MetresAreRecognisedAndScaled) {
  const Profile mm = ReadProfile(Shipped("MBench_S1002_v3.prw"), ProfileKind::kWheel);
  std::vector<double> y_m, z_m;
  for (std::size_t i = 0; i < mm.size(); ++i) {
    y_m.push_back(mm.y[i] / 1000.0);
    z_m.push_back(mm.z[i] / 1000.0);
  }
  try {
    MakeProfile(y_m, z_m, ProfileKind::kWheel, {}, "s1002_in_m.csv");
    FAIL() << "a profile in metres was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("set scale_yz = 1000"), std::string::npos)
        << error.what();
  }
  ProfileOptions options;
  options.scale_yz = 1000.0;
  const Profile scaled = MakeProfile(y_m, z_m, ProfileKind::kWheel, options, "s1002_in_m.csv");
  ASSERT_EQ(scaled.size(), mm.size());
  for (std::size_t i = 0; i < mm.size(); ++i) {
    EXPECT_NEAR(scaled.y[i], mm.y[i], 1e-9);
    EXPECT_NEAR(scaled.z[i], mm.z[i], 1e-9);
  }
  options.scale_yz = 0.0;
  EXPECT_THROW(MakeProfile(y_m, z_m, ProfileKind::kWheel, options), InputError);
}

TEST(ProfileOrientation, FlangeBackLiesWhereTheFormatPutsTheOrigin) {
  // MiniProf: origin at the flange back; the measurement starts 1.55 mm from it.
  const ProfileSpline miniprof(ReadProfile(Shipped("avg_wheel.whl"), ProfileKind::kWheel));
  ASSERT_TRUE(FlangeBackY(miniprof).has_value());
  EXPECT_NEAR(*FlangeBackY(miniprof), 1.55, 0.01);
  // Simpack S1002: origin at the tape circle line, the flange back 70 mm to the track centre.
  const ProfileSpline s1002(ReadProfile(Shipped("MBench_S1002_v3.prw"), ProfileKind::kWheel));
  ASSERT_TRUE(FlangeBackY(s1002).has_value());
  EXPECT_NEAR(*FlangeBackY(s1002), -70.0, 1.0);
  const ProfileSpline rail(ReadProfile(Shipped("MBench_UIC60_v3.prr"), ProfileKind::kRail));
  EXPECT_FALSE(FlangeBackY(rail).has_value());
}

}  // namespace
}  // namespace wrc
