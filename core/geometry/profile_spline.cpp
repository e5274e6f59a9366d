// Arc-length parametrised spline of a profile: y(s), z(s) as GSL natural cubic splines, one pair
// per part between kinks, and a table of the knot intervals by y for SAtY / ZAtY.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/geometry/profile_internal.h"
#include "core/gsl/spline.h"
#include "wrc/core/errors.h"
#include "wrc/core/profile.h"

namespace wrc {
namespace {

// Knot refinement stops when no knot moves by more than this fraction of the length; 1e-10 of
// at most 500 mm is 0.05 nm, far below anything geometric, yet well above the round-off of
// summing a few thousand interval lengths (~1e-13 relative).
constexpr double kKnotTolerance = 1e-10;
// The refinement contracts fast (each pass multiplies the knot changes by roughly the relative
// variation of the speed |r'| within an interval); 50 passes are never needed in practice, so a
// part that has not settled by then is refused rather than parametrised wrongly.
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

/// The root of p(t) = target in [lo, hi], where p is monotone and changes sign (f_lo and f_hi:
/// p − target at the ends): Newton steps kept inside the shrinking bracket, bisection when a
/// step would leave it.
double SolveMonotone(const Cubic& p, double target, double lo, double hi, double f_lo,
                     double f_hi) {
  // Start from the chord (regula falsi): on the short, nearly straight knot intervals of a
  // profile it is within a few ulps of the root after one or two Newton steps.
  double t = f_lo != f_hi ? lo + (hi - lo) * f_lo / (f_lo - f_hi) : 0.5 * (lo + hi);
  if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
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

/// One knot interval's y(s) as a cubic in t = s − s_i, with what SAtY needs precomputed.
struct YPiece {
  Cubic y;
  Cubic z;  ///< z(s) on the same interval, for ZAtY without a GSL lookup.
  /// 0, the critical points of y inside (0, h) ascending, h: y is monotone between them.
  std::array<double, 4> bounds;
  /// y at each bound, kept because every root search on the interval starts from them.
  std::array<double, 4> bound_y;
  std::size_t bound_count;
  double y_min;  ///< Range of y over the interval (end values and extrema).
  double y_max;
};

/// A part of the curve between kinks (or the profile ends): knots first..last of the profile.
struct Part {
  std::size_t first;
  std::size_t last;
  gsl::Spline y;
  gsl::Spline z;
};

/// The knot intervals grouped by y: bucket b covers [y0 + b·width, y0 + (b+1)·width) and lists
/// (ascending) every interval whose y range overlaps it. Bucket() is monotone in y, so an
/// interval with y_min ≤ y ≤ y_max, listed in the buckets of y_min to y_max, is always in the
/// bucket of y: the table never loses a candidate.
struct YTable {
  double y0 = 0.0;
  double width = 1.0;
  std::size_t bucket_count = 1;
  std::vector<std::size_t> begin;      ///< Bucket b's intervals: entries[begin[b], begin[b+1]).
  std::vector<std::size_t> intervals;  ///< The lists of all buckets, one after the other.

  std::size_t Bucket(double y) const {
    const double index = std::floor((y - y0) / width);
    return static_cast<std::size_t>(std::clamp(index, 0.0, static_cast<double>(bucket_count - 1)));
  }
};

}  // namespace

struct ProfileSpline::Impl {
  ProfileKind kind;
  std::string source;
  std::vector<std::string> warnings;            ///< The profile's repairs (Profile::warnings).
  std::vector<std::string> orientation_doubts;  ///< Profile::orientation_doubts.
  std::vector<double> s;                        ///< Knots: the arc length at each profile point.
  std::vector<Part> parts;         ///< Ascending in s; a kink is the last knot of one part and
                                   ///< the first of the next.
  std::vector<double> part_start;  ///< s at each part's first knot.
  std::vector<YPiece> pieces;      ///< One per knot interval.
  double last_y = 0.0;             ///< y of the last point.
  double y_min = 0.0;
  double y_max = 0.0;
  YTable table;

