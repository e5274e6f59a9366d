// The curved reference surface against hand calculations (paper §3.4, Fig. 8, and §3.6,
// Fig. 10), and the continuity that is the reason the method exists (paper §4.1, Fig. 12–13).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "wrc/core/case.h"
#include "wrc/core/wheelrail.h"

namespace wrc {
namespace {

namespace fs = std::filesystem;

// Writes y, z samples of f over [y0, y1] as a two-column CSV profile.
void WriteProfile(const fs::path& path, double y0, double y1, double step,
                  const std::function<double(double)>& f) {
  std::ofstream out(path);
  out.precision(15);
  const int n = static_cast<int>(std::lround((y1 - y0) / step));
  for (int k = 0; k <= n; ++k) {
    const double y = y0 + k * step;
    out << y << ',' << f(y) << '\n';
  }
}

std::string SingleWheelCase(const std::string& rail, const std::string& wheel, double z, double dx,
                            double ds, bool tangential, bool midplane, double radius) {
  std::ostringstream t;
  t.precision(17);
  t << "[problem]\ntype = \"wheel-rail\"\n[rail]\nprofile = \"" << rail
    << "\"\n[wheel]\nprofile = \"" << wheel
    << "\"\n[track]\ngauge_height = -1.0\nrail_y = 0.0\nrail_z = 0.0\ncant = 0.0\n"
    << "[wheelset]\nflange_back_distance = 0.0\nflange_back_position = 0.0\nnominal_radius = "
    << radius << "\n[friction]\nmu = 0.3\n[grid]\ndx = " << dx << "\nds = " << ds
    << "\n[method]\nreference = \"curved\"\n[effects]\ntangential = "
    << (tangential ? "true" : "false")
    << "\nmidplane_correction = " << (midplane ? "true" : "false")
    << "\n[state]\ny = 0.0\nz = " << z
    << "\nroll = 0.0\nyaw = 0.0\nvelocity = 1000.0\nomega = " << -1000.0 / radius << "\n";
  return t.str();
}

// Paper Fig. 8: a groove of radius 10.01 mm with its bottom at [0, −0.02] and a ball of radius
// 9.99 mm centred at [0, −9.97] (z down): the curved reference is the circle of radius 10 about
// [0, −10], and the undeformed distance along its normal at angle θ is, exactly,
//   h(θ) = [−0.03 cos θ + √(10.01² − 0.03² sin²θ)] − [0.03 cos θ + √(9.99² − 0.03² sin²θ)].
TEST(CurvedReference, BallInGrooveMatchesHandCalculation) {
  const fs::path dir = fs::temp_directory_path() / "wrc_ball_in_groove";
  fs::create_directories(dir);
  // Profiles to |y| <= 4.5 mm keep their end slopes below 30°, so no z-orientation guess
  // applies; the spline error of 0.05 mm samples on a 10 mm circle is ~1e-9 mm.
  WriteProfile(dir / "groove.csv", -4.5, 4.5, 0.05,
               [](double y) { return -10.03 + std::sqrt(10.01 * 10.01 - y * y); });
  WriteProfile(dir / "ball.csv", -4.5, 4.5, 0.05,
               [](double y) { return -9.97 + std::sqrt(9.99 * 9.99 - y * y); });
  const Case c =
      ParseCase(SingleWheelCase("groove.csv", "ball.csv", 0.0, 0.5, 0.2, false, true, 500.0), dir,
                "ball_in_groove.toml");
  WheelRailOptions options;
  options.keep_fields = true;
  const WheelRailResult r = SolveWheelRail(c, options);
  ASSERT_EQ(r.patches.size(), 1u);
  const PatchResult& p = r.patches[0];
  EXPECT_NEAR(p.contact_angle, 0.0, 1e-9);  // symmetric: the planar plane is Oxy
  const Grid& g = p.grid;
  int i0 = -1;  // the column through the reference, x = 0
  for (int i = 0; i < g.nx; ++i) {
    if (std::fabs(g.x(i)) < 1e-12) i0 = i;
  }
  ASSERT_GE(i0, 0);
  int checked = 0;
  for (int j = 0; j < g.ny; ++j) {
    const double y = p.curve_y[j], z = p.curve_z[j];
    const double theta = std::atan2(y, z + 10.0);
    if (std::fabs(y) > 4.0) continue;  // stay clear of the profile ends
    // On the circle of radius 10 about [0, −10]; the pairing of equal arc-length steps on
    // radii 10.01 and 9.99 moves the mean off it by 10·Δθ²/8 < 1e-8 mm.
    EXPECT_NEAR(std::hypot(y, z + 10.0), 10.0, 1e-6) << "j " << j;
    EXPECT_NEAR(p.curve_angle[j], -theta, 1e-6) << "j " << j;
    const double s2 = 0.03 * 0.03 * std::sin(theta) * std::sin(theta);
    const double hand = (-0.03 * std::cos(theta) + std::sqrt(10.01 * 10.01 - s2)) -
                        (0.03 * std::cos(theta) + std::sqrt(9.99 * 9.99 - s2));
    EXPECT_NEAR(p.h[g.index(i0, j)], hand, 1e-6) << "j " << j << " theta " << theta;
    ++checked;
  }
  EXPECT_GE(checked, 30);
  EXPECT_NEAR(p.h[g.index(i0, g.ny / 2)], -0.04, 1e-3);  // the 0.04 mm interpenetration
}

// Paper Fig. 10: a cylinder rolling freely on a plane. At x the wheel surface is inclined by
// θ = asin(x/R), the wheel particle moves at −V cos θ, the rail at −V, so measured along x the
// rigid slip is w_x = −(1 − cos θ); the mid-plane correction (Eq. 20) measures it half-way
// between the two velocity directions, where it vanishes.
TEST(CurvedReference, MidplaneCorrectionRemovesArtificialSlip) {
  const fs::path dir = fs::temp_directory_path() / "wrc_midplane";
  fs::create_directories(dir);
  WriteProfile(dir / "plane.csv", -20.0, 20.0, 0.5, [](double) { return 0.0; });
  WriteProfile(dir / "cylinder.csv", -15.0, 15.0, 0.5, [](double) { return 0.0; });
  const double radius = 460.0;
  for (bool midplane : {false, true}) {
    const Case c = ParseCase(
        SingleWheelCase("plane.csv", "cylinder.csv", 0.01, 0.25, 0.5, true, midplane, radius), dir,
        "midplane.toml");
    WheelRailOptions options;
    options.keep_fields = true;
    const WheelRailResult r = SolveWheelRail(c, options);
    ASSERT_EQ(r.patches.size(), 1u);
    const PatchResult& p = r.patches[0];
    double worst = 0.0, largest = 0.0;
    for (int j = 0; j < p.grid.ny; ++j) {
      for (int i = 0; i < p.grid.nx; ++i) {
        const std::size_t k = p.grid.index(i, j);
        if (p.h[k] > 0.0) continue;
        const double x = p.grid.x(i);
        const double expected =
            midplane ? 0.0 : -(1.0 - std::sqrt(radius * radius - x * x) / radius);
        worst = std::max(worst, std::fabs(p.wx[k] - expected));
        largest = std::max(largest, std::fabs(expected));
        EXPECT_NEAR(p.ws[k], 0.0, 1e-12);
      }
    }
    // Round-off of velocities of ~1e3 mm/s divided by V: 1e-12 relative is ample.
    EXPECT_LT(worst, 1e-12) << "midplane " << midplane;
    if (!midplane) {
      EXPECT_GT(largest, 1e-5);  // the artificial slip is there to be removed
    }
  }
}

// Heavy-haul pair of paper §4.1 (y = 14.85 mm) swept in z through the appearance of the tread
// region (normal problem only). The largest second difference of fz between neighbours
// measures a jump: for a continuous, smooth fz(z) it falls ~4x when the step is halved; a jump
// keeps it.
double LargestJump(Case c, double z0, double z1, int steps) {
  std::vector<double> fz;
  for (int k = 0; k <= steps; ++k) {
    c.state.z = z0 + (z1 - z0) * k / steps;
    fz.push_back(SolveWheelRail(c).force_T(2));
  }
  double worst = 0.0;
  for (int k = 1; k + 1 < steps; ++k) {
    const double d0 = fz[k] - fz[k - 1], d1 = fz[k + 1] - fz[k], d2 = fz[k + 2] - fz[k + 1];
    worst = std::max(worst, std::fabs(d1 - 0.5 * (d0 + d2)));
  }
  return worst;
}

Case HeavyHaul(ReferenceSurface reference, double combine_distance) {
  Case c = LoadCase(fs::path(WRC_TEST_DATA_DIR) / "reference" / "cases" / "heavy_haul" /
                    "heavy_haul_z1.087.toml");
  c.effects.tangential = false;
  c.method.reference = reference;
  c.method.combine_distance = combine_distance;
  if (reference == ReferenceSurface::kPlanar) {
    c.method.position = ReferencePosition::kInitial;
    c.method.angle = ReferenceAngle::kSampled;
  }
  return c;
}

TEST(CurvedReference, ContinuousWhereThePlanarMethodJumps) {
  // Curved reference with the greedy combination of the paper (combine distance 30 mm): the
  // regions form one patch throughout, so fz(z) is smooth (ratio ~0.25).
  const Case curved = HeavyHaul(ReferenceSurface::kCurved, 30.0);
  const double c8 = LargestJump(curved, 1.12, 1.20, 8);
  const double c16 = LargestJump(curved, 1.12, 1.20, 16);
  EXPECT_LT(c16 / c8, 0.5) << c8 << " " << c16;
  // Planar, initial contact point, separate patches that merge near z = 1.185 mm: the jump at
  // the merge does not shrink with the step.
  const Case planar = HeavyHaul(ReferenceSurface::kPlanar, 2.0);
  const double p8 = LargestJump(planar, 1.16, 1.20, 8);
  const double p16 = LargestJump(planar, 1.16, 1.20, 16);
  EXPECT_GT(p16 / p8, 0.8) << p8 << " " << p16;
  EXPECT_GT(p16, 5.0 * c16);
}

}  // namespace
}  // namespace wrc
