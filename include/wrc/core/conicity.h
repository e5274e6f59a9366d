#pragma once
/// @file conicity.h
/// Equivalent conicity of a wheelset from its rolling-radius difference function, by the
/// integration of the kinematic (Klingel) wheelset motion as EN 15302:2008+A1:2010 describes it:
/// a wheelset rolling without slip obeys y'' = −Δr(y)/(2·e·r0) along the track (x), a periodic
/// motion of amplitude ŷ has a wavelength λ(ŷ), and the equivalent conicity is the cone angle
/// whose linear motion has that wavelength, tan γe = 4π²·e·r0/λ² (Klingel: λ = 2π·√(e·r0/tan γ)).
/// In x/√(e·r0) the equation reads y'' = −Δr(y)/2: tan γe depends on Δr alone.

#include <vector>

namespace wrc {

/// Δr = r_right − r_left (mm) against the wheelset's lateral shift y (mm, y > 0 towards the
/// right rail), tabulated; linear between the samples.
struct RollingRadiusDifference {
  std::vector<double> y;   ///< mm, strictly ascending, at least two.
  std::vector<double> dr;  ///< mm, as many as y.
};

/// The periodic motion of one amplitude and its equivalent conicity. When the motion of that
/// amplitude leaves the tabulated range, or Δr does not bring the wheelset back (no periodic
/// motion), or its period cannot be integrated to 1e-6, valid is false and the other figures are
/// NaN: a numerical outcome, not an error.
struct EquivalentConicity {
  double amplitude = 0.0;  ///< ŷ, mm: half the peak-to-peak lateral motion.
  bool valid = false;
  double tan_gamma_e = 0.0;  ///< -
  double y_min = 0.0;        ///< mm, the turning points: y_max − y_min = 2ŷ.
  double y_max = 0.0;
  /// λ/√(e·r0), the wavelength in x/√(e·r0) (dimensionless): λ = this · √(e·r0).
  double scaled_wavelength = 0.0;
};

/// The equivalent conicity at amplitude ŷ > 0. The turning points are where the potential
/// V(y) = ∫ Δr/2 dy is equal (the motion's energy), 2ŷ apart; the half period is
/// ∫ dy / √(2·(V(y_max) − V(y))) between them. Throws InputError for a table that is not
/// strictly ascending, holds fewer than two or non-finite samples, or a non-positive amplitude.
EquivalentConicity EquivalentConicityAt(const RollingRadiusDifference& dr, double amplitude);

/// The equivalent conicity at amplitude ŷ > 0 by the linear regression of the Δr function, the
/// other method EN 15302 describes (informatively, its Annex C, beside the integration above):
/// the least-squares straight line through the Δr samples over the range the wheelset's motion
/// of that amplitude covers, whose slope is 2·tan γe (a cone of tan γ gives Δr = 2·y·tan γ).
/// The range is the integration's, between its turning points: ±ŷ about 0 for a symmetric
/// pair, shifted where unequal wheels move the wheelset's running centre (EquivalentConicity's
/// y_min, y_max), so the two methods see the same Δr and differ only in how they weigh it:
/// regression every y alike, the integration by how long the motion dwells there, longest near
/// its turning points. They part where Δr bends or jumps within the range. NaN where the
/// integration has no motion (the range leaves the table, Δr does not restore) or fewer than
/// two samples lie in the range. Throws InputError as EquivalentConicityAt does.
double EquivalentConicityByRegression(const RollingRadiusDifference& dr, double amplitude);

}  // namespace wrc
