// Quasi-static curving of the bogie (curving.h).

#include "studies/dynamics/curving.h"

#include <unsupported/Eigen/NonLinearOptimization>

#include <algorithm>
#include <cmath>

#include "studies/dynamics/model.h"

namespace wrc::dynamics {
namespace {

// Standard gravity, mm/s².
constexpr double kGravity = 9810.0;

// Central-difference steps of the contact's Jacobian: wide enough that the solver's convergence
// noise (about 10⁻⁶ of the load) stays below 10⁻³ of a difference, narrow against the flange
// climb's 0.1 mm width. The Jacobian only steers the iteration; the equilibrium is where the
// residual vanishes, whatever steps it took.
constexpr double kStepY = 0.02;    // mm
constexpr double kStepYaw = 2e-5;  // rad

// The unknowns scaled to similar sizes: lateral positions in mm, yaw angles in mrad.
constexpr double kYawScale = 1000.0;

using Vector = Eigen::VectorXd;
using Matrix = Eigen::MatrixXd;

// The bogie's equilibrium equations with the contact of both wheelsets: forces in N and moments
// over the semi-wheelbase in N, so that one tolerance serves both.
class Equations {
 public:
  Equations(const BogieParameters& p, const CurveCase& curve, const ForceSource (&forces)[2])
      : p_(p), curve_(curve), forces_(forces) {}

  // Powell's hybrid method's interface: the residual and its Jacobian.
  int operator()(const Vector& u, Vector& residual) {
    ContactLoads loads[2];
    Contact(u, loads);
    residual = Residual(u, loads);
    return 0;
  }
  int df(const Vector& u, Matrix& jacobian) {
    const ContactLoads none[2];
    const Vector base = Residual(u, none);
    jacobian.resize(6, 6);
    for (int j = 0; j < 6; ++j) jacobian.col(j) = Residual(u + Vector::Unit(6, j), none) - base;
    for (int k = 0; k < 2; ++k) AddContactJacobian(u, k, jacobian);
    return 0;
  }

  BogieVector Positions(const Vector& u) const {
    BogieVector x = BogieVector::Zero();
    for (int i = 0; i < 6; ++i) x(i) = i % 2 == 0 ? u(i) : u(i) / kYawScale;
    return x;
  }
  void Contact(const Vector& u, ContactLoads (&loads)[2]) {
    const BogieVector x = Positions(u);
    for (int k = 0; k < 2; ++k) loads[k] = forces_[k](Wheelset(x, k), curve_.speed);
    ++evaluations_;
  }
  BogieTrack Track(const Vector& u) const {
    BogieTrack track;
    track.curvature = 1.0 / curve_.radius;
    track.unbalanced_acceleration = curve_.UnbalancedAcceleration();
    // The body in steady state: its secondary springs carry its share of the unbalanced force
    // (two per bogie), and it lies along the chord between the bogie centres.
    const double share = 0.5 * p_.body_mass * track.unbalanced_acceleration / 1000.0;  // N
    track.body_y = u(4) + share / (2.0 * p_.secondary_lateral_stiffness);
    track.body_yaw = p_.bogie_semi_spacing * track.curvature;
    return track;
  }
  Vector Residual(const Vector& u, const ContactLoads (&loads)[2]) const {
    const BogieVector d = BogieDerivative(p_, Positions(u), loads, Track(u));
    const double a = p_.semi_wheelbase;
    Vector r(6);
    for (int k = 0; k < 2; ++k) {
      r(2 * k) = d(6 + 2 * k) * p_.wheelset_mass / 1000.0;
      r(2 * k + 1) = d(7 + 2 * k) * p_.wheelset_yaw_inertia * 1000.0 / a;
    }
    r(4) = d(10) * p_.frame_mass / 1000.0;
    r(5) = d(11) * p_.frame_yaw_inertia * 1000.0 / a;
    return r;
  }
  int evaluations() const { return evaluations_; }

 private:
  // The wheelset turns with the track: its yaw rate is the curve's, −V/R.
  State Wheelset(const BogieVector& x, int k) const {
    State s = WheelsetOf(x, k);
    s.vyaw = -curve_.speed / curve_.radius;
    return s;
  }
  // ∂(F_y, M_z/a)/∂(y_k, ψ_k) of wheelset k's contact, by central differences.
  void AddContactJacobian(const Vector& u, int k, Matrix& jacobian) {
    const double step[2] = {kStepY, kStepYaw * kYawScale};
    for (int j = 0; j < 2; ++j) {
      Vector plus = u, minus = u;
      plus(2 * k + j) += step[j];
      minus(2 * k + j) -= step[j];
      const BogieVector xp = Positions(plus), xm = Positions(minus);
      const ContactLoads lp = forces_[k](Wheelset(xp, k), curve_.speed);
      const ContactLoads lm = forces_[k](Wheelset(xm, k), curve_.speed);
      ++evaluations_;
      jacobian(2 * k, 2 * k + j) += (lp.fy - lm.fy) / (2.0 * step[j]);
      jacobian(2 * k + 1, 2 * k + j) += (lp.mz - lm.mz) / (2.0 * step[j] * p_.semi_wheelbase);
    }
  }

