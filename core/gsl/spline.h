#pragma once
/// @file spline.h
/// One-dimensional interpolating splines from GSL (gsl_spline), owned RAII-style. The spline is
/// evaluated without a gsl_interp_accel (GSL then bisects the knot table), so every const
/// member is safe to call from several threads at once. GSL failures throw wrc::GslError
/// (core/gsl/error.h).

#include <cstddef>
#include <memory>
#include <vector>

namespace wrc::gsl {

/// The GSL interpolation types offered here.
enum class SplineType {
  kLinear,        ///< gsl_interp_linear: piecewise linear.
  kNaturalCubic,  ///< gsl_interp_cspline: C2 cubic with zero second derivative at both ends.
  kAkima,         ///< gsl_interp_akima: C1 cubic, little overshoot near outliers.
  kSteffen,       ///< gsl_interp_steffen: C1 cubic, monotone between monotone data.
  kCubic,         ///< C2 cubic with an end condition chosen per end (CubicEnd); wrc's own
                  ///< gsl_interp_type, since GSL offers only natural and periodic ends.
};

/// End condition of a SplineType::kCubic spline at one end.
enum class CubicEnd {
  kNatural,   ///< Zero second derivative there, as gsl_interp_cspline.
  kNotAKnot,  ///< The two end intervals are one cubic (f''' continuous at the knot next to the
              ///< end): takes the curvature from the data instead of assuming zero. With only
              ///< 3 knots and this condition at both ends the spline is the parabola.
};

/// An interpolating spline f(x) through the knots (x_i, f_i), x strictly increasing.
class Spline {
 public:
  /// Builds the spline. Throws GslError (GSL_EINVAL) if x is not strictly increasing, the sizes
  /// differ or there are fewer knots than the type needs (2 for linear, 3 for cubic, 5 Akima).
  Spline(std::vector<double> x, std::vector<double> f, SplineType type = SplineType::kNaturalCubic);
  /// A SplineType::kCubic spline (at least 3 knots) with the given end conditions.
  Spline(std::vector<double> x, std::vector<double> f, CubicEnd first_end, CubicEnd last_end);
  ~Spline();
  Spline(const Spline& other);
  Spline& operator=(const Spline& other);
  Spline(Spline&& other) noexcept;
  Spline& operator=(Spline&& other) noexcept;

  /// f(x), f'(x), f''(x) for x in [x_min(), x_max()]; outside that range GslError(GSL_EDOM).
  double Value(double x) const;
  double Derivative(double x) const;
  double SecondDerivative(double x) const;
  /// f'(x) for x in knot interval [knots()[interval], knots()[interval + 1]], without the
  /// search for the interval (x is not checked against it): for loops that walk the intervals.
  double DerivativeOn(std::size_t interval, double x) const;
  /// f(x) as Value gives it, starting the search for the knot interval at `interval` (exact for
  /// any hint; cheap when it is right, e.g. in loops over ascending x).
  double ValueOn(std::size_t interval, double x) const;
  /// out[k] = f'(x[k]) for `count` points of one knot interval, as DerivativeOn gives them
  /// (at the interval's right end from its own piece, where DerivativeOn takes the next one: the
  /// same to round-off). A SplineType::kCubic spline takes its piece once for all of them (the
  /// arc-length quadrature of a profile evaluates five points per interval). Throws GslError
  /// (GSL_EDOM) for a point outside the interval.
  void DerivativesOn(std::size_t interval, const double* x, std::size_t count, double* out) const;
  /// ∫_a^b f(x) dx with a, b in [x_min(), x_max()].
  double Integral(double a, double b) const;

  double x_min() const { return x_.front(); }
  double x_max() const { return x_.back(); }
  std::size_t size() const { return x_.size(); }
  const std::vector<double>& knots() const { return x_; }
  const std::vector<double>& values() const { return f_; }
  SplineType type() const { return type_; }
  /// End conditions; kNatural for the other cubic types, meaningless for the non-cubic ones.
  CubicEnd first_end() const { return first_end_; }
  CubicEnd last_end() const { return last_end_; }

 private:
  struct State;  // Holds the gsl_spline; defined in spline.cpp so GSL's headers stay there.
  void Build();

  std::vector<double> x_;
  std::vector<double> f_;
  SplineType type_;
  CubicEnd first_end_ = CubicEnd::kNatural;
  CubicEnd last_end_ = CubicEnd::kNatural;
  std::unique_ptr<State> state_;
};

}  // namespace wrc::gsl
