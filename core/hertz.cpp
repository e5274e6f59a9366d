#include "wrc/core/hertz.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/common/numbers.h"
#include "core/gsl/elliptic.h"
#include "core/gsl/roots.h"

namespace wrc {
namespace {

void RequirePositiveFinite(double value, const char* name) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw std::invalid_argument(std::string("HertzContact: ") + name + " = " +
                                std::to_string(value) + ": must be positive and finite");
  }
}

void RequireNonNegativeFinite(double value, const char* name) {
  if (!(std::isfinite(value) && value >= 0.0)) {
    throw std::invalid_argument(std::string("HertzContact: ") + name + " = " +
                                std::to_string(value) + ": must be non-negative and finite");
  }
}

// Notation: L ≥ S are the long and short semi-axes, s = S/L, k = e = √(1 − s²) the modulus
// of the elliptic integrals, A ≤ B the curvature terms along L and S. The displacement under
// p0·√(1 − (x/L)² − (y/S)²) (Johnson ch. 3) matches h = A·x² + B·y² − δ inside the ellipse if
//   A = p0·S/(E*·L²)·(K − E)/e²,   B = p0·S/(E*·L²)·((L/S)²·E − K)/e²,   δ = p0·S·K/E*.
//
// B/A as a function of s. Written with K and E it is a ratio of two O(e²) differences, which
// loses all digits as the contact becomes circular; with Carlson's R_D (DLMF 19.25.1:
// K − E = (e²/3)·R_D(0, s², 1), E − s²·K = (e²s²/3)·R_D(0, 1, s²)) the e² cancels exactly.
double CurvatureRatio(double s) {
  const double m = s * s;
  return gsl::CarlsonRD(0.0, 1.0, m) / gsl::CarlsonRD(0.0, m, 1.0);
}

// Axis ratio s = S/L in (0, 1) that gives the curvature ratio B/A = ratio > 1.
double AxisRatioFor(double ratio) {
  // CurvatureRatio falls monotonically from ∞ (s → 0) to 1 (s = 1). The start is the classic
  // estimate s ≈ (A/B)^{2/3}, halved until it brackets the root.
  // Lower limit: e = √(1 − s²) carries a rounding error of ~1 ulp, i.e. ~1e-16/s² relative in
  // s² = 1 − e², which enters K(e) ≈ ln(4/s); at s = 1e-4 that is still below 1e-9.
  constexpr double kSmallestAxisRatio = 1e-4;
  double lo = std::max(0.5 * std::pow(ratio, -2.0 / 3.0), kSmallestAxisRatio);
  while (CurvatureRatio(lo) <= ratio) {
    if (lo == kSmallestAxisRatio) {
      throw std::invalid_argument("HertzContact: curvature ratio " + std::to_string(ratio) +
                                  " gives an ellipse more elongated than 1e4 : 1");
    }
    lo = std::max(0.5 * lo, kSmallestAxisRatio);
  }
  gsl::RootOptions options;
  // a, b, δ depend smoothly on s (no cancellation left), so a relative bracket of 1e-13 on s,
  // ~500 ulp and well above what Brent can always reach, keeps them correct to ~1e-13.
  options.rel_tolerance = 1e-13;
  const gsl::RootResult root =
      gsl::FindRootBrent([ratio](double s) { return CurvatureRatio(s) - ratio; }, lo, 1.0, options);
  // CurvatureRatio is monotone on the bracket [lo, 1] and changes sign there, so Brent's method
  // always converges within its iteration budget: failing to is a bug, not a numerical outcome.
  if (!root.converged) {
    throw std::logic_error("HertzContact: Brent's method failed on a bracketed monotone root");
  }
  return root.root;
}

}  // namespace

HertzContact::HertzContact(double a1, double b1, double effective_modulus) {
  RequirePositiveFinite(a1, "a1");
  RequirePositiveFinite(b1, "b1");
  RequirePositiveFinite(effective_modulus, "effective modulus");
  const double curvature_long = std::min(a1, b1);   // A: the long axis lies along the flatter
  const double curvature_short = std::max(a1, b1);  // direction.

  double s = 1.0;
  double e = 0.0;
  double elliptic_k = 0.5 * kPi;  // K(0) = E(0) = π/2 exactly: the circular case.
  double elliptic_e = 0.5 * kPi;
  if (curvature_short != curvature_long) {
    s = AxisRatioFor(curvature_short / curvature_long);
    // (1 − s)(1 + s) instead of 1 − s² keeps e accurate for nearly circular contacts.
    e = std::sqrt((1.0 - s) * (1.0 + s));
    elliptic_k = gsl::CompleteEllipticK(e);  // GSL takes the modulus k = e, not m = e².
    elliptic_e = gsl::CompleteEllipticE(e);
  }
  eccentricity_ = e;

  // Adding the A and B conditions gives A + B = p0·E/(E*·S), free of cancellation; with
  // p0 = 3·fn/(2π·L·S) and S = s·L: L³ = 3·fn·E/(2π·s²·E*·(A + B)). Here fn = 1 N. For a
  // circle (s = 1, E = π/2) this is Hertz's a³ = 3·fn·R/(4·E*) with A + B = 1/R.
  const double unit_force = 1.0;
  const double long_axis =
      std::cbrt(3.0 * unit_force * elliptic_e /
                (2.0 * kPi * s * s * effective_modulus * (curvature_long + curvature_short)));
  const double short_axis = s * long_axis;
  const double max_pressure = 3.0 * unit_force / (2.0 * kPi * long_axis * short_axis);

  unit_force_.semi_axis_x = a1 <= b1 ? long_axis : short_axis;
  unit_force_.semi_axis_y = a1 <= b1 ? short_axis : long_axis;
  unit_force_.axis_ratio = unit_force_.semi_axis_x / unit_force_.semi_axis_y;
  unit_force_.max_pressure = max_pressure;
  unit_force_.approach = max_pressure * short_axis * elliptic_k / effective_modulus;
  unit_force_.normal_force = unit_force;
  unit_force_.area = kPi * long_axis * short_axis;
}

HertzSolution HertzContact::ForForce(double normal_force) const {
  RequireNonNegativeFinite(normal_force, "normal force");
  const double length_scale = std::cbrt(normal_force);  // a, b, p0 ∝ fn^{1/3}
  HertzSolution solution = unit_force_;
  solution.semi_axis_x *= length_scale;
  solution.semi_axis_y *= length_scale;
  solution.max_pressure *= length_scale;
  solution.approach *= length_scale * length_scale;  // δ ∝ fn^{2/3}
  solution.area *= length_scale * length_scale;
  solution.normal_force = normal_force;
  return solution;
}

HertzSolution HertzContact::ForApproach(double approach) const {
  RequireNonNegativeFinite(approach, "approach");
  HertzSolution solution = ForForce(ForceForApproach(approach));
  solution.approach = approach;  // exact, rather than δ(fn(δ)) with its rounding
  return solution;
}

double HertzContact::ApproachForForce(double normal_force) const {
  RequireNonNegativeFinite(normal_force, "normal force");
  const double length_scale = std::cbrt(normal_force);
  return unit_force_.approach * length_scale * length_scale;
}

double HertzContact::ForceForApproach(double approach) const {
  RequireNonNegativeFinite(approach, "approach");
  const double relative = approach / unit_force_.approach;
  return relative * std::sqrt(relative);
}

}  // namespace wrc
