#include "wrc/core/conicity.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/gsl/error.h"
#include "core/gsl/fit.h"
#include "core/gsl/integration.h"
#include "core/gsl/roots.h"
#include "wrc/core/errors.h"

namespace wrc {
namespace {

constexpr double kPi = 3.14159265358979323846;

void CheckTable(const RollingRadiusDifference& t) {
  if (t.y.size() < 2 || t.y.size() != t.dr.size()) {
    throw InputError("rolling-radius difference: at least two (y, dr) samples, as many dr as y");
  }
  for (std::size_t i = 0; i < t.y.size(); ++i) {
    if (!std::isfinite(t.y[i]) || !std::isfinite(t.dr[i])) {
      throw InputError("rolling-radius difference: sample " + std::to_string(i) + " is not finite");
    }
    if (i > 0 && !(t.y[i] > t.y[i - 1])) {
      throw InputError("rolling-radius difference: y is not strictly ascending at sample " +
                       std::to_string(i));
    }
  }
}

void CheckAmplitude(double amplitude) {
  if (!(amplitude > 0.0) || !std::isfinite(amplitude)) {
    throw InputError("equivalent conicity: the amplitude must be > 0 and finite, not " +
                     FormatNumber(amplitude));
  }
}

// V(y) = ∫_{y0}^{y} Δr(u)/2 du, exact for the piecewise-linear Δr. Between nearby points it
// is summed piece by piece rather than taken as a difference of V (which would cancel near a
// turning point, where the motion's period is decided): on one interval the integral of a
// linear function is its width times its value at the midpoint.
class Potential {
 public:
  explicit Potential(const RollingRadiusDifference& t) : t_(t), at_sample_(t.y.size(), 0.0) {
    for (std::size_t i = 1; i < t.y.size(); ++i) {
      at_sample_[i] = at_sample_[i - 1] + Piece(i - 1, t.y[i - 1], t.y[i]);
    }
  }
  double operator()(double y) const {
    const std::size_t i = Interval(y);
    return at_sample_[i] + Piece(i, t_.y[i], y);
  }
  /// ∫_lo^hi Δr/2, lo <= hi.
  double Integral(double lo, double hi) const {
    std::size_t i = Interval(lo);
    const std::size_t last = Interval(hi);
    if (i == last) return Piece(i, lo, hi);
    double sum = Piece(i, lo, t_.y[i + 1]);
    for (++i; i < last; ++i) sum += at_sample_[i + 1] - at_sample_[i];
    return sum + Piece(last, t_.y[last], hi);
  }
  double Dr(double y) const {
    const std::size_t i = Interval(y);
    const double s = (y - t_.y[i]) / (t_.y[i + 1] - t_.y[i]);
    return t_.dr[i] + s * (t_.dr[i + 1] - t_.dr[i]);
  }

 private:
  std::size_t Interval(double y) const {
    const auto upper = std::upper_bound(t_.y.begin(), t_.y.end(), y);
    const std::ptrdiff_t i = upper - t_.y.begin() - 1;
    return static_cast<std::size_t>(
        std::clamp<std::ptrdiff_t>(i, 0, static_cast<std::ptrdiff_t>(t_.y.size()) - 2));
  }
  // ∫ Δr/2 over [lo, hi] inside interval i.
  double Piece(std::size_t i, double lo, double hi) const {
    const double mid = 0.5 * (lo + hi);
    const double s = (mid - t_.y[i]) / (t_.y[i + 1] - t_.y[i]);
    return 0.5 * (hi - lo) * (t_.dr[i] + s * (t_.dr[i + 1] - t_.dr[i]));
  }

