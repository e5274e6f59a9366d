#pragma once
/// @file roots.h
/// Bracketing root finding with GSL's Brent solver (bisection safeguarded inverse-quadratic
/// interpolation): always converges once the bracket holds a sign change.

#include <functional>

namespace wrc::gsl {

/// When the Brent iteration stops.
struct RootOptions {
  /// The bracket [lo, hi] counts as converged when hi − lo < abs_tolerance + rel_tolerance·min|x|
  /// (gsl_root_test_interval).
  double abs_tolerance = 0.0;
  double rel_tolerance = 1e-12;  ///< Relative bracket width goal.
  int max_iterations = 200;      ///< Iterations before giving up (converged = false).
};

/// Outcome of a root search.
struct RootResult {
  double root = 0.0;   ///< Best estimate of the root (GSL's current iterate).
  int iterations = 0;  ///< Brent iterations used.
  bool converged =
      false;  ///< False when max_iterations ran out first; root is then the last iterate.
};

/// Finds x in [lo, hi] with f(x) = 0 by Brent's method. f(lo) and f(hi) must have opposite
/// signs (or one of them be zero, which is then returned at once); otherwise GslError with
/// status GSL_EINVAL is thrown (GSL_EBADFUNC if f is not finite there). Other GSL failures also
/// throw GslError; an exception thrown by f is rethrown unchanged. A root at x = 0 needs
/// abs_tolerance > 0, since the relative test scales with min|x| over the bracket.
RootResult FindRootBrent(const std::function<double(double)>& f, double lo, double hi,
                         const RootOptions& options = {});

}  // namespace wrc::gsl
