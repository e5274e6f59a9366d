#pragma once
/// @file integration.h
/// Adaptive quadrature with GSL's QUADPACK routines (QAGS, QAGP, QAWC) and a 2-D routine built
/// from nested 1-D QAGS. Each call owns its workspace, so calls may nest (the 2-D routine does)
/// and run on different threads. GSL failures throw wrc::GslError (core/gsl/error.h); an
/// exception thrown by the integrand is carried across GSL's C frames and rethrown unchanged.

#include <cstddef>
#include <functional>
#include <vector>

namespace wrc::gsl {

/// Accuracy requested from an adaptive rule: it subdivides until the error estimate is below
/// max(abs_tolerance, rel_tolerance·|value|) or max_intervals subintervals are in use.
struct IntegrationOptions {
  double abs_tolerance = 0.0;        ///< Absolute error goal (0: relative goal only).
  double rel_tolerance = 1e-10;      ///< Relative error goal; must be ≥ 50·DBL_EPSILON for GSL.
  std::size_t max_intervals = 1000;  ///< Workspace size = most subintervals allowed.
};

/// An integral and GSL's estimate of its absolute error.
struct IntegrationResult {
  double value = 0.0;
  double abs_error = 0.0;
};

/// ∫_lo^hi f(x) dx by QAGS (21-point Gauss–Kronrod, bisection, Wynn-ε extrapolation); copes
/// with integrable singularities at the end points. Throws GslError if the goal is not met.
IntegrationResult IntegrateQags(const std::function<double(double)>& f, double lo, double hi,
                                const IntegrationOptions& options = {});

/// ∫ f(x) dx over [points.front(), points.back()] by QAGP, where the interior entries of the
/// sorted list `points` mark known singularities or kinks that the rule must not sample.
/// Throws std::invalid_argument for fewer than two points.
IntegrationResult IntegrateQagp(const std::function<double(double)>& f, std::vector<double> points,
                                const IntegrationOptions& options = {});

/// Cauchy principal value of ∫_lo^hi f(x)/(x − pole) dx by QAWC.
IntegrationResult IntegrateCauchy(const std::function<double(double)>& f, double lo, double hi,
                                  double pole, const IntegrationOptions& options = {});

/// ∫_xlo^xhi ∫_ylo^yhi f(x, y) dy dx by nested QAGS (inner over y, outer over x), with
/// options.rel_tolerance at both levels. options.abs_tolerance is the goal for the whole
/// integral: each inner integral gets abs_tolerance/|xhi − xlo| and each x piece its share in
/// proportion to its width, so both levels together stay within about 2·abs_tolerance. Set it
/// when the value may be small through cancellation (odd integrands), else the relative goal
/// cannot be met and GslError is thrown. The x and y ranges are first split at the
/// breakpoints that lie strictly inside them, so a point singularity placed on breakpoints sits
/// on a corner of every piece, where QAGS's end-point extrapolation handles it, and kinks along
/// breakpoint lines are never sampled across. abs_error adds the outer estimates and
/// (width × number of y pieces × largest inner estimate), a bound on what the inner errors add.
IntegrationResult Integrate2d(const std::function<double(double, double)>& f, double xlo,
                              double xhi, double ylo, double yhi,
                              const IntegrationOptions& options = {},
                              const std::vector<double>& x_breaks = {},
                              const std::vector<double>& y_breaks = {});

}  // namespace wrc::gsl
