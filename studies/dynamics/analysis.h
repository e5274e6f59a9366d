#pragma once
/// @file analysis.h
/// What a simulated run says about hunting: its frequency and growth rate, and how two runs
/// of the same model differ.

#include "studies/dynamics/model.h"

namespace wrc::dynamics {

/// Hunting of a run, from the extrema of y(t) after a settling time.
struct Hunting {
  /// Hz; NaN when y has fewer than three extrema (no oscillation to measure).
  double frequency = 0.0;
  /// 1/s, the slope of ln|y| at the extrema (least squares): > 0 grows, < 0 decays. Without
  /// extrema, from ln|y| at the start and end of the measured span.
  double growth_rate = 0.0;
  double max_abs_y = 0.0;  ///< mm, over the whole run.
  int extrema = 0;
};

Hunting MeasureHunting(const Trajectory& run, double settle_time);

/// The differences between two runs sampled at the same times.
struct RunDifference {
  double max_dy = 0.0;    ///< mm, largest |y_a − y_b|.
  double max_dyaw = 0.0;  ///< rad.
  double phase_deg =
      0.0;  ///< Lag of b behind a at a's hunting frequency (zero crossings); NaN if none.
  double frequency_difference = 0.0;  ///< Hz, f_b − f_a (NaN unless both oscillate).
};

RunDifference CompareRuns(const Trajectory& a, const Trajectory& b, double settle_time);

}  // namespace wrc::dynamics
