#include "core/wheelrail/contact_search.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace wrc::wr {
namespace {

// The wheel's height along x is a near-parabola z(x) ≈ z0 − (x − x0)²/(2R); three points 1 mm
// apart locate its top to O(h²/R²) and two refinements make that exact to round-off.
constexpr double kLocusStep = 1.0;
// The vertex step is a Newton step on the central difference, so a step shorter than this
// leaves an error of about its square over R (< 1e-8 mm for R > 100 mm), and the height at the
// top, where the surface is level, moves by its square again: no further fit is needed. With
// the neighbouring sample's top as the guess, one fit usually suffices (4 wheel evaluations
// per sample instead of 7).
constexpr double kConvergedShift = 1e-3;

bool Locate(const PlacedWheel& wheel, double y, double z_rail, double x_guess, LocusSample& out) {
  double x0 = x_guess;
  double zc = 0.0, curvature = 0.0;
  bool converged = false;
  for (int it = 0; it < 3; ++it) {
    const auto zm = wheel.SurfaceZ(x0 - kLocusStep, y);
    const auto z0 = wheel.SurfaceZ(x0, y);
    const auto zp = wheel.SurfaceZ(x0 + kLocusStep, y);
    if (!zm || !z0 || !zp) return false;
    // Parabola through the three heights; its vertex is the lowest wheel point (z down).
    const double d1 = (*zp - *zm) / (2.0 * kLocusStep);
    const double d2 = (*zp - 2.0 * *z0 + *zm) / (kLocusStep * kLocusStep);
    if (!(d2 < 0.0)) return false;
    const double shift = std::clamp(-d1 / d2, -20.0, 20.0);
    x0 += shift;
    zc = *z0 - 0.5 * d1 * d1 / d2;
    curvature = -d2;
    if (std::fabs(shift) < kConvergedShift) {
      converged = true;
      break;
    }
  }
  // After a converged fit the parabola's vertex height zc is the top to ~1e-11 mm: the quartic
  // term of the wheel's circle moves it by h²·shift²/R³, an asymmetry (yaw) by its third
  // derivative times shift·h²/6, both far below that for shift < kConvergedShift. That saves
  // the evaluation at the vertex, a quarter of the search.
  double top = zc;
  if (!converged) {
    const auto z_top = wheel.SurfaceZ(x0, y);
    if (!z_top) return false;
    top = *z_top;
  }
  out.x = x0;
  out.gap = z_rail - top;
  out.curvature = curvature;
  return true;
}

}  // namespace

