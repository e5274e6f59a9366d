#pragma once
/// @file fit.h
/// Least-squares straight lines with GSL's gsl_fit_linear. GSL failures throw wrc::GslError
/// (core/gsl/error.h).

#include <vector>

namespace wrc::gsl {

/// y ≈ intercept + slope·x in the least-squares sense.
struct Line {
  double intercept = 0.0;
  double slope = 0.0;
};

/// The least-squares line through (x[i], y[i]). x and y must be of equal length, at least two,
/// and x not all equal (GslError otherwise).
Line FitLine(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace wrc::gsl
