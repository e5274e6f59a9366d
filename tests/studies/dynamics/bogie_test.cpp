// The bogie model: the integrator against the exact solution of the linearised model, hunting
// against the eigenvalues, the critical speed against time integration, the limit of a frame
// held still against the single-wheelset model, and the shipped vehicle file.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "studies/dynamics/analysis.h"
#include "studies/dynamics/bogie.h"
#include "studies/dynamics/forces.h"
#include "tests/studies/dynamics/vehicle_test_util.h"
#include "wrc/core/errors.h"

namespace wrc::dynamics {
namespace {

constexpr double kPi = 3.14159265358979323846;

using test::Vehicle;
using test::VehicleCreep;

// That contact as its Jacobian at `speed` (mm/s).
LinearisedContact Linearised(const LinearContact& c, double speed) {
  LinearisedContact linear;
  linear.speed = speed;
  linear.jacobian = LinearisedLoads(c, State{}, speed, Eigen::Vector4d(0.1, 1e-4, 1.0, 1e-3));
  return linear;
}

LinearisedContact TestContact() { return Linearised(VehicleCreep(), 30000.0); }

// x(t) = e^{At} x0, by Eigen's matrix exponential (scaling and squaring with Padé
// approximants): the eigenvectors of A are too ill-conditioned to serve at 1e-9.
BogieVector ExactSolution(const BogieMatrix& a, const BogieVector& x0, double t) {
  const BogieMatrix at = a * t;
  return at.exp() * x0;
}

BogieTrajectory Simulate(BogieParameters p, const LinearisedContact& contact, double v) {
  const ForceSource forces[2] = {contact, contact};
  return SimulateBogie(p, forces, v);
}

TEST(BogieDynamics, ShippedVehicleCarriesItsPublishedWheelLoad) {
  const BogieParameters p = Vehicle();
  // (32 000/2 + 2615 + 2·1813) kg · 9.81 m/s² / 4.
  EXPECT_NEAR(p.WheelLoad(), 54546.05, 0.01);
}

// The study's step against e^{At} x0 (whose own accuracy, about 1e-8 mm here, is the floor), and
// the order from the step's own convergence: halving the step divides the change by 2^4 = 16
// (12–20 allows for higher-order terms).
TEST(BogieDynamics, Rk4IsFourthOrderAgainstTheExactLinearSolution) {
  const BogieParameters base = Vehicle();
  const LinearisedContact contact = TestContact();
  const double v = 40000.0, t = 0.25;
  BogieVector x0 = BogieVector::Zero();
  x0(0) = base.initial_y;
  const BogieVector exact = ExactSolution(BogieLinearSystem(base, contact, v), x0, t);
  std::vector<double> y;
  for (double h : {2e-3, 1e-3, 5e-4}) {
    BogieParameters p = base;
    p.time_step = h;
    p.duration = t;
    y.push_back(Simulate(p, contact, v).y.back());
  }
  EXPECT_LT(std::fabs(y[1] - exact(0)), 1e-6 * base.initial_y);  // the study's step
  const double ratio = std::fabs(y[0] - y[1]) / std::fabs(y[1] - y[2]);
  EXPECT_GT(ratio, 12.0);
  EXPECT_LT(ratio, 20.0);
}

TEST(BogieDynamics, HuntingFrequencyAndGrowthRateAreTheDominantEigenvalue) {
  const BogieParameters p = Vehicle();
  const LinearisedContact contact = TestContact();
  const double critical = BogieCriticalSpeed(p, contact, 5000.0, 200000.0);
  ASSERT_FALSE(std::isnan(critical));
  for (double v : {0.8 * critical, 1.1 * critical}) {
    const std::complex<double> lambda = DominantEigenvalue(BogieLinearSystem(p, contact, v));
    const Hunting h = MeasureHunting(Simulate(p, contact, v).Leading(), 1.0);
    EXPECT_NEAR(h.frequency, std::fabs(lambda.imag()) / (2 * kPi), 0.01 * h.frequency) << v;
    EXPECT_NEAR(h.growth_rate, lambda.real(), 0.05) << v;
  }
}

TEST(BogieDynamics, CriticalSpeedByTimeIntegrationMatchesTheEigenvalues) {
  const BogieParameters p = Vehicle();
  const LinearisedContact contact = TestContact();
  const double expected = BogieCriticalSpeed(p, contact, 5000.0, 200000.0);
  ASSERT_FALSE(std::isnan(expected));
  double lo = 0.7 * expected, hi = 1.3 * expected;
  while (hi - lo > 0.002 * expected) {
    const double mid = 0.5 * (lo + hi);
    (MeasureHunting(Simulate(p, contact, mid).Leading(), 1.0).growth_rate < 0.0 ? lo : hi) = mid;
  }
  EXPECT_NEAR(0.5 * (lo + hi), expected, 0.01 * expected);
}

// With the frame held still (as good as infinitely heavy) each wheelset is the single-wheelset
// model on the primary suspension: the single wheelset's dominant eigenvalue is one of the
// bogie's (the frame's own, near zero, are others).
TEST(BogieDynamics, AFrameHeldStillLeavesTwoSingleWheelsets) {
  BogieParameters p = Vehicle();
  p.frame_mass = p.frame_yaw_inertia = 1e12;
  Parameters single;
  single.mass = p.wheelset_mass;
  single.yaw_inertia = p.wheelset_yaw_inertia;
  single.lateral_stiffness = p.primary_lateral_stiffness;
  single.longitudinal_stiffness = p.primary_longitudinal_stiffness;
  single.spring_semi_spacing = p.primary_semi_spacing;
  const LinearContact c = VehicleCreep();
  const LinearisedContact linear = Linearised(c, 50000.0);
  for (double v : {20000.0, 80000.0}) {
    const Eigen::Matrix<std::complex<double>, 12, 1> bogie =
        Eigen::EigenSolver<BogieMatrix>(BogieLinearSystem(p, linear, v), false).eigenvalues();
    const Eigen::Vector4cd e =
        Eigen::EigenSolver<Eigen::Matrix4d>(LinearSystem(single, c, v), false).eigenvalues();
    int k = 0;
    for (int i = 1; i < 4; ++i) k = e(i).real() > e(k).real() ? i : k;
    double nearest = INFINITY;
    for (int i = 0; i < 12; ++i) nearest = std::min(nearest, std::abs(bogie(i) - e(k)));
    EXPECT_LT(nearest, 1e-6 * std::abs(e(k))) << v << ": " << e(k);
  }
}

TEST(BogieDynamics, VehicleFileErrorsNameTheKey) {
  const auto message = [](const std::string& text) {
    try {
      ParseBogieParameters(text, "v.toml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("[frame]\nmas = 1.0\n").find("did you mean mass"), std::string::npos);
  EXPECT_NE(message("[fram]\n").find("did you mean [frame]"), std::string::npos);
  EXPECT_NE(message("[wheelset]\nmass = -1.0\n").find("wheelset.mass = -1: must be positive"),
            std::string::npos);
  EXPECT_NE(message("[wheelset]\nmass = 1.0\nyaw_inertia = 1.0\n").find("frame.mass"),
            std::string::npos);
}

}  // namespace
}  // namespace wrc::dynamics
