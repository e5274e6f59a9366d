#pragma once
/// @file elliptic.h
/// Complete elliptic integrals with checked GSL status, to double precision.
///
/// Convention: the argument is the MODULUS k (GSL's and Abramowitz–Stegun's k), not the
/// parameter m = k² that e.g. Mathematica and scipy.special.ellipk take:
///   K(k) = ∫_0^{π/2} dθ / √(1 − k² sin²θ),   E(k) = ∫_0^{π/2} √(1 − k² sin²θ) dθ.

namespace wrc::gsl {

/// Complete elliptic integral of the first kind K(k), |k| < 1. Throws GslError (GSL_EDOM) for
/// |k| ≥ 1 (K has a log singularity at k = 1) and for NaN.
double CompleteEllipticK(double modulus);

/// Complete elliptic integral of the second kind E(k), |k| < 1. Throws GslError (GSL_EDOM) for
/// |k| ≥ 1 and for NaN (GSL does not accept k = 1, where E = 1).
double CompleteEllipticE(double modulus);

/// Carlson's symmetric integral R_D(x, y, z) = 3/2 ∫_0^∞ dt / [(t+z)·√((t+x)(t+y)(t+z))]
/// (DLMF 19.16.5), for x, y ≥ 0, x + y > 0, z > 0. It gives differences of complete integrals
/// without cancellation (DLMF 19.25.1): K − E = (k²/3)·R_D(0, 1−k², 1) and
/// E − (1−k²)·K = (k²(1−k²)/3)·R_D(0, 1, 1−k²). Throws GslError outside the domain.
double CarlsonRD(double x, double y, double z);

}  // namespace wrc::gsl
