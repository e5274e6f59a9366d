#pragma once
/// @file cubic_line.h
/// The cubic mode's arithmetic along one grid line (runtime/table_cubic.cpp describes the
/// method): the limited node slopes and the Hermite basis. Header-only and free of the table,
/// so that the generator measures a refinement's error with exactly the slopes the runtime will
/// interpolate with.

#include <algorithm>
#include <cmath>
#include <limits>

namespace wrc::cubic {

constexpr int kWindow = 5;  // Nodes in the slope estimate's polynomial (degree 4).

/// Derivative at x[j] of the polynomial through (x[m], f[m]), m < width.
inline double PolynomialSlope(const double* x, const double* f, int width, int j) {
  double slope = 0.0;
  for (int m = 0; m < width; ++m) {
    double coefficient = 0.0;
    if (m == j) {
      for (int k = 0; k < width; ++k) {
        if (k != j) coefficient += 1.0 / (x[j] - x[k]);
      }
    } else {
      // L_m'(x_j): of the product rule's terms only the one differentiating (x - x_j) survives.
      double numerator = 1.0;
      double denominator = 1.0;
      for (int k = 0; k < width; ++k) {
        if (k == m) continue;
        denominator *= x[m] - x[k];
        if (k != j) numerator *= x[j] - x[k];
      }
      coefficient = numerator / denominator;
    }
    slope += coefficient * f[m];
  }
  return slope;
}

/// The limiter (Fritsch–Carlson in Hyman's box form) with the secants of the adjacent cells.
inline double LimitSlope(double slope, bool has_left, double left, bool has_right, double right) {
  double direction = 0.0;
  double bound = 0.0;
  if (has_left && has_right) {
    if (left * right <= 0.0) return 0.0;
    direction = left > 0.0 ? 1.0 : -1.0;
    bound = 3.0 * std::min(std::abs(left), std::abs(right));
  } else if (has_left || has_right) {
    const double secant = has_left ? left : right;
    if (secant == 0.0) return 0.0;
    direction = secant > 0.0 ? 1.0 : -1.0;
    bound = 3.0 * std::abs(secant);
  } else {
    return 0.0;
  }
  if (slope * direction <= 0.0) return 0.0;
  return direction * std::min(std::abs(slope), bound);
}

/// First node of the slope window of node j on an axis of n nodes whose finite values at j span
/// [lo, hi] (at most 4 nodes either side).
inline int WindowStart(int j, int lo, int hi) {
  const int width = std::min(kWindow, hi - lo + 1);
  return std::clamp(j - width / 2, lo, hi - width + 1);
}

/// The limited slope at node j of a grid line of n nodes (x ascending, values f). Non-finite
/// values (failed nodes) are left out: the window and secants use only the finite run around
/// j, so a NaN node does not spoil its neighbours' slopes; its own slope is NaN. Reads at most
/// kWindow - 1 nodes either side of j.
inline double NodeSlope(const double* x, int n, const double* f, int j) {
  if (!std::isfinite(f[j])) return std::numeric_limits<double>::quiet_NaN();
  int lo = j;
  while (lo > 0 && j - lo < kWindow - 1 && std::isfinite(f[lo - 1])) --lo;
  int hi = j;
  while (hi < n - 1 && hi - j < kWindow - 1 && std::isfinite(f[hi + 1])) ++hi;
  const int width = std::min(kWindow, hi - lo + 1);
  const int start = WindowStart(j, lo, hi);
  const double estimate =
      width >= 2 ? PolynomialSlope(x + start, f + start, width, j - start) : 0.0;
  const bool has_left = j > lo;
  const bool has_right = j < hi;
  const double left = has_left ? (f[j] - f[j - 1]) / (x[j] - x[j - 1]) : 0.0;
  const double right = has_right ? (f[j + 1] - f[j]) / (x[j + 1] - x[j]) : 0.0;
  return LimitSlope(estimate, has_left, left, has_right, right);
}

/// The cubic Hermite basis at t in [0, 1] of a cell of width h: (h00, h·h10, h01, h·h11), the
/// weights of the lower value, lower slope, upper value and upper slope.
inline void HermiteBasis(double t, double h, double basis[4]) {
  const double t2 = t * t;
  const double t3 = t2 * t;
  basis[0] = 2.0 * t3 - 3.0 * t2 + 1.0;
  basis[1] = h * (t3 - 2.0 * t2 + t);
  basis[2] = -2.0 * t3 + 3.0 * t2;
  basis[3] = h * (t3 - t2);
}

}  // namespace wrc::cubic
