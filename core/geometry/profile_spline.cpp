// Arc-length parametrised spline of a profile: y(s), z(s) as GSL natural cubic splines.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/gsl/spline.h"
#include "wrc/errors.h"
#include "wrc/profile.h"

namespace wrc {
namespace {

// Knot refinement stops when no knot moves by more than this fraction of the length; 1e-10 of
// at most 500 mm is 0.05 nm, far below anything geometric, yet well above the round-off of
// summing a few thousand interval lengths (~1e-13 relative).
constexpr double kKnotTolerance = 1e-10;
// The refinement contracts fast (each pass multiplies the knot changes by roughly the relative
// variation of the speed |r'| within an interval); 50 passes are never needed in practice.
constexpr int kMaxRefinements = 50;
// Evaluations this far (relative to the length) outside [0, length] are clamped, so that
// s = length computed by subtraction still works; anything further out is an error.
constexpr double kRangeSlack = 1e-12;

/// 5-point Gauss–Legendre rule on [−1, 1]: exact for polynomials up to degree 9, so the speed
/// |r'(s)| of a cubic piece (the root of a quartic close to constant) integrates to ~1e-12.
struct GaussLegendre5 {
  std::array<double, 5> nodes;
  std::array<double, 5> weights;
  GaussLegendre5() {
    const double a = std::sqrt(5.0 - 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
    const double b = std::sqrt(5.0 + 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
    const double wa = (322.0 + 13.0 * std::sqrt(70.0)) / 900.0;
    const double wb = (322.0 - 13.0 * std::sqrt(70.0)) / 900.0;
    nodes = {-b, -a, 0.0, a, b};
    weights = {wb, wa, 128.0 / 225.0, wa, wb};
  }
};

/// A cubic c0 + c1 t + c2 t² + c3 t³ on t in [0, h].
struct Cubic {
  double c0, c1, c2, c3, h;
  double Value(double t) const { return c0 + t * (c1 + t * (c2 + t * c3)); }
  double Slope(double t) const { return c1 + t * (2.0 * c2 + t * 3.0 * c3); }
};

/// The cubic with the given end values and slopes (Hermite form). A GSL cubic-spline piece is
/// a cubic, so this reproduces it exactly from its end data.
Cubic HermiteCubic(double f0, double f1, double d0, double d1, double h) {
  const double secant = (f1 - f0) / h;
  return Cubic{f0, d0, (3.0 * secant - 2.0 * d0 - d1) / h, (d0 + d1 - 2.0 * secant) / (h * h), h};
}

/// Roots of c1 + 2 c2 t + 3 c3 t² strictly inside (0, h), ascending.
std::vector<double> CriticalPoints(const Cubic& p) {
  const double a = 3.0 * p.c3;
  const double b = 2.0 * p.c2;
  const double c = p.c1;
  std::vector<double> roots;
  const double scale = std::abs(b) + std::abs(c) + std::abs(a) * p.h;
  if (std::abs(a) * p.h <= 1e-14 * scale) {  // Effectively linear slope.
    if (b != 0.0) roots.push_back(-c / b);
  } else {
    const double discriminant = b * b - 4.0 * a * c;
    if (discriminant >= 0.0) {
      // The stable form avoids cancellation between −b and the root of the discriminant.
      const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
      roots.push_back(q / a);
      if (q != 0.0) roots.push_back(c / q);
    }
  }
  std::vector<double> inside;
  for (const double t : roots) {
    if (t > 0.0 && t < p.h) inside.push_back(t);
  }
  std::sort(inside.begin(), inside.end());
  return inside;
}

/// The root of p(t) = target in [lo, hi], where p is monotone and changes sign: Newton steps
/// kept inside the shrinking bracket, bisection when a step would leave it.
double SolveMonotone(const Cubic& p, double target, double lo, double hi) {
  double f_lo = p.Value(lo) - target;
  double t = 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double f = p.Value(t) - target;
    if (f == 0.0) return t;
    if ((f < 0.0) == (f_lo < 0.0)) {
      lo = t;
      f_lo = f;
    } else {
      hi = t;
    }
    if (hi - lo <= 4.0 * std::numeric_limits<double>::epsilon() * (std::abs(lo) + p.h)) break;
    const double slope = p.Slope(t);
    double next = slope != 0.0 ? t - f / slope : lo - 1.0;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    t = next;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

struct ProfileSpline::Impl {
  ProfileKind kind;
  std::string source;
  std::vector<double> s;
  gsl::Spline y;
  gsl::Spline z;
  std::vector<Cubic> y_pieces;  ///< y on each knot interval, for SAtY.
  std::vector<double> piece_y_min;
  std::vector<double> piece_y_max;

  void CheckRange(double& at) const {
    const double length = s.back();
    const double slack = kRangeSlack * length;
    if (!(at >= -slack && at <= length + slack)) {
      throw std::out_of_range(source + ": arc length " + std::to_string(at) +
                              " mm outside the profile [0, " + std::to_string(length) + "]");
    }
    at = std::clamp(at, 0.0, length);
  }
};

namespace {

std::vector<double> ChordLengths(const std::vector<double>& y, const std::vector<double>& z) {
  std::vector<double> s(y.size(), 0.0);
  for (std::size_t i = 1; i < y.size(); ++i) {
    s[i] = s[i - 1] + std::hypot(y[i] - y[i - 1], z[i] - z[i - 1]);
  }
  return s;
}

/// Arc lengths from the first knot to every knot of the curve (y(s), z(s)).
std::vector<double> ArcLengths(const gsl::Spline& y, const gsl::Spline& z) {
  static const GaussLegendre5 rule;
  const std::vector<double>& knots = y.knots();
  std::vector<double> arc(knots.size(), 0.0);
  for (std::size_t i = 0; i + 1 < knots.size(); ++i) {
    const double mid = 0.5 * (knots[i] + knots[i + 1]);
    const double half = 0.5 * (knots[i + 1] - knots[i]);
    double sum = 0.0;
    for (std::size_t k = 0; k < rule.nodes.size(); ++k) {
      const double at = mid + half * rule.nodes[k];
      sum += rule.weights[k] * std::hypot(y.Derivative(at), z.Derivative(at));
    }
    arc[i + 1] = arc[i] + half * sum;
  }
  return arc;
}

}  // namespace

ProfileSpline::ProfileSpline(const Profile& profile) {
  const std::size_t n = profile.y.size();
  if (n < 4 || profile.z.size() != n) {
    throw InputError(profile.source + ": a profile spline needs at least 4 points, got " +
                     std::to_string(n));
  }
  std::vector<double> s = ChordLengths(profile.y, profile.z);
  for (std::size_t i = 1; i < n; ++i) {
    if (!(s[i] > s[i - 1])) {
      const int line = i < profile.lines.size() ? profile.lines[i] : static_cast<int>(i) + 1;
      throw InputError(profile.source + ":" + std::to_string(line) +
                       ": point coincides with the previous one");
    }
  }
  // Chord length underestimates the arc length of curved parts; refine the knots until each
  // interval's parameter length equals the spline's arc length over it.
  for (int pass = 0; pass < kMaxRefinements; ++pass) {
    const gsl::Spline y(s, profile.y);
    const gsl::Spline z(s, profile.z);
    std::vector<double> refined = ArcLengths(y, z);
    double change = 0.0;
    for (std::size_t i = 0; i < n; ++i) change = std::max(change, std::abs(refined[i] - s[i]));
    s = std::move(refined);
    if (change <= kKnotTolerance * s.back()) break;
  }
  impl_ = std::make_unique<Impl>(Impl{profile.kind,
                                      profile.source,
                                      s,
                                      gsl::Spline(s, profile.y),
                                      gsl::Spline(s, profile.z),
                                      {},
                                      {},
                                      {}});

  Impl& impl = *impl_;
  impl.y_pieces.reserve(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double h = s[i + 1] - s[i];
    const Cubic piece = HermiteCubic(profile.y[i], profile.y[i + 1], impl.y.Derivative(s[i]),
                                     impl.y.Derivative(s[i + 1]), h);
    double lo = std::min(profile.y[i], profile.y[i + 1]);
    double hi = std::max(profile.y[i], profile.y[i + 1]);
    for (const double t : CriticalPoints(piece)) {
      lo = std::min(lo, piece.Value(t));
      hi = std::max(hi, piece.Value(t));
    }
    impl.y_pieces.push_back(piece);
    impl.piece_y_min.push_back(lo);
    impl.piece_y_max.push_back(hi);
  }
}

ProfileSpline::~ProfileSpline() = default;
ProfileSpline::ProfileSpline(const ProfileSpline& other)
    : impl_(std::make_unique<Impl>(*other.impl_)) {}
ProfileSpline& ProfileSpline::operator=(const ProfileSpline& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
ProfileSpline::ProfileSpline(ProfileSpline&& other) noexcept = default;
ProfileSpline& ProfileSpline::operator=(ProfileSpline&& other) noexcept = default;

ProfileKind ProfileSpline::kind() const { return impl_->kind; }
double ProfileSpline::length() const { return impl_->s.back(); }
const std::vector<double>& ProfileSpline::knots() const { return impl_->s; }

double ProfileSpline::YMin() const {
  return *std::min_element(impl_->piece_y_min.begin(), impl_->piece_y_min.end());
}
double ProfileSpline::YMax() const {
  return *std::max_element(impl_->piece_y_max.begin(), impl_->piece_y_max.end());
}

ProfileVector ProfileSpline::PositionAt(double s) const {
  impl_->CheckRange(s);
  return ProfileVector{impl_->y.Value(s), impl_->z.Value(s)};
}

ProfileVector ProfileSpline::TangentAt(double s) const {
  impl_->CheckRange(s);
  const double dy = impl_->y.Derivative(s);
  const double dz = impl_->z.Derivative(s);
  const double speed = std::hypot(dy, dz);
  return ProfileVector{dy / speed, dz / speed};
}

ProfileVector ProfileSpline::NormalAt(double s) const {
  // The material lies to the right of the tangent (in the y–z picture with z down), that is
  // in direction (−t_z, t_y); the outward normal is the opposite.
  const ProfileVector t = TangentAt(s);
  return ProfileVector{t.z, -t.y};
}

double ProfileSpline::InclinationAt(double s) const {
  const ProfileVector t = TangentAt(s);
  // Wheels run with y descending; their tangent is turned around so that, like on a rail, the
  // angle is measured along the direction of increasing y.
  const double sign = impl_->kind == ProfileKind::kRail ? 1.0 : -1.0;
  return std::atan2(sign * t.z, sign * t.y);
}

double ProfileSpline::CurvatureAt(double s) const {
  impl_->CheckRange(s);
  const double dy = impl_->y.Derivative(s);
  const double dz = impl_->z.Derivative(s);
  const double ddy = impl_->y.SecondDerivative(s);
  const double ddz = impl_->z.SecondDerivative(s);
  const double speed = std::hypot(dy, dz);
  // Positive when the curve bends towards the material side (convex body).
  return (dy * ddz - dz * ddy) / (speed * speed * speed);
}

std::vector<double> ProfileSpline::SAtY(double y) const {
  const Impl& impl = *impl_;
  std::vector<double> roots;
  const std::size_t pieces = impl.y_pieces.size();
  for (std::size_t k = 0; k < pieces; ++k) {
    if (y < impl.piece_y_min[k] || y > impl.piece_y_max[k]) continue;
    const Cubic& p = impl.y_pieces[k];
    std::vector<double> bounds{0.0};
    for (const double t : CriticalPoints(p)) bounds.push_back(t);
    bounds.push_back(p.h);
    for (std::size_t b = 0; b + 1 < bounds.size(); ++b) {
      const double f_lo = p.Value(bounds[b]) - y;
      const double f_hi = p.Value(bounds[b + 1]) - y;
      // Each sub-interval owns its left end; the right end of the whole curve is added last.
      if (f_lo == 0.0) {
        roots.push_back(impl.s[k] + bounds[b]);
      } else if ((f_lo < 0.0) != (f_hi < 0.0) && f_hi != 0.0) {
        roots.push_back(impl.s[k] + SolveMonotone(p, y, bounds[b], bounds[b + 1]));
      }
    }
  }
  if (impl.y.values().back() == y) roots.push_back(impl.s.back());
  std::sort(roots.begin(), roots.end());
  // A root on a knot or critical point can be found from both sides; 1e-9 mm apart is the same.
  roots.erase(std::unique(roots.begin(), roots.end(),
                          [](double a, double b) { return std::abs(a - b) <= 1e-9; }),
              roots.end());
  for (double& root : roots) root = std::clamp(root, 0.0, impl.s.back());
  return roots;
}

ProfileHeight ProfileSpline::ZAtY(double y) const {
  ProfileHeight result;
  const std::vector<double> roots = SAtY(y);
  if (roots.empty()) {
    result.status = ProfileHeight::Status::kOutside;
    result.z = std::numeric_limits<double>::quiet_NaN();
    result.s = std::numeric_limits<double>::quiet_NaN();
    return result;
  }
  result.status =
      roots.size() == 1 ? ProfileHeight::Status::kInside : ProfileHeight::Status::kMultiValued;
  // The surface facing the other body: the top of a rail, the bottom of a wheel.
  const bool rail = impl_->kind == ProfileKind::kRail;
  result.s = roots.front();
  result.z = impl_->z.Value(roots.front());
  for (std::size_t i = 1; i < roots.size(); ++i) {
    const double z = impl_->z.Value(roots[i]);
    if (rail ? z < result.z : z > result.z) {
      result.z = z;
      result.s = roots[i];
    }
  }
  return result;
}

}  // namespace wrc
