#pragma once
/// @file hertz.h
/// Hertz's solution for the frictionless normal contact of two elastic bodies whose undeformed
/// distance is h(x, y) = a1·x² + b1·y² − approach (K.L. Johnson, "Contact Mechanics", 1985,
/// ch. 3 for the displacements under an ellipsoidal pressure, ch. 4 for Hertz theory).

namespace wrc {

/// The Hertz contact for one normal load. The contact is the ellipse (x/a)² + (y/b)² ≤ 1 with
/// pressure p = max_pressure·√(1 − (x/a)² − (y/b)²).
struct HertzSolution {
  double semi_axis_x = 0.0;   ///< a, semi-axis along x, mm.
  double semi_axis_y = 0.0;   ///< b, semi-axis along y, mm.
  double axis_ratio = 1.0;    ///< a/b, -.
  double max_pressure = 0.0;  ///< p0 = 3·fn/(2π·a·b), N/mm².
  double approach = 0.0;      ///< Approach δ of distant points of the two bodies, mm.
  double normal_force = 0.0;  ///< fn, N.
  double area = 0.0;          ///< π·a·b, mm².
};

/// Hertz theory for fixed combined curvatures and elasticity. The shape of the contact ellipse
/// (its eccentricity) depends on the curvatures only; it is found once, in the constructor.
/// Loads then scale as a, b, p0 ∝ fn^{1/3} and δ ∝ fn^{2/3}.
class HertzContact {
 public:
  /// @param a1 Combined curvature term along x, 1/(2·Rx), 1/mm; positive.
  /// @param b1 Combined curvature term along y, 1/(2·Ry), 1/mm; positive. a1 = b1 gives a
  ///           circle (computed exactly); a1 < b1 makes the ellipse longer in x, a1 > b1 in y.
  /// @param effective_modulus E* with 1/E* = (1−ν1²)/E1 + (1−ν2²)/E2, N/mm²; see
  ///           CombinedElasticity::EffectiveModulus().
  /// @throws std::invalid_argument unless all three are positive and finite, or if the
  ///         ellipse would be more elongated than 10⁴ : 1 (K(e) would lose digits).
  HertzContact(double a1, double b1, double effective_modulus);

  /// The contact under normal force fn ≥ 0 N. Throws std::invalid_argument for fn < 0 or NaN.
  HertzSolution ForForce(double normal_force) const;
  /// The contact at the approach δ ≥ 0 mm. Throws std::invalid_argument for δ < 0 or NaN.
  HertzSolution ForApproach(double approach) const;

  /// δ(fn) = δ₁·fn^{2/3}, δ₁ being the approach for 1 N.
  double ApproachForForce(double normal_force) const;
  /// fn(δ) = (δ/δ₁)^{3/2}, the inverse of ApproachForForce.
  double ForceForApproach(double approach) const;

  /// Eccentricity e = √(1 − (short/long semi-axis)²) of the contact ellipse; 0 for a circle.
  double eccentricity() const { return eccentricity_; }
  /// a/b, the same for every load.
  double axis_ratio() const { return unit_force_.axis_ratio; }

 private:
  double eccentricity_ = 0.0;
  HertzSolution unit_force_;  ///< The solution for fn = 1 N, scaled by ForForce.
};

}  // namespace wrc
