// Hunting frequency, growth rate and run differences (analysis.h).

#include "studies/dynamics/analysis.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace wrc::dynamics {
namespace {

struct Extremum {
  double t, y;
};

// Local extrema of y after `settle`, placed by the parabola through the three samples around
// each (sampling at 1 kHz would otherwise quantise the period to 1 ms).
std::vector<Extremum> Extrema(const Trajectory& run, double settle) {
  std::vector<Extremum> out;
  for (std::size_t i = 1; i + 1 < run.y.size(); ++i) {
    if (run.t[i] < settle) continue;
    const double a = run.y[i - 1], b = run.y[i], c = run.y[i + 1];
    const bool peak = (b > a && b >= c) || (b < a && b <= c);
    if (!peak) continue;
    const double curvature = a - 2.0 * b + c;
    const double shift = curvature != 0.0 ? 0.5 * (a - c) / curvature : 0.0;
    const double h = run.t[i + 1] - run.t[i];
    out.push_back({run.t[i] + shift * h, b - 0.25 * (a - c) * shift});
  }
  return out;
}

// Times where y crosses zero upwards, linearly interpolated.
std::vector<double> UpCrossings(const Trajectory& run, double settle) {
  std::vector<double> out;
  for (std::size_t i = 0; i + 1 < run.y.size(); ++i) {
    if (run.t[i] < settle || !(run.y[i] < 0.0 && run.y[i + 1] >= 0.0)) continue;
    const double f = run.y[i] / (run.y[i] - run.y[i + 1]);
    out.push_back(run.t[i] + f * (run.t[i + 1] - run.t[i]));
  }
  return out;
}

double LeastSquaresSlope(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    mx += x[i] / x.size();
    my += y[i] / y.size();
  }
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
  }
  return sxx > 0.0 ? sxy / sxx : 0.0;
}

}  // namespace

Hunting MeasureHunting(const Trajectory& run, double settle_time) {
  Hunting h;
  for (double y : run.y) h.max_abs_y = std::max(h.max_abs_y, std::fabs(y));
  const std::vector<Extremum> ext = Extrema(run, settle_time);
  h.extrema = static_cast<int>(ext.size());
  if (ext.size() < 3) {
    h.frequency = NAN;
    const auto first = std::lower_bound(run.t.begin(), run.t.end(), settle_time) - run.t.begin();
    const double y0 = std::fabs(run.y[first]), y1 = std::fabs(run.y.back());
    const double span = run.t.back() - run.t[first];
    h.growth_rate = y0 > 0.0 && y1 > 0.0 && span > 0.0 ? std::log(y1 / y0) / span : 0.0;
    return h;
  }
  h.frequency = 0.5 * (ext.size() - 1) / (ext.back().t - ext.front().t);
  std::vector<double> t, log_y;
  for (const Extremum& e : ext) {
    if (e.y == 0.0) continue;
    t.push_back(e.t);
    log_y.push_back(std::log(std::fabs(e.y)));
  }
  h.growth_rate = LeastSquaresSlope(t, log_y);
  return h;
}

RunDifference CompareRuns(const Trajectory& a, const Trajectory& b, double settle_time) {
  RunDifference d;
  const std::size_t n = std::min(a.y.size(), b.y.size());
  for (std::size_t i = 0; i < n; ++i) {
    d.max_dy = std::max(d.max_dy, std::fabs(a.y[i] - b.y[i]));
    d.max_dyaw = std::max(d.max_dyaw, std::fabs(a.yaw[i] - b.yaw[i]));
  }
  const Hunting ha = MeasureHunting(a, settle_time), hb = MeasureHunting(b, settle_time);
  d.frequency_difference = hb.frequency - ha.frequency;
  // Mean delay of each of a's crossings to b's nearest one, as a phase of a's period.
  const std::vector<double> ca = UpCrossings(a, settle_time), cb = UpCrossings(b, settle_time);
  if (ca.empty() || cb.empty() || std::isnan(ha.frequency)) {
    d.phase_deg = NAN;
    return d;
  }
  double delay = 0.0;
  for (double t : ca) {
    const auto nearest = std::min_element(cb.begin(), cb.end(), [t](double x, double y) {
      return std::fabs(x - t) < std::fabs(y - t);
    });
    delay += (*nearest - t) / ca.size();
  }
  d.phase_deg = 360.0 * ha.frequency * delay;
  return d;
}

}  // namespace wrc::dynamics
