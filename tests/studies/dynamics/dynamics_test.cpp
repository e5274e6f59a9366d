// The wheelset model of `wrc study dynamics`: the integrator against the exact solution of the
// linear model, hunting frequency, growth rate and critical speed against its eigenvalues and
// Klingel's kinematic frequency, and the table-driven forces against full solves.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <string>

#include "studies/dynamics/analysis.h"
#include "studies/dynamics/forces.h"
#include "studies/dynamics/model.h"
#include "tests/generator/generator_test_util.h"
#include "wrc/core/errors.h"
#include "wrc/core/scene.h"
#include "wrc/core/wheelrail.h"
#include "wrc/generator/generator.h"

namespace wrc::dynamics {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Manchester wheelset mass and inertia with a soft suspension (the study's parameter file).
Parameters TestParameters() {
  return ParseParameters(
      "[wheelset]\nmass = 1813.0\nyaw_inertia = 1120.0\nwheel_load = 12500.0\n"
      "[suspension]\nlateral_stiffness = 100.0\nlongitudinal_stiffness = 100.0\n"
      "semi_spacing = 1000.0\n[simulation]\ntime_step = 0.001\nduration = 2.0\ninitial_y = 1.0\n",
      "test.toml");
}

// Kalker-size creep coefficients of a 12.5 kN contact, conicity of a worn profile.
LinearContact TestContact() {
  LinearContact c;
  c.f11 = 3.0e6;
  c.f22 = 2.7e6;
  c.conicity = 0.15;
  c.semi_spacing = 750.0;
  c.nominal_radius = 460.0;
  return c;
}

// The exact solution x(t) = V e^{Λt} V⁻¹ x0 of ẋ = A x.
Eigen::Vector4d ExactSolution(const Eigen::Matrix4d& a, const Eigen::Vector4d& x0, double t) {
  const Eigen::EigenSolver<Eigen::Matrix4d> eig(a);
  const Eigen::Matrix4cd v = eig.eigenvectors();
  Eigen::Vector4cd lambda_t = eig.eigenvalues() * t;
  const Eigen::Vector4cd c = v.inverse() * x0.cast<std::complex<double>>();
  Eigen::Vector4cd x = v * (lambda_t.array().exp() * c.array()).matrix();
  return x.real();
}

// The eigenvalue with the largest real part.
std::complex<double> Dominant(const Eigen::Matrix4d& a) {
  const Eigen::Vector4cd e = Eigen::EigenSolver<Eigen::Matrix4d>(a, false).eigenvalues();
  int k = 0;
  for (int i = 1; i < 4; ++i) {
    if (e(i).real() > e(k).real()) k = i;
  }
  return e(k);
}

TEST(WheelsetDynamics, Rk4IsFourthOrderAgainstTheExactLinearSolution) {
  const Parameters base = TestParameters();
  const LinearContact contact = TestContact();
  const double v = 30000.0;
  const Eigen::Vector4d exact =
      ExactSolution(LinearSystem(base, contact, v), Eigen::Vector4d(base.initial_y, 0, 0, 0), 1.0);
  double previous = 0.0;
  for (double h : {4e-3, 2e-3, 1e-3}) {
    Parameters p = base;
    p.time_step = h;
    p.duration = 1.0;
    const Trajectory run = Simulate(p, contact, v);
    const double error = std::fabs(run.y.back() - exact(0));
    if (h == 1e-3) {
      EXPECT_LT(error, 1e-6 * base.initial_y);  // the study's step
    }
    // Halving the step divides the error by 2^4 = 16 (12–20 allows for higher-order terms).
    if (previous > 0.0) {
      EXPECT_GT(previous / error, 12.0) << "h = " << h;
      EXPECT_LT(previous / error, 20.0) << "h = " << h;
    }
    previous = error;
  }
}

TEST(WheelsetDynamics, HuntingFrequencyAndGrowthRateAreTheDominantEigenvalue) {
  const Parameters p = TestParameters();
  const LinearContact contact = TestContact();
  for (double v : {20000.0, 60000.0}) {
    const std::complex<double> lambda = Dominant(LinearSystem(p, contact, v));
    const Hunting h = MeasureHunting(Simulate(p, contact, v), 0.3);
    EXPECT_NEAR(h.frequency, std::fabs(lambda.imag()) / (2 * kPi), 0.005 * h.frequency) << v;
    EXPECT_NEAR(h.growth_rate, lambda.real(), 0.02) << v;
  }
}

TEST(WheelsetDynamics, CriticalSpeedByBisectionMatchesTheEigenvalues) {
  const Parameters p = TestParameters();
  const LinearContact contact = TestContact();
  const double expected = LinearCriticalSpeed(p, contact, 5000.0, 200000.0);
  ASSERT_FALSE(std::isnan(expected));
  double lo = 5000.0, hi = 200000.0;
  while (hi - lo > 50.0) {
    const double mid = 0.5 * (lo + hi);
    (MeasureHunting(Simulate(p, contact, mid), 0.3).growth_rate < 0.0 ? lo : hi) = mid;
  }
  EXPECT_NEAR(0.5 * (lo + hi), expected, 0.005 * expected);
}

// With creep so stiff that the wheels cannot slip and no suspension, the wheelset rolls along
// Klingel's kinematic sine: ω = V·sqrt(λ / (r0·b)).
TEST(WheelsetDynamics, StiffCreepGivesKlingelsKinematicFrequency) {
  Parameters p = TestParameters();
  p.lateral_stiffness = p.longitudinal_stiffness = 0.0;
  LinearContact contact = TestContact();
  contact.f11 = contact.f22 = 1e7;  // stiffer would need a shorter step (yaw creep damping)
  p.duration = 6.0;
  const double v = 10000.0;
  const double klingel =
      v * std::sqrt(contact.conicity / (contact.nominal_radius * contact.semi_spacing)) / (2 * kPi);
  const Hunting h = MeasureHunting(Simulate(p, contact, v), 0.1);
  EXPECT_NEAR(h.frequency, klingel, 0.005 * klingel);
  EXPECT_NEAR(h.growth_rate, 0.0, 0.05);  // neutral, as the kinematic motion is
}

TEST(WheelsetDynamics, LinearisedLoadsAreTheLinearContactsCoefficients) {
  // The linear source is linear, so central differences give its coefficients up to
  // rounding: 1e-9 relative to the largest of them.
  LinearContact c = TestContact();
  c.gravity_stiffness = 123.0;
  const double v = 30000.0;
  State at;
  at.y = 0.7;
  at.yaw = 2e-4;
  const Eigen::Matrix<double, 2, 4> d =
      LinearisedLoads(c, at, v, Eigen::Vector4d(0.25, 1e-4, 3.0, 4e-3));
  const double b = c.semi_spacing;
  Eigen::Matrix<double, 2, 4> expected;
  expected << -c.gravity_stiffness, 2.0 * c.f22, -2.0 * c.f22 / v, 0.0,  //
      -2.0 * c.f11 * b * c.conicity / c.nominal_radius, 0.0, 0.0, -2.0 * c.f11 * b * b / v;
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 4; ++j) {
      EXPECT_NEAR(d(i, j), expected(i, j), 1e-9 * expected.cwiseAbs().row(i).maxCoeff())
          << i << "," << j;
    }
  }
}

