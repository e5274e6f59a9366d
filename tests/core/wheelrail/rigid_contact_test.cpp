// The rigid contact of undeformed profiles (RigidContactAt, wrc/core/profile_placement.h): the
// rolling-radius difference of EN 15302's benchmark cases E1–E9 from their profiles, and its
// equivalent conicity inside the standard's tolerance band at every amplitude, the wider band
// only next to a contact jump. The Δr tables themselves are printed against for reading: they
// agree to a few hundredths of a millimetre on the treads, and differ where a jump falls one
// sample earlier or later and in flange contact.

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/number_table.h"
#include "wrc/core/case.h"
#include "wrc/core/conicity.h"
#include "wrc/core/profile.h"
#include "wrc/core/profile_placement.h"

namespace {

const std::string kEn15302 = std::string(WRC_TEST_DATA_DIR) + "/en15302/";

// EN 15302's set-up (tests/data/en15302/README.md): wheel profile origins at ±750 mm (flange
// back distance 1360, flange back position −70), the rail as tabulated with its origin at ±750
// mm at the tape-circle height, no cant; as the right wheel of a right rail.
wrc::Case Wheel(const std::string& profile, double nominal_radius) {
  wrc::Case c;
  c.rail.path = kEn15302 + "profiles/SUIC519A.dat";
  c.rail.path_as_written = "SUIC519A.dat";
  c.wheel.path = kEn15302 + "profiles/RUIC519" + profile + ".dat";
  c.wheel.path_as_written = "RUIC519" + profile + ".dat";
  c.track.gauge_height = 0.0;  // absolute placement
  c.track.rail_y = 750.0;
  c.track.rail_z = 0.0;
  c.track.cant = 0.0;
  c.wheelset.flange_back_distance = 1360.0;
  c.wheelset.flange_back_position = -70.0;
  c.wheelset.nominal_radius = nominal_radius;
  // Read once, as LoadCase does: each case is placed at hundreds of shifts.
  c.rail.spline = wrc::SplineOf(c.rail, wrc::ProfileKind::kRail);
  c.wheel.spline = wrc::SplineOf(c.wheel, wrc::ProfileKind::kWheel);
  return c;
}

// Δr = r_right(y) − r_left(y) at the given y; the left wheel is the right-side equivalent at −y.
wrc::RollingRadiusDifference Dr(const wrc::Case& right, const wrc::Case& left,
                                const std::vector<double>& ys) {
  wrc::RollingRadiusDifference t;
  for (const double y : ys) {
    const auto r = wrc::RigidContactAt(right, {y, 0.0, 0.0, 0.0}, 0.01);
    const auto l = wrc::RigidContactAt(left, {-y, 0.0, 0.0, 0.0}, 0.01);
    EXPECT_TRUE(r.found && l.found) << y;
    t.y.push_back(y);
    t.dr.push_back(r.rolling_radius - l.rolling_radius);
  }
  return t;
}

// A 1:20 cone (no flange) on a rail crowned by a 300 mm arc, written z up: the wheel touches
// where the crown's slope is the cone's, 300·tan γ/√(1 + tan² γ) to the gauge side of the
// crown, whatever the shift, so each wheel's radius changes by tan γ per mm of shift and
// Δr = 2·y·tan γ exactly, and so is the equivalent conicity tan γ.
TEST(RigidContact, OfAConeOnACrownGivesDrOfTheCone) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("wrc_cone_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  constexpr double kTan = 0.05, kCrown = 300.0;
  {
    std::ofstream wheel(dir / "cone.csv"), rail(dir / "crown.csv");
    for (int i = 0; i <= 120; ++i) wheel << -60 + i << ' ' << kTan * (-60 + i) << '\n';
    for (int i = 0; i <= 140; ++i) {
      const double y = -35.0 + 0.5 * i;
      rail << y << ' ' << std::sqrt(kCrown * kCrown - y * y) - kCrown << '\n';
    }
  }
  wrc::Case c = Wheel("A", 460.0);
  c.rail.path = dir / "crown.csv";
  c.wheel.path = dir / "cone.csv";
  c.rail.spline = c.wheel.spline = nullptr;                 // read from the paths above
  c.rail.mirror_z = c.wheel.mirror_z = wrc::MirrorZ::kYes;  // z up; no side faces to tell
  wrc::RollingRadiusDifference dr;
  for (int i = -50; i <= 50; ++i) {
    const double y = 0.1 * i;
    const auto r = wrc::RigidContactAt(c, {y, 0.0, 0.0, 0.0}, 0.01);
    const auto l = wrc::RigidContactAt(c, {-y, 0.0, 0.0, 0.0}, 0.01);
    ASSERT_TRUE(r.found && l.found);
    // The spline through the crown's 0.5 mm points places the tangent point within 1e-3 mm.
    EXPECT_NEAR(r.rail_y, 750.0 - kCrown * kTan / std::sqrt(1.0 + kTan * kTan), 1e-3) << y;
    dr.y.push_back(y);
    dr.dr.push_back(r.rolling_radius - l.rolling_radius);
    EXPECT_NEAR(dr.dr.back(), 2.0 * kTan * y, 1e-9) << y;
  }
  for (double amplitude : {1.0, 4.0}) {
    EXPECT_NEAR(wrc::EquivalentConicityAt(dr, amplitude).tan_gamma_e, kTan, 1e-9);
  }
  EXPECT_FALSE(wrc::RigidContactAt(c, {0.0, 0.0, 0.0, 0.0}, 0.01).at_profile_end);
  // The crown taken upside down is a trough: the cone rests on its gauge-side end.
  c.rail.mirror_z = wrc::MirrorZ::kNo;
  const auto on_edge = wrc::RigidContactAt(c, {0.0, 0.0, 0.0, 0.0}, 0.01);
  EXPECT_TRUE(on_edge.at_profile_end);
  EXPECT_NEAR(on_edge.rail_y, 750.0 - 35.0, 0.05);
  std::filesystem::remove_all(dir);
}

// Circular arcs in conformal contact: a wheel profile of radius Rw = 200 mm (centred on its
// origin) on a rail crown of Rr = 80 mm whose centre lies d = 4 mm to the side, both written z
// up. Two arcs touch where their slopes agree, on the line through their centres: with the
// wheel's centre c = d + y from the crown's, sin φ = −c/(Rw − Rr), and the wheel touches
// Rw·(1 − cos φ) below its apex, so r(y) = const + Rw·(1 − cos φ(y)) and
// Δr(y) = r(y) − r(−y) = Rw·(cos φ(−y) − cos φ(y)) exactly; for small y the slope is
// −2·Rw·tan φ0/(Rw − Rr), twice the classic conformal-contact conicity (φ0 = φ(0)).
TEST(RigidContact, OfCircularArcsGivesTheirClosedForm) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("wrc_arcs_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  constexpr double kWheel = 200.0, kRail = 80.0, kOffset = 4.0;
  {
    std::ofstream wheel(dir / "arc.csv"), rail(dir / "crown.csv");
    for (int i = 0; i <= 240; ++i) {
      const double y = -60.0 + 0.5 * i;
      wheel << y << ' ' << std::sqrt(kWheel * kWheel - y * y) - kWheel << '\n';
    }
    for (int i = 0; i <= 140; ++i) {
      const double y = -35.0 + 0.5 * i;
      rail << y << ' ' << std::sqrt(kRail * kRail - (y + kOffset) * (y + kOffset)) - kRail << '\n';
    }
  }
  wrc::Case c = Wheel("A", 460.0);
  c.rail.path = dir / "crown.csv";
  c.wheel.path = dir / "arc.csv";
  c.rail.spline = c.wheel.spline = nullptr;
  c.rail.mirror_z = c.wheel.mirror_z = wrc::MirrorZ::kYes;
  const auto angle = [&](double y) { return std::asin(-(kOffset + y) / (kWheel - kRail)); };
  wrc::RollingRadiusDifference measured, exact;
  for (int i = -40; i <= 40; ++i) {
    const double y = 0.1 * i;
    const auto r = wrc::RigidContactAt(c, {y, 0.0, 0.0, 0.0}, 0.01);
    const auto l = wrc::RigidContactAt(c, {-y, 0.0, 0.0, 0.0}, 0.01);
    ASSERT_TRUE(r.found && l.found);
    measured.y.push_back(y);
    measured.dr.push_back(r.rolling_radius - l.rolling_radius);
    exact.y.push_back(y);
    exact.dr.push_back(kWheel * (std::cos(angle(-y)) - std::cos(angle(y))));
    // Conformal contact leaves the gap flat (curvature 1/Rr − 1/Rw = 0.0075/mm), so the
    // parabola through its 0.01 mm samples places the contact to a few 1e-4 mm, which moves r
    // by tan φ (under 0.08) times that, Δr within 5e-5 mm, and turns the crown's normal by that
    // over Rr, the angle within 1e-5 rad.
    EXPECT_NEAR(measured.dr.back(), exact.dr.back(), 5e-5) << y;
    EXPECT_NEAR(std::fabs(r.contact_angle), std::fabs(angle(y)), 1e-5) << y;
  }
  const double slope = -2.0 * kWheel * std::tan(angle(0.0)) / (kWheel - kRail);
  EXPECT_NEAR((measured.dr[41] - measured.dr[39]) / 0.2, slope, 1e-4 * std::fabs(slope));
  for (double amplitude : {1.0, 3.0}) {  // Δr within 5e-5 mm of 0.1–0.4 mm: 1e-4 relative
    const double expected = wrc::EquivalentConicityAt(exact, amplitude).tan_gamma_e;
    EXPECT_NEAR(wrc::EquivalentConicityAt(measured, amplitude).tan_gamma_e, expected,
                1e-4 * expected);
  }
  std::filesystem::remove_all(dir);
}

// With the roll solved both wheels touch together: equal first-touch heights. The pair E1 is
// symmetric, so the roll is 0 at y = 0 and odd in y; on the treads it is a fraction of a
// milliradian (Δr over the 1500 mm base), in flange contact several.
TEST(RigidContact, WheelsetRollBringsBothWheelsDownTogether) {
  const wrc::Case right = Wheel("A", 460.0), left = Wheel("A", 460.0);
  EXPECT_NEAR(wrc::WheelsetRollAt(right, left, 0.0, 0.01), 0.0, 1e-8);
  for (const double y : {3.0, 6.5}) {
    const double roll = wrc::WheelsetRollAt(right, left, y, 0.01);
    ASSERT_TRUE(std::isfinite(roll)) << y;
    EXPECT_NEAR(wrc::WheelsetRollAt(right, left, -y, 0.01), -roll, 1e-8) << y;
    const double h_right = wrc::RigidContactAt(right, {y, 0.0, roll, 0.0}, 0.01).height;
    const double h_left = wrc::RigidContactAt(left, {-y, 0.0, -roll, 0.0}, 0.01).height;
    EXPECT_NEAR(h_right, h_left, 1e-6) << y;
    EXPECT_LT(std::fabs(roll), y < 5.0 ? 1e-3 : 2e-2) << y;
    EXPECT_GT(std::fabs(roll), 1e-6) << y;
  }
}

std::vector<std::vector<double>> Rows(const std::string& path, char separator) {
  return wrc::test_support::NumberRows(path, separator);
}

struct BenchmarkCase {
  int number;
  const char* right;
  const char* left;
  double left_radius;
};
const BenchmarkCase kCases[] = {{1, "A", "A", 460.0}, {2, "B", "B", 460.0}, {3, "H", "H", 460.0},
                                {4, "I", "I", 460.0}, {5, "A", "A", 459.0}, {6, "B", "B", 459.0},
                                {7, "H", "H", 459.0}, {8, "I", "I", 459.0}, {9, "A", "B", 460.0}};

class FromProfiles : public ::testing::TestWithParam<BenchmarkCase> {};

TEST_P(FromProfiles, DrAndConicityMatchEN15302) {
  const BenchmarkCase& e = GetParam();
  const std::string n = std::to_string(e.number);
  const auto reference =
      Rows(kEn15302 + "tables/dr_E" + (e.number == 5 ? "5_reconstructed" : n) + ".txt", ' ');
  std::vector<double> ys;
  for (const auto& row : reference) ys.push_back(row.at(0));
  const auto dr = Dr(Wheel(e.right, 460.0), Wheel(e.left, e.left_radius), ys);
  double worst = 0.0;
  int off = 0;
  for (std::size_t i = 0; i < dr.y.size(); ++i) {
    const double difference = std::fabs(dr.dr[i] - reference[i].at(1));
    worst = std::max(worst, difference);
    off += difference > 0.01;
  }
  std::cout << "E" << n << ": largest |Δr − table| " << worst << " mm, " << off << " of "
            << dr.y.size() << " off by more than 0.01 mm\n";
  // Contact jumps: Δr steps by more than 0.5 mm between neighbouring samples 0.1 mm apart
  // (tread to tread, tread to flange). EN 15302 grants the wider band next to them: here, where
  // the motion's amplitude lies within 0.3 mm of a jump's |y|, three samples.
  std::vector<double> jumps;
  for (std::size_t i = 0; i + 1 < dr.y.size(); ++i) {
    if (std::fabs(dr.dr[i + 1] - dr.dr[i]) > 0.5) jumps.push_back(0.5 * (dr.y[i] + dr.y[i + 1]));
  }
  const auto next_to_jump = [&](double amplitude) {
    for (double y : jumps) {
      if (std::fabs(amplitude - std::fabs(y)) <= 0.3) return true;
    }
    return false;
  };
  int checked = 0, outside = 0, outside_wide = 0;
  for (const auto& row : Rows(kEn15302 + "tables/conicity_E" + n + ".csv", ',')) {
    const auto c = wrc::EquivalentConicityAt(dr, row.at(0));
    if (!c.valid) continue;
    ++checked;
    const bool in_band = c.tan_gamma_e <= row.at(2) && c.tan_gamma_e >= row.at(3);
    outside += !in_band;
    EXPECT_TRUE(in_band || next_to_jump(row.at(0))) << "E" << n << " at " << row.at(0) << " mm";
    if (!in_band) {
      std::cout << "E" << n << " at " << row.at(0) << " mm: " << c.tan_gamma_e << ", band ["
                << row.at(3) << ", " << row.at(2) << "], wider [" << row.at(5) << ", " << row.at(4)
                << "]\n";
    }
    outside_wide += c.tan_gamma_e > row.at(4) || c.tan_gamma_e < row.at(5);
  }
  std::cout << "E" << n << ": " << checked << " amplitudes, " << outside << " outside the band, "
            << outside_wide << " outside the wider band\n";
  EXPECT_EQ(outside_wide, 0) << "E" << n;
  EXPECT_GE(checked, 40) << "E" << n;
}

INSTANTIATE_TEST_SUITE_P(EN15302, FromProfiles, ::testing::ValuesIn(kCases),
                         [](const auto& info) { return "E" + std::to_string(info.param.number); });

}  // namespace