ContactSearch SearchContact(const PlacedRail& rail, const PlacedWheel& wheel, double step,
                            double reach, double z_limit) {
  ContactSearch search;
  // Equal steps of at most `step` that end exactly on the profile's last point, so that a
  // symmetric profile pair gives a symmetric search.
  const int n = std::max(1, static_cast<int>(std::ceil(rail.length() / step)));
  step = rail.length() / n;
  search.step = step;
  search.samples.resize(n + 1);
  std::vector<double> s(n + 1);
  for (int k = 0; k <= n; ++k) s[k] = std::min(k * step, rail.length());
  const std::vector<Eigen::Vector2d> positions = rail.PositionsAt(s);
  for (int k = 0; k <= n; ++k) {
    LocusSample& sample = search.samples[k];
    sample.s = s[k];
    sample.y = positions[k](0);
    sample.z = positions[k](1);
    sample.gap = std::numeric_limits<double>::infinity();
  }
  // The inclination only where the wheel is located: it weighs interpenetration, and most
  // samples are never located.
  auto locate = [&](LocusSample& sample, double guess) {
    sample.alpha = rail.InclinationAt(sample.s);
    const bool located = Locate(wheel, sample.y, sample.z, guess, sample);
    sample.off_wheel = !located;
    return located;
  };
  // Most of the profile pair is far apart, and locating the wheel there is most of the cost,
  // so the samples are located in levels: every kStrides[0]-th first, then every
  // kStrides[1]-th, then all, each level only between samples of the previous one that may come
  // within `reach` of the smallest gap and below z_limit (no z of an fz iteration goes deeper;
  // samples with a larger gap carry no interpenetration at any z asked for). Between two
  // samples h apart the gap cannot dip below the lower end by more than h²/8·|g''|, which is
  // 0.125 mm for h = 1 mm and |g''| <= 1/mm (radii of 1 mm in both profiles at once);
  // kDipMargin·h² is four times that, so it covers any real profile pair. On conformal
  // contacts (heavy haul) the gap stays within that margin over tens of mm: the middle level
  // keeps the finest one to where the gap is within 0.03 mm of the needed range, and locates
  // 40-60 % fewer samples than two levels.
  constexpr int kStrides[] = {20, 5, 1};
  constexpr double kDipMargin = 0.5;  // mm per mm² of interval length
  std::vector<int> located;           // the current level's samples, ascending
  for (int k = 0; k < n; k += kStrides[0]) located.push_back(k);
  located.push_back(n);
  double x_guess = 0.0;
  double smallest = std::numeric_limits<double>::infinity();
  for (const int k : located) {
    LocusSample& sample = search.samples[k];
    sample.valid = locate(sample, x_guess);
    if (sample.valid) {
      x_guess = sample.x;
      smallest = std::min(smallest, sample.gap);
    }
  }
  const double needed = std::max(smallest, std::min(smallest + reach, z_limit));
  // Whether the gap between located samples a < b may come below `needed`.
  auto near = [&](int a, int b) {
    const LocusSample& sa = search.samples[a];
    const LocusSample& sb = search.samples[b];
    const double h = (b - a) * step;
    const double threshold = needed + kDipMargin * h * h;
    return (sa.valid && sa.gap < threshold) || (sb.valid && sb.gap < threshold) ||
           sa.valid != sb.valid;  // the wheel's edge: locate it finely
  };
  for (std::size_t level = 1; level < std::size(kStrides); ++level) {
    const int stride = kStrides[level];
    std::vector<int> next;
    for (std::size_t c = 0; c + 1 < located.size(); ++c) {
      const int a = located[c], b = located[c + 1];
      next.push_back(a);
      if (!near(a, b)) continue;
      // Each sample starts from the previous one's top moved on by the locus's last step (at
      // yaw the top's x changes along the profile), so that one fit usually converges.
      x_guess = search.samples[a].valid ? search.samples[a].x : search.samples[b].x;
      double x_step = 0.0;
      for (int k = a + stride; k < b; k += stride) {
        LocusSample& sample = search.samples[k];
        sample.valid = locate(sample, x_guess + x_step);
        if (sample.valid) {
          x_step = sample.x - x_guess;
          x_guess = sample.x;
        } else {
          x_step = 0.0;
        }
        next.push_back(k);
      }
    }
    next.push_back(located.back());
    located = std::move(next);
  }
  // Samples far from contact stay as located at the coarser levels: invalid, as the ones never
  // located, so that every valid sample is within reach.
  const double far = needed + kDipMargin * std::pow(kStrides[0] * step, 2);
  for (LocusSample& sample : search.samples) {
    if (sample.valid && sample.gap >= far) {
      sample.valid = false;
      sample.gap = std::numeric_limits<double>::infinity();
    }
  }
  return search;
}

double LocusHalfLength(const LocusSample& sample, double dz) {
  const double g0 = sample.gap - dz;
  if (!sample.valid || g0 >= 0.0) return 0.0;
  return std::sqrt(2.0 * -g0 / sample.curvature);
}

double LocusWeight(const LocusSample& sample, double dz, bool quadratic) {
  const double a = LocusHalfLength(sample, dz);
  if (a == 0.0) return 0.0;
  const double g0 = sample.gap - dz;
  return quadratic ? (16.0 / 15.0) * a * g0 * g0 : (4.0 / 3.0) * a * -g0;
}

std::vector<PatchExtent> FindPatches(const ContactSearch& search, double dz,
                                     double combine_distance) {
  // Interpenetration regions: runs of samples with negative gap.
  std::vector<PatchExtent> regions;
  const int n = static_cast<int>(search.samples.size());
  for (int k = 0; k < n; ++k) {
    if (LocusHalfLength(search.samples[k], dz) == 0.0) continue;
    if (regions.empty() || regions.back().last != k - 1) {
      regions.push_back({k, k, 1e300, -1e300});
    }
    PatchExtent& r = regions.back();
    r.last = k;
    const double a = LocusHalfLength(search.samples[k], dz);
    r.x_min = std::min(r.x_min, search.samples[k].x - a);
    r.x_max = std::max(r.x_max, search.samples[k].x + a);
  }
  // Greedy combination of neighbours along the rail.
  std::vector<PatchExtent> patches;
  for (const PatchExtent& r : regions) {
    if (!patches.empty()) {
      PatchExtent& p = patches.back();
      const LocusSample& a = search.samples[p.last];
      const LocusSample& b = search.samples[r.first];
      const double lateral = std::hypot(b.y - a.y, b.z - a.z);
      const double longitudinal = std::max({0.0, r.x_min - p.x_max, p.x_min - r.x_max});
      if (std::hypot(lateral, longitudinal) <= combine_distance) {
        p.last = r.last;
        p.x_min = std::min(p.x_min, r.x_min);
        p.x_max = std::max(p.x_max, r.x_max);
        continue;
      }
    }
    patches.push_back(r);
  }
  std::reverse(patches.begin(), patches.end());  // field side (large s) first
  return patches;
}

}  // namespace wrc::wr