// The least-squares slope through n samples a side out to ±h of f(y) = a·y + c·y³ (the even part
// cancels): a + c·h²·Σk⁴ / (n²·Σk²), k = 1..n, against the closed form; the yaw column,
// sampled once a side, is the central difference.
TEST(WheelsetDynamics, LinearisedLoadsFitALeastSquaresSlope) {
  constexpr double a = -500.0, c = 80.0, h = 0.5, q = 3.0;
  constexpr int n = 4;
  const ForceSource cubic = [](const State& s, double) {
    ContactLoads loads;
    loads.fy = a * s.y + c * s.y * s.y * s.y + q * s.y * s.y;
    loads.mz = 2.0 * loads.fy + 1e6 * s.yaw;
    return loads;
  };
  const Eigen::Matrix<double, 2, 4> d = LinearisedLoads(
      cubic, State{}, 1000.0, Eigen::Vector4d(h, 1e-4, 1.0, 1e-3), Eigen::Vector4i(n, 1, 1, 1));
  double k2 = 0.0, k4 = 0.0;
  for (int k = 1; k <= n; ++k) {
    k2 += k * k;
    k4 += k * k * k * k;
  }
  const double expected = a + c * h * h * k4 / (n * n * k2);  // 14.75 N/mm above a
  EXPECT_NEAR(d(0, 0), expected, 1e-9 * std::fabs(a));
  EXPECT_NEAR(d(1, 0), 2.0 * expected, 2e-9 * std::fabs(a));
  EXPECT_NEAR(d(1, 1), 1e6, 1e-3);
  EXPECT_THROW(
      LinearisedLoads(cubic, State{}, 1000.0, Eigen::Vector4d::Ones(), Eigen::Vector4i(0, 1, 1, 1)),
      std::invalid_argument);
}