  const BogieParameters& p_;
  const CurveCase& curve_;
  const ForceSource (&forces_)[2];
  int evaluations_ = 0;
};

}  // namespace

CurveCase CurveCase::WithDeficiency(double radius, const CurvingSettings& settings) {
  CurveCase c;
  c.radius = radius;
  c.cant = settings.cant;
  c.rail_spacing = settings.rail_spacing;
  c.speed = std::sqrt(radius * kGravity * (settings.cant + settings.cant_deficiency) /
                      settings.rail_spacing);
  return c;
}

double CurveCase::UnbalancedAcceleration() const {
  return speed * speed / radius - kGravity * cant / rail_spacing;
}

namespace {

// Powell's hybrid method on one curve from `u`; the solution replaces `u`. True when the
// residual is below kCurvingResidual. `evaluations` counts the bogie's contact evaluations.
bool SolveFrom(const BogieParameters& p, const CurveCase& curve, const ForceSource (&forces)[2],
               Vector& u, int* evaluations) {
  Equations equations(p, curve, forces);
  Eigen::HybridNonLinearSolver<Equations> solver(equations);
  solver.parameters.xtol = 1e-12;  // relative step: far below the residual tolerance's reach
  solver.parameters.maxfev = 200;
  solver.solve(u);
  ContactLoads loads[2];
  equations.Contact(u, loads);
  *evaluations += equations.evaluations();
  return equations.Residual(u, loads).cwiseAbs().maxCoeff() < kCurvingResidual;
}

// The curve scaled by `lambda` in curvature and cant at the same speed: its unbalanced
// acceleration and every curvature term scale with lambda, and lambda = 0 is straight track,
// where centred running is the equilibrium.
CurveCase Scaled(const CurveCase& curve, double lambda) {
  CurveCase c = curve;
  c.radius = curve.radius / lambda;
  c.cant = curve.cant * lambda;
  return c;
}

// Continuation from straight track: where the direct solve from centred running stops short (an
// equilibrium at the flange, behind a jump of the contact from the tread), the curve is reached
// in steps of curvature, each solved from the last; a step that fails is halved, down to 1/64.
bool SolveByContinuation(const BogieParameters& p, const CurveCase& curve,
                         const ForceSource (&forces)[2], Vector& u, int* evaluations) {
  constexpr double kSmallestStep = 1.0 / 64.0;
  Vector reached = Vector::Zero(6);
  double lambda = 0.0, step = 0.25;
  while (lambda < 1.0) {
    const double next = std::min(1.0, lambda + step);
    Vector trial = reached;
    if (SolveFrom(p, Scaled(curve, next), forces, trial, evaluations)) {
      reached = trial;
      lambda = next;
      step = std::min(0.25, 2.0 * step);
    } else if ((step *= 0.5) < kSmallestStep) {
      return false;
    }
  }
  u = reached;
  return true;
}

}  // namespace

CurvingResult SolveCurving(const BogieParameters& p, const CurveCase& curve,
                           const ForceSource (&forces)[2]) {
  const RunClock clock;
  CurvingResult result;
  Vector u = Vector::Zero(6);
  if (!SolveFrom(p, curve, forces, u, &result.evaluations)) {
    Vector continued;
    if (SolveByContinuation(p, curve, forces, continued, &result.evaluations)) u = continued;
  }
  Equations equations(p, curve, forces);
  ContactLoads loads[2];
  equations.Contact(u, loads);
  const Vector residual = equations.Residual(u, loads);
  const BogieVector x = equations.Positions(u);
  result.position = x.head<6>();
  for (int k = 0; k < 2; ++k) result.loads[k] = loads[k];
  result.body_y = equations.Track(u).body_y;
  result.residual = residual.cwiseAbs().maxCoeff();
  result.converged = result.residual < kCurvingResidual;
  result.evaluations += equations.evaluations();
  result.seconds = clock.WallSeconds();
  return result;
}

}  // namespace wrc::dynamics
