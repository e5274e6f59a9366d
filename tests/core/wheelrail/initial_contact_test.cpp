// The planar method with the initial contact point (icp) against CONTACT on the Manchester
// cases. CONTACT's results there are for the weighted centre and weighted angle (wgt-wgt-2); the
// initial contact point changes the position of the planar patch, the sampled angle its
// orientation. With the weighted angle, icp has to reproduce CONTACT within the 1 % of the load
// the planar group is held to; the sampled angle differs from CONTACT's by the difference of the
// two angle definitions, which is computed here from the rail's points independently of wrc.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "wrc/core/case.h"
#include "wrc/core/wheelrail.h"

namespace wrc {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kPlanarCases = fs::path(WRC_TEST_DATA_DIR) / "reference" / "cases" / "mbench_planar";

json Reference(const std::string& name) {
  return json::parse(std::ifstream(kPlanarCases / (name + ".contact.json")));
}

Case PlanarCase(const std::string& name, ReferencePosition position, ReferenceAngle angle) {
  Case c = LoadCase(kPlanarCases / (name + ".toml"));
  c.method.position = position;
  c.method.angle = angle;
  return c;
}

// The rail profile's raw points (y, z) of the SIMPACK file, in file order.
std::vector<Eigen::Vector2d> RailPoints() {
  std::ifstream in(fs::path(WRC_TEST_DATA_DIR) / "profiles" / "MBench_UIC60_v3.prr");
  std::vector<Eigen::Vector2d> points;
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    double y = 0.0, z = 0.0;
    std::string rest;
    if (fields >> y >> z && !(fields >> rest)) points.emplace_back(y, z);
  }
  return points;
}

// Inclination atan(dz/dy) of the rail's points at lateral position y_r, from quadratics in arc
// length through the five points nearest to it: independent of wrc's spline and search.
double RailInclinationAt(const std::vector<Eigen::Vector2d>& points, double y_r) {
  std::size_t nearest = 2;
  for (std::size_t k = 2; k + 2 < points.size(); ++k) {
    if (std::fabs(points[k](0) - y_r) < std::fabs(points[nearest](0) - y_r)) nearest = k;
  }
  Eigen::Matrix<double, 5, 3> a;
  Eigen::Matrix<double, 5, 2> b;
  double s = 0.0;
  for (int i = 0; i < 5; ++i) {
    const Eigen::Vector2d& p = points[nearest - 2 + i];
    if (i > 0) s += (p - points[nearest - 3 + i]).norm();
    a.row(i) << 1.0, s, s * s;
    b.row(i) = p.transpose();
  }
  const Eigen::Matrix<double, 3, 2> c = a.colPivHouseholderQr().solve(b);
  // The arc length where y = y_r (Newton on the quadratic), then the slope there.
  double at = a(2, 1);
  for (int it = 0; it < 20; ++it) {
    const double f = c(0, 0) + c(1, 0) * at + c(2, 0) * at * at - y_r;
    at -= f / (c(1, 0) + 2.0 * c(2, 0) * at);
  }
  const double dy = c(1, 0) + 2.0 * c(2, 0) * at, dz = c(1, 1) + 2.0 * c(2, 1) * at;
  return std::atan(dz / dy);
}

// Every Manchester planar case, tread to flange climb: the initial contact point with the
// weighted angle gives CONTACT's totals within 1 % of the load and its angle within 0.5°,
// the tolerances of the planar reference group.
TEST(InitialContactPoint, WithTheWeightedAngleMatchesContact) {
  for (const char* name : {"mbench_planar_y0", "mbench_planar_y2", "mbench_planar_y4",
                           "mbench_planar_y6", "mbench_planar_y8", "mbench_planar_y10"}) {
    const json ref = Reference(name);
    const WheelRailResult r =
        SolveWheelRail(PlanarCase(name, ReferencePosition::kInitial, ReferenceAngle::kWeighted));
    const json& f = ref["rail_forces_track"];
    const double load = std::fabs(f["fz"].get<double>());
    ASSERT_EQ(r.patches.size(), ref["patches"].size()) << name;
    EXPECT_NEAR(r.force_T(0), f["fx"].get<double>(), 0.01 * load) << name;
    EXPECT_NEAR(r.force_T(1), f["fy"].get<double>(), 0.01 * load) << name;
    for (std::size_t k = 0; k < r.patches.size(); ++k) {
      EXPECT_NEAR(r.patches[k].contact_angle, ref["patches"][k]["contact_angle"].get<double>(),
                  0.5 * M_PI / 180.0)
          << name << " patch " << k;
    }
  }
}

