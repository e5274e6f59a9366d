// Quasi-static curving: the equilibrium against the closed-form solution of a bogie without
// primary yaw stiffness on linear creep, and against the balance of the whole bogie's lateral
// forces and yaw moments (the unbalanced force of every body and the car body's share) with
// saturating creep forces in a curve with cant deficiency.

#include "studies/dynamics/curving.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "studies/dynamics/forces.h"
#include "tests/studies/dynamics/vehicle_test_util.h"
#include "wrc/core/errors.h"

namespace wrc::dynamics {
namespace {

using test::Vehicle;
using test::VehicleCreep;

// Without primary yaw stiffness and with the cant balancing the speed, each wheelset rolls on
// its pure-rolling line y = b·r0/(λR), where its longitudinal creepages vanish; the frame
// centres the primary's lateral forces between them, its yaw set by the car body's chord
// against the primary's lateral springs acting over the wheelbase (derivation: the six
// equations solved by hand, with k1 the primary lateral stiffness per axlebox).
TEST(Curving, WithoutPrimaryYawStiffnessWheelsetsRollOnThePureRollingLine) {
  BogieParameters p = Vehicle();
  p.primary_longitudinal_stiffness = 0.0;
  const LinearContact c = VehicleCreep();
  CurveCase curve;
  curve.radius = 600e3;
  curve.speed = 20000.0;
  curve.cant = curve.speed * curve.speed / curve.radius * curve.rail_spacing / 9810.0;
  ASSERT_NEAR(curve.UnbalancedAcceleration(), 0.0, 1e-9);
  const ForceSource forces[2] = {c, c};
  const CurvingResult r = SolveCurving(p, curve, forces);
  ASSERT_TRUE(r.converged) << r.residual;

  const double kappa = 1.0 / curve.radius, a = p.semi_wheelbase;
  const double y = c.semi_spacing * c.nominal_radius / (c.conicity * curve.radius);
  const double k1 = p.primary_lateral_stiffness;
  const double k_yaw2 = 2.0 * p.secondary_longitudinal_stiffness * p.secondary_semi_spacing *
                        p.secondary_semi_spacing;
  const double frame_yaw = k_yaw2 * p.bogie_semi_spacing * kappa / (k_yaw2 + 4.0 * k1 * a * a);
  const double lateral = 2.0 * k1 * a * frame_yaw;  // primary force on the leading wheelset
  // 10⁻⁶ mm and 10⁻⁹ rad: the residual's 1 N over stiffnesses of 10³–10⁷ N/mm.
  EXPECT_NEAR(r.position(0), y, 1e-6);
  EXPECT_NEAR(r.position(2), y, 1e-6);
  EXPECT_NEAR(r.position(4), y - 0.5 * a * a * kappa, 1e-6);
  EXPECT_NEAR(r.position(5), frame_yaw, 1e-9);
  EXPECT_NEAR(r.position(1), -lateral / (2.0 * c.f22), 1e-9);
  EXPECT_NEAR(r.position(3), lateral / (2.0 * c.f22), 1e-9);
}

// Creep forces that saturate at 40 kN per wheelset (as friction does): the equilibrium must
// still balance the bogie as a whole.
struct SaturatingCreep {
  LinearContact linear;
  ContactLoads operator()(const State& s, double velocity) const {
    ContactLoads l = linear(s, velocity);
    constexpr double kLimit = 40000.0;  // N
    l.fy = kLimit * std::tanh(l.fy / kLimit);
    l.mz = kLimit * linear.semi_spacing * std::tanh(l.mz / (kLimit * linear.semi_spacing));
    return l;
  }
};

TEST(Curving, TheWholeBogieBalancesItsUnbalancedForceAndYawMoment) {
  const BogieParameters p = Vehicle();
  ASSERT_EQ(p.curving.radii.size(), 3u);
  const SaturatingCreep creep{VehicleCreep(500.0)};
  const ForceSource forces[2] = {creep, creep};
  for (const double radius : p.curving.radii) {
    const CurveCase curve = CurveCase::WithDeficiency(radius, p.curving);
    EXPECT_NEAR(curve.UnbalancedAcceleration(), 9810.0 * 100.0 / 1500.0, 1e-9);
    const CurvingResult r = SolveCurving(p, curve, forces);
    ASSERT_TRUE(r.converged) << radius << ": " << r.residual;
    // Lateral: the creep forces carry every body's unbalanced force, the car body's half too.
    const double mass = 2.0 * p.wheelset_mass + p.frame_mass + 0.5 * p.body_mass;
    const double unbalanced = mass * curve.UnbalancedAcceleration() / 1000.0;  // N
    EXPECT_NEAR(r.loads[0].fy + r.loads[1].fy + unbalanced, 0.0, 6.0 * kCurvingResidual);
    // Yaw about the bogie centre: the contact's moments against the secondary yaw springs
    // turned by the car body's chord.
    const double a = p.semi_wheelbase;
    const double contact = r.loads[0].mz + r.loads[1].mz + a * (r.loads[0].fy - r.loads[1].fy);
    const double secondary = -2.0 * p.secondary_longitudinal_stiffness * p.secondary_semi_spacing *
                             p.secondary_semi_spacing *
                             (r.position(5) - p.bogie_semi_spacing / radius);
    EXPECT_NEAR(contact + secondary, 0.0, 6.0 * kCurvingResidual * a);
    // Outwards in the curve, and the tighter the further.
    EXPECT_GT(r.position(0), 0.0) << radius;
  }
}

// A low-conicity pair whose wheelsets run to the flange in every curve: beyond 6 mm the flange
// adds a lateral force that rises to 10 kN within 0.05 mm and then stiffens (two-point contact, as
// on a worn rail). The equilibrium lies on that steep rise; it must be found and balance the
// bogie.
struct FlangeContact {
  LinearContact creep;
  ContactLoads operator()(const State& s, double velocity) const {
    ContactLoads l = creep(s, velocity);
    // 10 kN over the first 0.05 mm beyond the flange root (2·10⁵ N/mm), then 2·10⁴ N/mm.
    constexpr double kRoot = 6.0, kRise = 0.05, kJump = 10000.0, kStiffness = 20000.0;
    const double beyond = std::fabs(s.y) - kRoot;
    if (beyond > 0.0) {
      const double flange =
          beyond < kRise ? kJump * beyond / kRise : kJump + kStiffness * (beyond - kRise);
      l.fy -= std::copysign(flange, s.y);
    }
    return l;
  }
};

TEST(Curving, AnEquilibriumAtTheFlangeIsFound) {
  const BogieParameters p = Vehicle();
  LinearContact creep = VehicleCreep();
  creep.conicity = 0.005;  // the rolling-radius difference cannot steer it round the curve
  const FlangeContact flange{creep};
  const ForceSource forces[2] = {flange, flange};
  for (const double radius : p.curving.radii) {
    const CurveCase curve = CurveCase::WithDeficiency(radius, p.curving);
    const CurvingResult r = SolveCurving(p, curve, forces);
    ASSERT_TRUE(r.converged) << radius << ": " << r.residual;
    const double mass = 2.0 * p.wheelset_mass + p.frame_mass + 0.5 * p.body_mass;
    const double unbalanced = mass * curve.UnbalancedAcceleration() / 1000.0;  // N
    EXPECT_NEAR(r.loads[0].fy + r.loads[1].fy + unbalanced, 0.0, 6.0 * kCurvingResidual);
    EXPECT_GT(r.position(0), 6.0) << radius;  // the leading wheelset at its flange
  }
}

TEST(Curving, CurvingSectionErrorsNameTheKey) {
  const auto message = [](const std::string& curving) {
    std::string text =
        "[wheelset]\nmass = 1.0\nyaw_inertia = 1.0\n[frame]\nmass = 1.0\n"
        "yaw_inertia = 1.0\nsemi_wheelbase = 1.0\n[body]\nmass = 1.0\n"
        "[primary]\nlateral_stiffness = 1.0\nlongitudinal_stiffness = 1.0\n"
        "semi_spacing = 1.0\n[secondary]\nlateral_stiffness = 1.0\n"
        "longitudinal_stiffness = 1.0\nsemi_spacing = 1.0\n[curving]\n" +
        curving;
    try {
      ParseBogieParameters(text, "v.toml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("radii = [600e3]\ncant = 150.0\ncant_deficiency = 0.0\n"), "no error");
  EXPECT_NE(message("radii = [600e3, -1.0]\ncant = 1.0\ncant_deficiency = 0.0\n")
                .find("curving.radii[1] must be positive"),
            std::string::npos);
  const std::string empty = message("radii = []\ncant = 1.0\ncant_deficiency = 0.0\n");
  EXPECT_NE(empty.find("curving.radii = []: must not be empty"), std::string::npos) << empty;
  EXPECT_NE(message("radii = [600e3]\ncant = 1.0\n").find("curving.cant_deficiency"),
            std::string::npos);
  EXPECT_NE(message("radius = [600e3]\n").find("did you mean radii"), std::string::npos);
}

}  // namespace
}  // namespace wrc::dynamics