// A roll proportional to y, roll = c·y, is found as the root of the wheels' height mismatch and
// interpolated exactly; the wheelset position whose wheels sit at w on their rails is then
// w / (1 − r0·c).
TEST(WheelsetDynamics, RollCurveGivesTheWheelsetPositionOfAWheelPosition) {
  constexpr double c = 1e-4, r0 = 460.0;
  const RollCurve roll(
      [](int side, double y, double r) { return side == WRC_RIGHT ? r - c * y : 0.0; }, 10.0, 0.25,
      -0.01, 0.01);
  EXPECT_EQ(roll.clamped(), 0);
  EXPECT_NEAR(roll(3.3), c * 3.3, 1e-12);
  for (const double w : {0.25, -0.25, 1.0, 4.0}) {
    EXPECT_NEAR(roll.WheelsetY(w, r0), w / (1.0 - r0 * c), 1e-9) << w;
  }
}

TEST(WheelsetDynamics, ParameterFileErrorsNameTheKey) {
  const auto message = [](const std::string& text) {
    try {
      ParseParameters(text, "m.toml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("[wheelset]\nmass = 1.0\nyaw_inertia = 1.0\nwheel_load = -5.0\n")
                .find("wheelset.wheel_load = -5: must be positive"),
            std::string::npos);
  EXPECT_NE(message("[wheelset]\nmas = 1.0\n").find("did you mean mass"), std::string::npos);
  EXPECT_NE(message("[wheelset]\nyaw_inertia = 1.0\n").find("wheelset.mass"), std::string::npos);
}

// ---- table against solver ----------------------------------------------------------------

// A tiny table of the Manchester pair (1 mm elements), nodes around the central position.
class TableAgainstSolver : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::ScratchDir("dynamics");
    const std::string text = test::TinyScene(
        "axes = [\"y_wheel\", \"fz\", \"roll\", \"yaw\", \"spin\"]\n"
        "y_wheel = [-1.0, 0.0, 1.0]\nfz = [12500.0]\nroll = [-0.001, 0.0, 0.001]\n"
        "yaw = [-0.002, -0.001, -0.0005, 0.0, 0.0005, 0.001, 0.002]\n"
        "spin = [-0.002, -0.001, -0.0005, 0.0, 0.0005, 0.001, 0.002]\n"
        "outputs = [\"fx\", \"fy\", \"fz\", \"mx\", \"my\", \"mz\", \"z\"]",
        "velocity = 2000.0");
    scene_ = new Scene(LoadScene(test::WriteFile(*dir_ / "scene.toml", text)));
    GenerateOptions options;
    options.output = *dir_ / "table.h5";
    options.threads = 2;
    options.progress = ProgressMode::kOff;
    options.warm_start = false;
    options.mpi = MpiMode::kOff;
    ASSERT_TRUE(GenerateTable(*scene_, options).complete);
    table_ = new wrc::Table(options.output.string());
    geometry_ = SceneGeometry(scene_->base, 12500.0);
  }
  static void TearDownTestSuite() {
    delete table_;
    delete scene_;
    delete dir_;
  }
  static inline test::ScratchDir* dir_ = nullptr;
  static inline Scene* scene_ = nullptr;
  static inline wrc::Table* table_ = nullptr;
  static inline ContactGeometry geometry_;
};

// At y = 0 the roll is 0 for both, and yaw ±2 mrad, spin 0 are nodes for both wheels: the
// table holds exactly the solver's forces there (to the fz tolerance, 1e-6 of the load).
TEST_F(TableAgainstSolver, ForcesAgreeAtANode) {
  TableForces table(*table_, geometry_, 1.0);
  SolverForces solver(scene_->base, geometry_, 1.0);
  State s;
  s.yaw = 0.002;
  const ContactLoads a = table(s, 30000.0), b = solver(s, 30000.0);
  EXPECT_GT(std::fabs(a.fy), 100.0);  // a real lateral force, not two zeros
  EXPECT_NEAR(a.fy, b.fy, 0.05);
  EXPECT_NEAR(a.mz, b.mz, 50.0);
  EXPECT_EQ(a.flags, 0);
}