  const RollingRadiusDifference& t_;
  std::vector<double> at_sample_;
};

// The lower turning point a: V(a + 2ŷ) = V(a). V(a + 2ŷ) − V(a) grows with a wherever Δr
// restores (Δr(a + 2ŷ) > Δr(a)); without a sign change in the table there is no such motion.
bool TurningPoints(const Potential& v, const RollingRadiusDifference& t, double amplitude,
                   double* a) {
  const double lo = t.y.front(), hi = t.y.back() - 2.0 * amplitude;
  if (!(hi > lo)) return false;
  const auto g = [&](double x) { return v(x + 2.0 * amplitude) - v(x); };
  if (g(lo) > 0.0 || g(hi) < 0.0) return false;
  gsl::RootOptions options;
  options.abs_tolerance = 1e-12 * (t.y.back() - t.y.front());  // far below the 0.1 mm samples
  *a = gsl::FindRootBrent(g, lo, hi, options).root;
  return true;
}

// ∫ dy / √(2·(E − V(y))) from y_min to y_max, with y = m + ŷ·sin θ: the square-root
// singularities at the turning points become a finite integrand. It is smooth between the
// samples of Δr (V quadratic there), so QAGP is given their θ as breakpoints.
double HalfPeriod(const Potential& v, const RollingRadiusDifference& t, double y_min,
                  double amplitude) {
  const double middle = y_min + amplitude, y_max = y_min + 2.0 * amplitude;
  // E − V(y), from the nearer turning point: E sits halfway between V(y_min) and V(y_max),
  // which the root finding made equal to its tolerance.
  const double offset = 0.5 * (v(y_max) - v(y_min));
  const auto gap = [&](double y) {
    return y >= middle ? v.Integral(y, y_max) - offset : offset - v.Integral(y_min, y);
  };
  const auto f = [&](double theta) {
    const double y = std::clamp(middle + amplitude * std::sin(theta), y_min, y_max);
    return amplitude * std::cos(theta) / std::sqrt(2.0 * std::max(gap(y), 1e-300));
  };
  // Samples that coincide with a turning point (to the root finding's tolerance) are no
  // breakpoint: their θ would round onto ±π/2.
  std::vector<double> points = {-0.5 * kPi};
  const double margin = 1e-9 * amplitude;
  for (double y : t.y) {
    if (y > y_min + margin && y < y_max - margin) {
      points.push_back(std::asin((y - middle) / amplitude));
    }
  }
  points.push_back(0.5 * kPi);
  gsl::IntegrationOptions options;
  options.rel_tolerance = 1e-9;  // tan γe to ~1e-9: far below the 3 decimals it is quoted to
  options.max_intervals = 4 * points.size() + 1000;
  try {
    return gsl::IntegrateQagp(f, points, options).value;
  } catch (const GslError&) {
    // A Δr with kinks between its samples (a measured profile's) can keep QAGP from proving
    // 1e-9; 1e-6 is still a thousand times below the three decimals tan γe is quoted to.
    options.rel_tolerance = 1e-6;
    return gsl::IntegrateQagp(f, points, options).value;
  }
}

}  // namespace

EquivalentConicity EquivalentConicityAt(const RollingRadiusDifference& dr, double amplitude) {
  CheckTable(dr);
  CheckAmplitude(amplitude);
  EquivalentConicity c;
  c.amplitude = amplitude;
  c.tan_gamma_e = c.y_min = c.y_max = c.scaled_wavelength = NAN;
  const Potential v(dr);
  double a = 0.0;
  if (!TurningPoints(v, dr, amplitude, &a)) return c;
  c.valid = true;
  c.y_min = a;
  c.y_max = a + 2.0 * amplitude;
  // No restoring Δr at a turning point (a cylindrical tread within ±ŷ): the wheelset would
  // take forever to turn there, the wavelength is infinite and tan γe = 0, as EN 15302's
  // cylindrical-tread case E4 has it.
  if (!(v.Dr(c.y_max) > 0.0) || !(v.Dr(c.y_min) < 0.0)) {
    c.scaled_wavelength = INFINITY;
    c.tan_gamma_e = 0.0;
    return c;
  }
  try {
    c.scaled_wavelength = 2.0 * HalfPeriod(v, dr, a, amplitude);
  } catch (const GslError&) {  // not even 1e-6: no figure rather than a doubtful one
    c.valid = false;
    c.y_min = c.y_max = NAN;
    return c;
  }
  c.tan_gamma_e = 4.0 * kPi * kPi / (c.scaled_wavelength * c.scaled_wavelength);
  return c;
}

double EquivalentConicityByRegression(const RollingRadiusDifference& dr, double amplitude) {
  CheckTable(dr);
  CheckAmplitude(amplitude);
  const Potential v(dr);
  double y_min = 0.0;
  if (!TurningPoints(v, dr, amplitude, &y_min)) return std::numeric_limits<double>::quiet_NaN();
  // Samples on the range's edges belong to it, whatever the root finding left in the last bits.
  const double margin = 1e-9 * amplitude, y_max = y_min + 2.0 * amplitude;
  std::vector<double> y, r;
  for (std::size_t i = 0; i < dr.y.size(); ++i) {
    if (dr.y[i] >= y_min - margin && dr.y[i] <= y_max + margin) {
      y.push_back(dr.y[i]);
      r.push_back(dr.dr[i]);
    }
  }
  if (y.size() < 2) return std::numeric_limits<double>::quiet_NaN();
  return 0.5 * gsl::FitLine(y, r).slope;
}

}  // namespace wrc