  void CheckRange(double& at) const {
    const double length = s.back();
    const double slack = kRangeSlack * length;
    if (!(at >= -slack && at <= length + slack)) {
      throw std::out_of_range(source + ": arc length " + FormatNumber(at) +
                              " mm outside the profile [0, " + FormatNumber(length) + "]");
    }
    at = std::clamp(at, 0.0, length);
  }

  /// The part whose spline is evaluated at `at` (in range): the last one starting at or
  /// before it, so at a kink the part after the kink.
  const Part& PartAt(double at) const {
    const auto after = std::upper_bound(part_start.begin(), part_start.end(), at);
    const auto index =
        static_cast<std::size_t>(std::max<std::ptrdiff_t>(after - part_start.begin() - 1, 0));
    return parts[index];
  }

  /// Adds the roots of y(s) = y on knot interval k to `roots`. Each monotone sub-interval owns
  /// its left end; the right end of the whole curve is added by FinishRoots.
  void AddRootsInInterval(std::size_t k, double y, std::vector<double>& roots) const {
    ForEachRootInInterval(k, y, [&](double t) { roots.push_back(s[k] + t); });
  }

  /// Calls found(t) for each root t (relative to s_k) of y(s) = y on knot interval k, with the
  /// convention of AddRootsInInterval.
  template <typename Found>
  void ForEachRootInInterval(std::size_t k, double y, Found found) const {
    const YPiece& piece = pieces[k];
    if (y < piece.y_min || y > piece.y_max) return;
    for (std::size_t b = 0; b + 1 < piece.bound_count; ++b) {
      const double f_lo = piece.bound_y[b] - y;
      const double f_hi = piece.bound_y[b + 1] - y;
      if (f_lo == 0.0) {
        found(piece.bounds[b]);
      } else if ((f_lo < 0.0) != (f_hi < 0.0) && f_hi != 0.0) {
        found(SolveMonotone(piece.y, y, piece.bounds[b], piece.bounds[b + 1], f_lo, f_hi));
      }
    }
  }

