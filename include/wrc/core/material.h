#pragma once
/// @file material.h
/// Elastic materials of the two bodies and their combination as in Kalker's theory.

#include <limits>

namespace wrc {

/// Linear elastic, isotropic material of one body.
struct ElasticMaterial {
  double shear_modulus = 82000.0;  ///< G, N/mm².
  double poisson = 0.28;           ///< ν, -.
  /// k, the yield limit in pure shear, N/mm² (NaN: not given). Not part of the contact problem:
  /// the surface-fatigue index of the body (SurfaceFatigueIndex) compares the load with it.
  double shear_yield = std::numeric_limits<double>::quiet_NaN();
};

/// Combined constants of two half-spaces (Kalker, "Three-dimensional elastic bodies in rolling
/// contact", §1.5): 1/G = (1/G1 + 1/G2)/2, ν/G = (ν1/G1 + ν2/G2)/2,
/// K = (G/4)·[(1−2ν1)/G1 − (1−2ν2)/G2]. K = 0 for identical (quasi-identical) bodies, and then
/// normal and tangential problems decouple.
struct CombinedElasticity {
  double shear_modulus = 82000.0;  ///< Combined G, N/mm².
  double poisson = 0.28;           ///< Combined ν, -.
  double kappa = 0.0;              ///< Difference parameter K, -.

  /// Combines body 1 and body 2. Throws std::invalid_argument for G <= 0 or ν outside [0, 0.5].
  static CombinedElasticity FromBodies(const ElasticMaterial& body1, const ElasticMaterial& body2);
  /// Two bodies of the same material.
  static CombinedElasticity Identical(const ElasticMaterial& body) {
    return FromBodies(body, body);
  }
  /// Effective modulus E* of Hertz theory: 1/E* = (1−ν1²)/E1 + (1−ν2²)/E2 = (1−ν)/G for
  /// identical bodies.
  double EffectiveModulus() const { return shear_modulus / (1.0 - poisson); }
};

}  // namespace wrc