// The solver is given vy and vyaw; the table reads the pose with the same creepages. Between
// nodes the two differ by the table's interpolation error and by what the equivalence leaves
// out (the yaw angle's small effect on the contact geometry, the contact's lateral position
// against the nominal b). Here the creep forces saturate at creepages of about 1e-3, and the
// yaw and spin nodes lie 0.5e-3 apart: linear interpolation across the bend is good to about 1 %
// of the wheel load for fy and 2 % of load × b for mz (measured: 0.4 % and 1.4 %).
TEST_F(TableAgainstSolver, ForcesAgreeBetweenNodesWithVelocities) {
  TableForces table(*table_, geometry_, 1.0);
  SolverForces solver(scene_->base, geometry_, 1.0);
  const double load = geometry_.wheel_load, b = geometry_.semi_spacing;
  for (const State& s : {State{0.4, 0.001, 20.0, 0.0}, State{-0.3, -0.0005, -30.0, 0.02},
                         State{0.2, 0.0, 0.0, -0.03}}) {
    const ContactLoads a = table(s, 30000.0), c = solver(s, 30000.0);
    EXPECT_NEAR(a.fy, c.fy, 0.01 * load) << s.y << " " << s.yaw;
    EXPECT_NEAR(a.mz, c.mz, 0.02 * load * b) << s.y << " " << s.yaw;
    EXPECT_GT(std::fabs(c.fy) + std::fabs(c.mz) / b, 0.02 * load);  // forces worth comparing
  }
}

// Steps that land on nodes (yaw ±0.5 mrad; vy and vyaw giving the same creepages, read on the
// yaw and spin nodes ±5e-4) make the table's derivatives at y = 0 the solver's, apart from what
// the velocity folds leave out (the yaw angle's effect on the geometry, the contact's lever
// against the nominal b: below 1 % for fy; for the yaw-rate damping of mz 1.9 % measured, as the
// lever enters squared, 3.3 mm beyond b here, and the table's spin axis carries no share of the
// yaw rate's spin creepage). The y column crosses roll values between nodes and is left out.
TEST_F(TableAgainstSolver, LinearisedContactAgreesOnNodes) {
  TableForces table(*table_, geometry_, 1.0);
  SolverForces solver(scene_->base, geometry_, 1.0);
  const double v = 30000.0;
  const Eigen::Vector4d h(0.5, 5e-4, 5e-4 * v, 5e-4 * v / geometry_.semi_spacing);
  const ForceSource table_source = [&table](const State& s, double speed) {
    return table(s, speed);
  };
  const ForceSource solver_source = [&solver](const State& s, double speed) {
    return solver(s, speed);
  };
  const Eigen::Matrix<double, 2, 4> a = LinearisedLoads(table_source, State{}, v, h),
                                    b = LinearisedLoads(solver_source, State{}, v, h);
  EXPECT_NEAR(a(0, 1), b(0, 1), 1e-3 * std::fabs(b(0, 1)));  // ∂Fy/∂ψ: both at nodes
  EXPECT_NEAR(a(1, 1), b(1, 1), 1e-3 * std::fabs(b(1, 1)));  // ∂Mz/∂ψ
  EXPECT_NEAR(a(0, 2), b(0, 2), 0.01 * std::fabs(b(0, 2)));  // ∂Fy/∂vy
  EXPECT_NEAR(a(1, 3), b(1, 3), 0.03 * std::fabs(b(1, 3)));  // ∂Mz/∂vyaw
  EXPECT_GT(std::fabs(b(0, 1)), 1e5);  // N/rad: a creep coefficient, not noise
}

// Both roll curves solve the same condition (equal wheelset heights at the load); the table's
// comes from interpolated heights, within its z accuracy over the track width.
TEST_F(TableAgainstSolver, RollCurvesAgree) {
  TableForces table(*table_, geometry_, 1.0);
  SolverForces solver(scene_->base, geometry_, 1.0);
  for (double y : {0.25, 0.5, 0.75}) {
    EXPECT_NEAR(table.roll_curve()(y), solver.roll_curve()(y), 5e-5) << y;
    EXPECT_NEAR(table.roll_curve()(-y), -table.roll_curve()(y), 1e-15);
  }
}

}  // namespace
}  // namespace wrc::dynamics