  void FinishRoots(double y, std::vector<double>& roots) const {
    if (last_y == y) roots.push_back(s.back());
    std::sort(roots.begin(), roots.end());
    // A root on a knot or critical point can be found from both sides; 1e-9 mm apart is the
    // same point (far below any geometric scale, far above the root solver's round-off).
    roots.erase(std::unique(roots.begin(), roots.end(),
                            [](double a, double b) { return std::abs(a - b) <= 1e-9; }),
                roots.end());
    for (double& root : roots) root = std::clamp(root, 0.0, s.back());
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

/// Arc lengths of the curve (y(s), z(s)) at every knot, counted from `start` at the first.
std::vector<double> ArcLengths(const gsl::Spline& y, const gsl::Spline& z, double start) {
  static const GaussLegendre5 rule;
  const std::vector<double>& knots = y.knots();
  std::vector<double> arc(knots.size(), start);
  std::array<double, 5> at, dy, dz;
  static_assert(std::tuple_size<decltype(rule.nodes)>::value == at.size());
  for (std::size_t i = 0; i + 1 < knots.size(); ++i) {
    const double mid = 0.5 * (knots[i] + knots[i + 1]);
    const double half = 0.5 * (knots[i + 1] - knots[i]);
    for (std::size_t k = 0; k < at.size(); ++k) at[k] = mid + half * rule.nodes[k];
    y.DerivativesOn(i, at.data(), at.size(), dy.data());
    z.DerivativesOn(i, at.data(), at.size(), dz.data());
    double sum = 0.0;
    for (std::size_t k = 0; k < at.size(); ++k) {
      // The plain root: the speed is ~1 (arc-length parameter), far from over- or underflow,
      // and std::hypot's rescaling was a tenth of reading a profile.
      sum += rule.weights[k] * std::sqrt(dy[k] * dy[k] + dz[k] * dz[k]);
    }
    arc[i + 1] = arc[i] + half * sum;
  }
  return arc;
}

/// Where a part ends: at an end of the profile or at a kink.
struct PartEnds {
  bool kink_before = false;
  bool kink_after = false;
};

/// The spline of one coordinate over a part. Two points make a straight piece (a cubic needs
/// three knots). The profile's own ends keep the natural condition (a part without kinks is
/// the natural cubic spline of the profile without kink detection). At a kink, a natural end would
/// force zero curvature into the corner of a curved part (3.7 µm of z error on the wall of
/// groove_r1010.prr, whose last interval spans 1.4 mm of arc); the not-a-knot end takes the
/// curvature from the data instead.
gsl::Spline PartSpline(std::vector<double> s, std::vector<double> f, PartEnds ends) {
  if (f.size() < 3) return gsl::Spline(std::move(s), std::move(f), gsl::SplineType::kLinear);
  // wrc's own cubic type also where both ends are natural (the spline of gsl_interp_cspline):
  // its pieces are at hand, so the arc-length quadrature takes each interval's once for its
  // five points instead of five GSL lookups (a third of reading a profile).
  const auto end = [](bool kink) {
    return kink ? gsl::CubicEnd::kNotAKnot : gsl::CubicEnd::kNatural;
  };
  return gsl::Spline(std::move(s), std::move(f), end(ends.kink_before), end(ends.kink_after));
}

/// The knots of the part through (y, z) starting at arc length `start`: chord lengths, then
/// refined until each interval's parameter length equals the spline's arc length over it
/// (chord length underestimates the arc length of curved parts). Empty when the refinement
/// does not settle: points that turn back sharply within a part can make it run away (each
/// pass lengthens an overshooting interval, which overshoots more) until the knots overflow.
std::vector<double> PartKnots(const std::vector<double>& y, const std::vector<double>& z,
                              double start, PartEnds ends) {
  std::vector<double> s = ChordLengths(y, z);
  for (double& knot : s) knot += start;
  for (int pass = 0; pass < kMaxRefinements; ++pass) {
    const gsl::Spline spline_y = PartSpline(s, y, ends);
    const gsl::Spline spline_z = PartSpline(s, z, ends);
    std::vector<double> refined = ArcLengths(spline_y, spline_z, start);
    double change = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      change = std::max(change, std::abs(refined[i] - s[i]));
      // NaN fails the comparison too.
      if (i > 0 && !(refined[i] > refined[i - 1] && std::isfinite(refined[i]))) return {};
    }
    s = std::move(refined);
    if (change <= kKnotTolerance * s.back()) return s;
  }
  return {};
}

/// y on knot interval [s_i, s_i+1] of `part`, with its monotone pieces and range.
YPiece MakeYPiece(const Part& part, const std::vector<double>& s, const std::vector<double>& y,
                  const std::vector<double>& z, std::size_t i) {
  YPiece piece{};
  const std::size_t k = i - part.first;  // the interval within the part's splines
  piece.y = HermiteCubic(y[i], y[i + 1], part.y.DerivativeOn(k, s[i]),
                         part.y.DerivativeOn(k, s[i + 1]), s[i + 1] - s[i]);
  piece.z = HermiteCubic(z[i], z[i + 1], part.z.DerivativeOn(k, s[i]),
                         part.z.DerivativeOn(k, s[i + 1]), s[i + 1] - s[i]);
  piece.y_min = std::min(y[i], y[i + 1]);
  piece.y_max = std::max(y[i], y[i + 1]);
  piece.bound_count = 0;
  piece.bounds[piece.bound_count++] = 0.0;
  for (const double t : CriticalPoints(piece.y)) {
    piece.bounds[piece.bound_count++] = t;
    piece.y_min = std::min(piece.y_min, piece.y.Value(t));
    piece.y_max = std::max(piece.y_max, piece.y.Value(t));
  }
  piece.bounds[piece.bound_count++] = piece.y.h;
  for (std::size_t b = 0; b < piece.bound_count; ++b)
    piece.bound_y[b] = piece.y.Value(piece.bounds[b]);
  return piece;
}

/// The table of intervals by y over [y_min, y_max], with as many buckets as intervals: about
/// one interval per bucket where the profile is single-valued in y.
YTable MakeYTable(const std::vector<YPiece>& pieces, double y_min, double y_max) {
  YTable table;
  table.y0 = y_min;
  if (y_max > y_min) {
    table.bucket_count = pieces.size();
    table.width = (y_max - y_min) / static_cast<double>(table.bucket_count);
  }
  std::vector<std::size_t> counts(table.bucket_count + 1, 0);
  for (const YPiece& piece : pieces) {
    for (std::size_t b = table.Bucket(piece.y_min); b <= table.Bucket(piece.y_max); ++b) {
      ++counts[b + 1];
    }
  }
  table.begin.resize(table.bucket_count + 1, 0);
  for (std::size_t b = 0; b < table.bucket_count; ++b) {
    table.begin[b + 1] = table.begin[b] + counts[b + 1];
  }
  table.intervals.resize(table.begin.back());
  std::vector<std::size_t> filled(table.begin.begin(), table.begin.end() - 1);
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    for (std::size_t b = table.Bucket(pieces[k].y_min); b <= table.Bucket(pieces[k].y_max); ++b) {
      table.intervals[filled[b]++] = k;
    }
  }
  return table;
}

}  // namespace

ProfileSpline::ProfileSpline(const Profile& profile) {
  const std::size_t n = profile.y.size();
  if (n < 4 || profile.z.size() != n) {
    throw InputError(profile.source + ": a profile spline needs at least 4 points, got " +
                     std::to_string(n));
  }
  const std::vector<double> chords = ChordLengths(profile.y, profile.z);
  for (std::size_t i = 1; i < n; ++i) {
    if (!(chords[i] > chords[i - 1])) {
      const int line = i < profile.lines.size() ? profile.lines[i] : static_cast<int>(i) + 1;
      throw InputError(profile.source + ":" + std::to_string(line) +
                       ": point coincides with the previous one");
    }
  }
  // The parts run from one kink to the next; kinks at the ends or out of order would make
  // empty parts and are not something RepairProfile produces.
  std::vector<std::size_t> bounds{0};
  for (const std::size_t kink : profile.kinks) {
    if (kink <= bounds.back() || kink + 1 >= n) {
      throw InputError(profile.source + ": kink index " + std::to_string(kink) +
                       " is not an interior point in ascending order");
    }
    bounds.push_back(kink);
  }
  bounds.push_back(n - 1);

  impl_ = std::make_unique<Impl>();
  Impl& impl = *impl_;
  impl.warnings = profile.warnings;
  impl.orientation_doubts = profile.orientation_doubts;
  impl.kind = profile.kind;
  impl.source = profile.source;
  impl.s.assign(n, 0.0);
  impl.last_y = profile.y.back();
  for (std::size_t p = 0; p + 1 < bounds.size(); ++p) {
    const auto first = static_cast<std::ptrdiff_t>(bounds[p]);
    const auto end = static_cast<std::ptrdiff_t>(bounds[p + 1]) + 1;
    std::vector<double> y(profile.y.begin() + first, profile.y.begin() + end);
    std::vector<double> z(profile.z.begin() + first, profile.z.begin() + end);
    // Each part starts where the previous one ended, so s stays the arc length from point 0.
    const double start = impl.s[bounds[p]];
    const PartEnds ends{p > 0, p + 2 < bounds.size()};
    std::vector<double> knots = PartKnots(y, z, start, ends);
    if (knots.empty()) {
      const auto line_of = [&profile](std::size_t i) {
        return i < profile.lines.size() ? profile.lines[i] : static_cast<int>(i) + 1;
      };
      throw InputError(profile.source + ":" + std::to_string(line_of(bounds[p])) +
                       ": no arc-length spline through the points of lines " +
                       std::to_string(line_of(bounds[p])) + " to " +
                       std::to_string(line_of(bounds[p + 1])) +
                       " (its knot refinement does not converge); the profile turns back "
                       "sharply there");
    }
    std::copy(knots.begin(), knots.end(), impl.s.begin() + first);
    impl.part_start.push_back(knots.front());
    impl.parts.push_back(Part{bounds[p], bounds[p + 1], PartSpline(knots, std::move(y), ends),
                              PartSpline(knots, std::move(z), ends)});
  }

  impl.pieces.reserve(n - 1);
  for (const Part& part : impl.parts) {
    for (std::size_t i = part.first; i < part.last; ++i) {
      impl.pieces.push_back(MakeYPiece(part, impl.s, profile.y, profile.z, i));
    }
  }
  impl.y_min = impl.pieces.front().y_min;
  impl.y_max = impl.pieces.front().y_max;
  for (const YPiece& piece : impl.pieces) {
    impl.y_min = std::min(impl.y_min, piece.y_min);
    impl.y_max = std::max(impl.y_max, piece.y_max);
  }
  impl.table = MakeYTable(impl.pieces, impl.y_min, impl.y_max);
}

ProfileSpline::~ProfileSpline() = default;
const std::vector<std::string>& ProfileSpline::warnings() const { return impl_->warnings; }
const std::vector<std::string>& ProfileSpline::orientation_doubts() const {
  return impl_->orientation_doubts;
}

ProfileSpline::ProfileSpline(const ProfileSpline& other)
    : impl_(std::make_unique<Impl>(*other.impl_)) {}
ProfileSpline& ProfileSpline::operator=(const ProfileSpline& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
ProfileSpline::ProfileSpline(ProfileSpline&& other) noexcept = default;
ProfileSpline& ProfileSpline::operator=(ProfileSpline&& other) noexcept = default;

const std::string& ProfileSpline::source() const { return impl_->source; }

ProfileKind ProfileSpline::kind() const { return impl_->kind; }
double ProfileSpline::length() const { return impl_->s.back(); }
const std::vector<double>& ProfileSpline::knots() const { return impl_->s; }

double ProfileSpline::YMin() const { return impl_->y_min; }
double ProfileSpline::YMax() const { return impl_->y_max; }

ProfileVector ProfileSpline::PositionAt(double s) const {
  impl_->CheckRange(s);
  const Part& part = impl_->PartAt(s);
  return ProfileVector{part.y.Value(s), part.z.Value(s)};
}

std::vector<ProfileVector> ProfileSpline::PositionsAt(const std::vector<double>& s) const {
  const Impl& impl = *impl_;
  std::vector<ProfileVector> out(s.size());
  std::size_t part = 0, interval = 0;  // hints, moved on as s ascends
  for (std::size_t k = 0; k < s.size(); ++k) {
    double at = s[k];
    impl.CheckRange(at);
    if (k > 0 && !(s[k] >= s[k - 1])) {
      throw std::invalid_argument("ProfileSpline::PositionsAt: arc lengths must ascend");
    }
    // As PartAt: the last part starting at or before `at`.
    while (part + 1 < impl.parts.size() && impl.part_start[part + 1] <= at) {
      ++part;
      interval = 0;
    }
    const Part& p = impl.parts[part];
    const std::vector<double>& knots = p.y.knots();
    while (interval + 2 < knots.size() && knots[interval + 1] <= at) ++interval;
    out[k] = ProfileVector{p.y.ValueOn(interval, at), p.z.ValueOn(interval, at)};
  }
  return out;
}

ProfileVector ProfileSpline::TangentAt(double s) const {
  impl_->CheckRange(s);
  const Part& part = impl_->PartAt(s);
  const double dy = part.y.Derivative(s);
  const double dz = part.z.Derivative(s);
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
  const Part& part = impl_->PartAt(s);
  const double dy = part.y.Derivative(s);
  const double dz = part.z.Derivative(s);
  const double ddy = part.y.SecondDerivative(s);
  const double ddz = part.z.SecondDerivative(s);
  const double speed = std::hypot(dy, dz);
  // Positive when the curve bends towards the material side (convex body).
  return (dy * ddz - dz * ddy) / (speed * speed * speed);
}

std::vector<double> ProfileSpline::SAtY(double y) const {
  const Impl& impl = *impl_;
  std::vector<double> roots;
  // Outside [YMin, YMax] no interval reaches y (and NaN reaches none).
  if (y >= impl.y_min && y <= impl.y_max) {
    const YTable& table = impl.table;
    const std::size_t bucket = table.Bucket(y);
    for (std::size_t e = table.begin[bucket]; e < table.begin[bucket + 1]; ++e) {
      impl.AddRootsInInterval(table.intervals[e], y, roots);
    }
  }
  impl.FinishRoots(y, roots);
  return roots;
}

std::vector<double> profile_detail::SplineAccess::SAtYTryingEveryInterval(
    const ProfileSpline& spline, double y) {
  const ProfileSpline::Impl& impl = *spline.impl_;
  std::vector<double> roots;
  for (std::size_t k = 0; k < impl.pieces.size(); ++k) impl.AddRootsInInterval(k, y, roots);
  impl.FinishRoots(y, roots);
  return roots;
}

ProfileHeight ProfileSpline::ZAtY(double y) const {
  // The roots of SAtY, collected in a fixed buffer and evaluated on the cached interval cubics:
  // ZAtY is the inner loop of every wheel–rail distance (thousands of calls per solve), where a
  // heap-allocated root list and two GSL interval searches per call cost more than the roots.
  const Impl& impl = *impl_;
  struct Root {
    double s, z, dz_dy;
  };
  constexpr std::size_t kCapacity = 16;
  std::array<Root, kCapacity> inline_roots;
  std::vector<Root> spilled;  // only for a profile crossing y more than kCapacity times
  Root* roots = inline_roots.data();
  std::size_t count = 0;
  auto add = [&](const YPiece& piece, std::size_t k, double t) {
    const double dy = piece.y.Slope(t), dz = piece.z.Slope(t);
    const Root root{std::clamp(impl.s[k] + t, 0.0, impl.s.back()), piece.z.Value(t),
                    std::fabs(dy) > 1e-12 * std::fabs(dz) ? dz / dy : 1e12};
    if (count == kCapacity && spilled.empty()) spilled.assign(roots, roots + count);
    if (!spilled.empty()) {
      spilled.push_back(root);
      roots = spilled.data();
    } else {
      roots[count] = root;
    }
    ++count;
  };
  if (y >= impl.y_min && y <= impl.y_max) {
    const YTable& table = impl.table;
    const std::size_t bucket = table.Bucket(y);
    for (std::size_t e = table.begin[bucket]; e < table.begin[bucket + 1]; ++e) {
      const std::size_t k = table.intervals[e];
      impl.ForEachRootInInterval(k, y, [&](double t) { add(impl.pieces[k], k, t); });
    }
  }
  if (impl.last_y == y) {
    const YPiece& last = impl.pieces.back();
    add(last, impl.pieces.size() - 1, last.y.h);
  }
  ProfileHeight result;
  if (count == 0) {
    result.status = ProfileHeight::Status::kOutside;
    result.z = result.s = result.dz_dy = std::numeric_limits<double>::quiet_NaN();
    return result;
  }
  std::sort(roots, roots + count, [](const Root& a, const Root& b) { return a.s < b.s; });
  // A root on a knot or critical point can be found from both sides (as in SAtY).
  std::size_t distinct = 1;
  for (std::size_t i = 1; i < count; ++i) {
    if (roots[i].s - roots[distinct - 1].s > 1e-9) roots[distinct++] = roots[i];
  }
  result.status =
      distinct == 1 ? ProfileHeight::Status::kInside : ProfileHeight::Status::kMultiValued;
  // The surface facing the other body: the top of a rail, the bottom of a wheel.
  const bool rail = impl.kind == ProfileKind::kRail;
  std::size_t best = 0;
  for (std::size_t i = 1; i < distinct; ++i) {
    if (rail ? roots[i].z < roots[best].z : roots[i].z > roots[best].z) best = i;
  }
  result.s = roots[best].s;
  result.z = roots[best].z;
  result.dz_dy = roots[best].dz_dy;
  return result;
}

}  // namespace wrc