// The flange case (y = 8 mm, 69°): the sampled angle is the rail's inclination at the initial
// contact point, turned by the cant (the rail stands at 1/40 in the track), to 0.3 mrad (the
// five points span 0.3 mm of a 13 mm gauge-corner radius: a quadratic's error there is below
// 0.01 mrad; the rest is the point's position, 0.01 mm). Its force difference to CONTACT's
// weighted angle is what that angle difference makes of a prescribed vertical force:
// fy = fz tan(δ + ...) turns by fz (1 + (fy/fz)²) Δδ, to 15 % (the tangential force turns too).
TEST(InitialContactPoint, SampledAngleIsTheRailsInclinationThere) {
  const json ref = Reference("mbench_planar_y8");
  const WheelRailResult r = SolveWheelRail(
      PlanarCase("mbench_planar_y8", ReferencePosition::kInitial, ReferenceAngle::kSampled));
  ASSERT_EQ(r.patches.size(), 1u);
  const PatchResult& p = r.patches[0];
  const double cant = 0.025;  // rad, of the case
  EXPECT_NEAR(p.contact_angle, RailInclinationAt(RailPoints(), p.reference_rail(0)) - cant, 3e-4);
  const double fz = ref["rail_forces_track"]["fz"].get<double>();
  const double fy = ref["rail_forces_track"]["fy"].get<double>();
  const double d_angle = p.contact_angle - ref["patches"][0]["contact_angle"].get<double>();
  const double predicted = -fz * (1.0 + (fy / fz) * (fy / fz)) * d_angle;
  EXPECT_GT(std::fabs(d_angle), 1e-3);  // the definitions differ here by more than 1 mrad
  EXPECT_NEAR(r.force_T(1) - fy, predicted, 0.15 * std::fabs(predicted));
}

// A worn pair whose measured rail ends just beyond the gauge corner: at y = 1 mm and 100 kN the
// initial contact point lies at the rail profile's end, where the resultant's location cannot be
// put on the rail. The solve still ends with finite forces, no location, and the warning that
// names the truncated profile (it once stopped with "arc length nan").
TEST(InitialContactPoint, AtTheEndOfTheRailProfileWarnsInsteadOfFailing) {
  const std::string text = R"([problem]
type = "wheel-rail"
[rail]
profile = "rail_left_iter795.ban"
smooth = 2.0
mirror_y = true
[wheel]
profile = "whl_left_iter795.whl"
smooth = 2.0
[track]
gauge_height = 14.0
cant = 0.025
[wheelset]
flange_back_distance = 1360.0
flange_back_position = 0.0
nominal_radius = 460.0
[friction]
alpha_deg = [-30.0, -20.0]
mu = [0.2, 0.35]
[grid]
dx = 0.5
ds = 0.5
[method]
reference = "planar"
position = "initial"
angle = "sampled"
[state]
velocity = 15000.0
y = 1.0
fz = 100000.0
)";
  const WheelRailResult r = SolveWheelRail(
      ParseCase(text, fs::path(WRC_SOURCE_DIR) / "tables" / "profiles", "icp_end.toml"));
  EXPECT_EQ(r.status, SolverStatus::kConverged);
  EXPECT_NEAR(r.force_T(2), 1e5, 1e-6 * 1e5 + 1e-3);
  EXPECT_TRUE(std::isfinite(r.force_T(1)));
  EXPECT_FALSE(r.has_force_location);
  bool warned = false;
  for (const std::string& w : r.warnings) {
    warned = warned || w.find("reaches an end of the rail profile") != std::string::npos;
  }
  EXPECT_TRUE(warned);
}

}  // namespace
}  // namespace wrc
