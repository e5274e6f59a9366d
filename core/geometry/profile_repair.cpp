// Repairs of measured profiles as CONTACT applies them: mirroring, orientation, duplicate
// points, zig-zags, loops, and the final checks.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "core/common/numbers.h"
#include "core/geometry/profile_internal.h"
#include "wrc/core/errors.h"
#include "wrc/core/profile.h"

namespace wrc {
namespace {

using profile_detail::At;

// Side-face detection for MirrorZ::kAuto. The end face is the chord over the last 2 mm of arc
// length: long enough to average the noise of a few measured points (MiniProf spacing is
// 0.1–0.5 mm), short enough to see only the outermost face. It counts as a side face when
// steeper than 30°, well above any running surface inclination (treads and rail tops are
// within a few degrees, flange roots reach ~20° only beyond the first 2 mm).
constexpr double kEndFaceLength = 2.0;
constexpr double kSideFaceMinAngleDeg = 30.0;
// A self-crossing whose loop is at most this long (mm) is cut out: stitching two measured
// sections leaves overlaps of a few point spacings; longer loops are real geometry or a broken
// file, which CONTACT refuses, and so do we.
constexpr double kMaxRepairableLoop = 2.0;
// CONTACT requires the summed chord length to lie in this range (mm), which catches profiles
// given in m or in inches.
constexpr double kMinProfileLength = 5.0;
constexpr double kMaxProfileLength = 500.0;
constexpr std::size_t kMinPoints = 4;
// A point this close (mm) to the previous one counts as a repeat. 1 nm lies far below the
// resolution of profile measurements (micrometres), and a shorter segment has no usable
// direction: it made the smoothing system singular (found by fuzzing, see docs/robustness.md)
// and can vanish in the spline's summed arc length.
constexpr double kRepeatDistance = 1e-6;

struct Point {
  double y;
  double z;
  int line;
};

std::string Format(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

double Distance(const Point& a, const Point& b) { return std::hypot(b.y - a.y, b.z - a.z); }

double Length(const std::vector<Point>& points) {
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) length += Distance(points[i - 1], points[i]);
  return length;
}

/// Turning angle at interior point i in (−π, π]: the change of direction from segment (i−1, i)
/// to segment (i, i+1). Zero-length segments give 0 (they are removed before this is used).
double TurnAngle(const std::vector<Point>& p, std::size_t i) {
  const double ay = p[i].y - p[i - 1].y;
  const double az = p[i].z - p[i - 1].z;
  const double by = p[i + 1].y - p[i].y;
  const double bz = p[i + 1].z - p[i].z;
  return std::atan2(ay * bz - az * by, ay * by + az * bz);
}

std::string KindName(ProfileKind kind) { return kind == ProfileKind::kRail ? "rail" : "wheel"; }

/// +1 when the end face starting at points[first] (walking in direction `step`) points the way
/// a side face of `kind` should (rail: towards +z going outwards, wheel: towards −z), −1 when
/// the other way, 0 when the end is no side face (not steep enough).
int EndFaceVote(const std::vector<Point>& points, std::size_t first, int step, ProfileKind kind) {
  const std::size_t n = points.size();
  std::size_t inner = first;
  double walked = 0.0;
  while (walked < kEndFaceLength) {
    const std::size_t next = step > 0 ? inner + 1 : inner - 1;
    if (step > 0 ? next >= n : inner == 0) break;
    walked += Distance(points[inner], points[next]);
    inner = next;
  }
  const double dy = points[first].y - points[inner].y;  // Outward along the face.
  const double dz = points[first].z - points[inner].z;
  if (std::abs(dz) <= std::tan(kSideFaceMinAngleDeg * kPi / 180.0) * std::abs(dy)) return 0;
  const bool outward_down = dz > 0.0;
  return outward_down == (kind == ProfileKind::kRail) ? 1 : -1;
}

/// The side faces' vote on the z orientation of `points` as they stand: > 0 right way up,
/// < 0 upside down, 0 undecided.
int SideFaceVotes(const std::vector<Point>& points, ProfileKind kind) {
  return EndFaceVote(points, 0, +1, kind) + EndFaceVote(points, points.size() - 1, -1, kind);
}

/// The evidence behind a vote, for messages.
std::string SideFaceReason(int votes, ProfileKind kind) {
  const std::string expected =
      kind == ProfileKind::kRail ? "a rail's run downwards (+z)" : "a wheel's run upwards (−z)";
  if (votes > 0) return "its end faces point the way " + expected;
  return "its end faces point against the way " + expected;
}

/// Decides MirrorZ::kAuto: true when z must be mirrored. Adds a warning when undecided, and
/// one with the decision when asked to report it.
bool AutoMirrorZ(const std::vector<Point>& points, ProfileKind kind, const std::string& source,
                 bool report, std::vector<std::string>& warnings) {
  const int first = EndFaceVote(points, 0, +1, kind);
  const int votes = SideFaceVotes(points, kind);
  if (votes != 0) {
    if (report) {
      warnings.push_back(source + ": mirror_z = \"auto\": z " +
                         (votes < 0 ? "mirrored" : "used as given") + " (" +
                         SideFaceReason(votes, kind) + ")");
    }
    return votes < 0;
  }
  const std::string reason = first == 0 ? "neither end has a side face steeper than 30°"
                                        : "the two end faces point different ways";
  warnings.push_back(source + ": cannot detect the z orientation of the " + KindName(kind) +
                     " profile (" + reason + "); z is used as given (set mirror_z to decide)");
  return false;
}

/// A warning that the orientation looks wrong, also kept apart for error messages.
void AddDoubt(Profile& profile, std::string message) {
  profile.orientation_doubts.push_back(message);
  profile.warnings.push_back(std::move(message));
}

/// For an explicit mirror_z: warns when the side faces say the result is upside down.
void CheckZOrientation(const std::vector<Point>& points, ProfileKind kind, bool mirrored,
                       const std::string& source, Profile& profile) {
  const int votes = SideFaceVotes(points, kind);
  if (votes >= 0) return;
  AddDoubt(profile, source + ": the " + KindName(kind) + " profile looks upside down (" +
                        SideFaceReason(votes, kind) +
                        "): set mirror_z = " + (mirrored ? "false" : "true") + " (or \"auto\")");
}

/// Mirrors y when detect_mirror_y says so, or warns when the shape contradicts mirror_y.
/// `points` have z the right way up already.
void OrientLaterally(std::vector<Point>& points, ProfileKind kind, const ProfileOptions& options,
                     const std::string& source, Profile& profile,
                     std::vector<std::string>& warnings) {
  std::vector<double> y(points.size()), z(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    y[i] = points[i].y;
    z[i] = points[i].z;
  }
  const LateralOrientation judged = JudgeLateralOrientation(y, z, kind);
  const bool mirrored = judged.verdict == LateralVerdict::kMirrored;
  if (!options.detect_mirror_y) {
    if (!mirrored) return;
    AddDoubt(profile, source + ": the " + KindName(kind) +
                          " profile looks mirrored in y, field side and track-centre side "
                          "swapped (" +
                          judged.reason + "): set mirror_y = " +
                          (options.mirror_y ? "false" : "true") + " (or \"auto\")");
    return;
  }
  if (mirrored) {
    for (Point& p : points) p.y = -p.y;
    profile.mirrored_y = !profile.mirrored_y;
  }
  if (judged.verdict == LateralVerdict::kUndecided) {
    warnings.push_back(source + ": mirror_y = \"auto\" cannot tell the side of the " +
                       KindName(kind) + " profile (" + judged.reason +
                       "); y is used as given (set mirror_y to decide)");
  } else if (options.report_orientation) {
    warnings.push_back(source + ": mirror_y = \"auto\": y " +
                       (mirrored ? "mirrored" : "used as given") + " (" + judged.reason + ")");
  }
}

/// The length check's message, with the scale that would bring a metre file into range.
std::string LengthProblem(const std::string& source, double length) {
  std::string message = source + ": profile length " + Format("%.6g", length) +
                        " mm is outside [5, 500] mm (CONTACT's limits); are the units mm?";
  if (length * 1000.0 >= kMinProfileLength && length * 1000.0 <= kMaxProfileLength) {
    message += " The values look like metres: set scale_yz = 1000";
  } else if (length / 1000.0 >= kMinProfileLength && length / 1000.0 <= kMaxProfileLength) {
    message += " The values look like micrometres: set scale_yz = 0.001";
  }
  return message;
}

/// Drops points equal to (within kRepeatDistance of) their predecessor.
void RemoveDuplicates(std::vector<Point>& points, const std::string& source,
                      std::vector<std::string>& warnings) {
  std::vector<Point> kept;
  kept.reserve(points.size());
  std::vector<int> dropped_lines;
  for (const Point& p : points) {
    if (!kept.empty() && Distance(kept.back(), p) <= kRepeatDistance) {
      dropped_lines.push_back(p.line);
      continue;
    }
    kept.push_back(p);
  }
  if (dropped_lines.empty()) return;
  std::string list;
  constexpr std::size_t kListed = 5;
  for (std::size_t i = 0; i < dropped_lines.size() && i < kListed; ++i) {
    list += (i == 0 ? "" : ", ") + std::to_string(dropped_lines[i]);
  }
  if (dropped_lines.size() > kListed) list += ", ...";
  warnings.push_back(At(
      source, dropped_lines.front(),
      std::to_string(dropped_lines.size()) + " duplicate point(s) removed (lines " + list + ")"));
  points = std::move(kept);
}

/// Zig-zags: two successive points that both turn by more than the threshold are replaced by
/// their average (CONTACT); a single point turning by more than the threshold is deleted when
/// `remove_spikes` is set.
void RemoveZigZags(std::vector<Point>& points, double threshold_deg, bool remove_spikes,
                   const std::string& source, std::vector<std::string>& warnings) {
  const double threshold = threshold_deg * kPi / 180.0;
  std::size_t i = 1;
  while (points.size() >= 3 && i + 1 < points.size()) {
    const double turn = std::abs(TurnAngle(points, i));
    if (turn <= threshold) {
      ++i;
      continue;
    }
    const bool pair = i + 2 < points.size() && std::abs(TurnAngle(points, i + 1)) > threshold;
    if (pair) {
      const double next_turn = std::abs(TurnAngle(points, i + 1));
      // The merged point keeps the smaller line number, so that the result and the message
      // do not depend on the direction the file runs in.
      const int first_line = std::min(points[i].line, points[i + 1].line);
      const int second_line = std::max(points[i].line, points[i + 1].line);
      const Point merged{0.5 * (points[i].y + points[i + 1].y),
                         0.5 * (points[i].z + points[i + 1].z), first_line};
      warnings.push_back(
          At(source, first_line,
             "zig-zag at lines " + std::to_string(first_line) + " and " +
                 std::to_string(second_line) + " (turns of " + Format("%.1f", turn * 180.0 / kPi) +
                 "° and " + Format("%.1f", next_turn * 180.0 / kPi) + "° > " +
                 FormatNumber(threshold_deg) + "°): the two points are replaced by their average"));
      points[i] = merged;
      points.erase(points.begin() + static_cast<std::ptrdiff_t>(i) + 1);
    } else if (!remove_spikes) {
      ++i;
      continue;
    } else {
      warnings.push_back(At(source, points[i].line,
                            "spike: the profile turns back by " +
                                Format("%.1f", turn * 180.0 / kPi) + "° > " +
                                FormatNumber(threshold_deg) + "° at line " +
                                std::to_string(points[i].line) + "; the point is deleted"));
      points.erase(points.begin() + static_cast<std::ptrdiff_t>(i));
    }
    // The neighbours' turns changed; look at them again.
    i = i > 1 ? i - 1 : 1;
  }
}

double Cross(double ay, double az, double by, double bz) { return ay * bz - az * by; }

/// Whether segments (a, b) and (c, d) share a point; if so `where` gets one such point and
/// `t_ab`, `t_cd` its fractions along both segments.
bool SegmentsIntersect(const Point& a, const Point& b, const Point& c, const Point& d, Point& where,
                       double& t_ab, double& t_cd) {
  if (std::max(a.y, b.y) < std::min(c.y, d.y) || std::max(c.y, d.y) < std::min(a.y, b.y) ||
      std::max(a.z, b.z) < std::min(c.z, d.z) || std::max(c.z, d.z) < std::min(a.z, b.z)) {
    return false;
  }
  const double ry = b.y - a.y, rz = b.z - a.z;
  const double sy = d.y - c.y, sz = d.z - c.z;
  const double qy = c.y - a.y, qz = c.z - a.z;
  const double denominator = Cross(ry, rz, sy, sz);
  if (denominator == 0.0) {
    // Parallel: they meet only if collinear and overlapping.
    if (Cross(qy, qz, ry, rz) != 0.0) return false;
    const double rr = ry * ry + rz * rz;
    const double t0 = (qy * ry + qz * rz) / rr;
    const double t1 = t0 + (sy * ry + sz * rz) / rr;
    const double lo = std::max(0.0, std::min(t0, t1));
    const double hi = std::min(1.0, std::max(t0, t1));
    if (lo > hi) return false;
    t_ab = lo;
    where = Point{a.y + lo * ry, a.z + lo * rz, a.line};
    t_cd = (t1 == t0) ? 0.0 : (lo - t0) / (t1 - t0);
    return true;
  }
  t_ab = Cross(qy, qz, sy, sz) / denominator;
  t_cd = Cross(qy, qz, ry, rz) / denominator;
  // Written so that NaN (from coordinates whose products overflow) means no crossing.
  if (!(t_ab >= 0.0 && t_ab <= 1.0 && t_cd >= 0.0 && t_cd <= 1.0)) return false;
  where = Point{a.y + t_ab * ry, a.z + t_ab * rz, a.line};
  return true;
}

/// Finds self-crossings; cuts out short loops, throws for long ones.
// Whether any two non-adjacent segments meet: a sweep over the segments in order of their
// lowest y, comparing each only with those whose y range overlaps its own. A profile runs
// mostly in one direction of y, so that is a few neighbours each, O(n log n) instead of the
// O(n²) of all pairs (2-5 million instructions for a measured profile, a tenth of a solve's
// start-up).
bool AnyCrossing(const std::vector<Point>& points) {
  const std::size_t segments = points.size() < 2 ? 0 : points.size() - 1;
  std::vector<std::size_t> order(segments);
  for (std::size_t i = 0; i < segments; ++i) order[i] = i;
  auto low = [&](std::size_t i) { return std::min(points[i].y, points[i + 1].y); };
  auto high = [&](std::size_t i) { return std::max(points[i].y, points[i + 1].y); };
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return low(a) < low(b); });
  for (std::size_t a = 0; a < segments; ++a) {
    const std::size_t i = order[a];
    for (std::size_t b = a + 1; b < segments && low(order[b]) <= high(i); ++b) {
      const std::size_t j = order[b];
      if (j + 1 == i || i + 1 == j) continue;  // neighbours share a point
      Point where{};
      double t_i = 0.0, t_j = 0.0;
      if (SegmentsIntersect(points[i], points[i + 1], points[j], points[j + 1], where, t_i, t_j)) {
        return true;
      }
    }
  }
  return false;
}

void RemoveLoops(std::vector<Point>& points, const std::string& source,
                 std::vector<std::string>& warnings) {
  // The pairwise search below finds the first crossing in profile order, which decides which
  // loop is cut; it only runs when there is a crossing at all (rarely: most profiles have none).
  if (!AnyCrossing(points)) return;
  bool changed = true;
  while (changed) {
    changed = false;
    const std::size_t n = points.size();
    for (std::size_t i = 0; i + 1 < n && !changed; ++i) {
      for (std::size_t j = i + 2; j + 1 < n && !changed; ++j) {
        Point crossing{};
        double t_i = 0.0;
        double t_j = 0.0;
        if (!SegmentsIntersect(points[i], points[i + 1], points[j], points[j + 1], crossing, t_i,
                               t_j)) {
          continue;
        }
        // The loop runs from the crossing over points i+1 .. j back to the crossing.
        double loop = Distance(crossing, points[i + 1]) + Distance(points[j], crossing);
        for (std::size_t k = i + 1; k < j; ++k) loop += Distance(points[k], points[k + 1]);
        const std::string where = "segment from line " + std::to_string(points[i].line) + " to " +
                                  std::to_string(points[i + 1].line) +
                                  " crosses segment from line " + std::to_string(points[j].line) +
                                  " to " + std::to_string(points[j + 1].line);
        if (!(loop <= kMaxRepairableLoop)) {  // NaN too: never "repair" an unmeasurable loop.
          throw InputError(At(source, points[i].line,
                              "the profile crosses itself (" + where + ", a loop of " +
                                  Format("%.3g", loop) +
                                  " mm); loops longer than 2 mm are not repaired"));
        }
        warnings.push_back(At(source, points[i + 1].line,
                              "loop removed: " + where + "; the " + std::to_string(j - i) +
                                  " point(s) of the " + Format("%.3g", loop) +
                                  " mm loop are replaced by the crossing point"));
        crossing.line = points[i + 1].line;
        points[i + 1] = crossing;
        points.erase(points.begin() + static_cast<std::ptrdiff_t>(i) + 2,
                     points.begin() + static_cast<std::ptrdiff_t>(j) + 1);
        changed = true;
      }
    }
  }
}

void RequireEnoughPoints(const std::vector<Point>& points, const std::string& source, int last_line,
                         const std::string& when) {
  if (points.size() >= kMinPoints) return;
  throw InputError(At(source, last_line,
                      "only " + std::to_string(points.size()) + " profile point(s)" + when +
                          "; a profile needs at least " + std::to_string(kMinPoints)));
}

// The options a repair reads, checked before any point is looked at.
void ValidateRepairOptions(const ProfileOptions& options, const std::string& source) {
  if (!(options.zigzag_threshold_deg > 45.0 && options.zigzag_threshold_deg <= 180.0)) {
    throw InputError(source + ": zig-zag threshold " + FormatNumber(options.zigzag_threshold_deg) +
                     "° outside (45°, 180°]");
  }
  if (!(options.smoothing >= 0.0) || !std::isfinite(options.smoothing)) {
    throw InputError(source + ": smoothing " + FormatNumber(options.smoothing) +
                     " must be a finite number >= 0");
  }
  // NaN fails every comparison below, so it is refused too.
  if (!(options.kink_high_rad > 0.0)) {
    throw InputError(source + ": kink_high_rad " + FormatNumber(options.kink_high_rad) +
                     " must be > 0 (>= pi disables kink detection)");
  }
  if (std::isnan(options.kink_low_rad)) {
    throw InputError(source + ": kink_low_rad is not a number (negative means kink_high_rad/5)");
  }
  if (!(options.kink_width >= 0.0) || !std::isfinite(options.kink_width)) {
    throw InputError(source + ": kink_width " + FormatNumber(options.kink_width) +
                     " mm must be a finite number >= 0");
  }
  if (!(options.scale_yz > 0.0) || !std::isfinite(options.scale_yz)) {
    throw InputError(source + ": scale_yz " + FormatNumber(options.scale_yz) +
                     " must be a finite number > 0");
  }
}

// The input's points, each with its line, refused where a coordinate is not finite.
std::vector<Point> FinitePoints(const ProfilePoints& input) {
  if (input.y.size() != input.z.size() || input.y.size() != input.lines.size()) {
    throw InputError(input.source + ": y, z and line arrays differ in size");
  }
  std::vector<Point> points(input.y.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i] = Point{input.y[i], input.z[i], input.lines[i]};
    if (!std::isfinite(points[i].y) || !std::isfinite(points[i].z)) {
      throw InputError(At(input.source, points[i].line, "coordinate is not a finite number"));
    }
  }
  return points;
}

// Units and mirroring: z first, since judging the lateral side needs z the right way up.
void ScaleAndOrient(std::vector<Point>& points, ProfileKind kind, const ProfileOptions& options,
                    const std::string& source, Profile& profile) {
  if (options.scale_yz != 1.0) {
    for (Point& p : points) {
      p.y *= options.scale_yz;
      p.z *= options.scale_yz;
    }
  }
  if (options.mirror_y && !options.detect_mirror_y) {
    for (Point& p : points) p.y = -p.y;
    profile.mirrored_y = !profile.mirrored_y;
  }
  bool flip_z = options.mirror_z == MirrorZ::kYes;
  if (options.mirror_z == MirrorZ::kAuto) {
    flip_z = AutoMirrorZ(points, kind, source, options.report_orientation, profile.warnings);
  }
  if (flip_z) {
    for (Point& p : points) p.z = -p.z;
    profile.mirrored_z = !profile.mirrored_z;
  }
  if (options.mirror_z != MirrorZ::kAuto) CheckZOrientation(points, kind, flip_z, source, profile);
  // Upside down, the rail's deep side and the wheel's flange are not what they seem: the
  // lateral judgement would name the wrong key.
  if (profile.orientation_doubts.empty()) {
    OrientLaterally(points, kind, options, source, profile, profile.warnings);
  }
}

// Rails run with y ascending, wheels with y descending (material on the right-hand side).
// Judged from the end points, which also works for overhanging parts.
void OrderPoints(std::vector<Point>& points, ProfileKind kind, const std::string& source,
                 Profile& profile) {
  const bool ascending = points.back().y > points.front().y;
  if (points.back().y == points.front().y) {
    profile.warnings.push_back(source +
                               ": both ends of the profile have the same y; point order kept");
  } else if (ascending != (kind == ProfileKind::kRail)) {
    std::reverse(points.begin(), points.end());
    profile.reversed = true;
  }
}

// Repeated points, zig-zags, spikes and loops, each repair followed by the duplicates it may
// leave (averaging, or a crossing point that coincides with its neighbour).
void RemoveDefects(std::vector<Point>& points, const ProfileOptions& options,
                   const std::string& source, int last_line, std::vector<std::string>& warnings) {
  RemoveZigZags(points, options.zigzag_threshold_deg, options.remove_spikes, source, warnings);
  RemoveDuplicates(points, source, warnings);
  RequireEnoughPoints(points, source, last_line, " after removing zig-zags");
  RemoveLoops(points, source, warnings);
  RemoveDuplicates(points, source, warnings);
  RequireEnoughPoints(points, source, last_line, " after removing loops");
}

void StorePoints(const std::vector<Point>& points, Profile& profile) {
  profile.y.reserve(points.size());
  profile.z.reserve(points.size());
  profile.lines.reserve(points.size());
  for (const Point& p : points) {
    profile.y.push_back(p.y);
    profile.z.push_back(p.z);
    profile.lines.push_back(p.line);
  }
}

}  // namespace

double Profile::PolylineLength() const {
  double length = 0.0;
  for (std::size_t i = 1; i < y.size(); ++i) length += std::hypot(y[i] - y[i - 1], z[i] - z[i - 1]);
  return length;
}

Profile RepairProfile(ProfilePoints input, ProfileKind kind, const ProfileOptions& options) {
  const std::string& source = input.source;
  ValidateRepairOptions(options, source);
  std::vector<Point> points = FinitePoints(input);
  Profile profile;
  profile.kind = kind;
  profile.format = input.format;
  profile.source = source;
  profile.mirrored_y = input.mirrored_y;
  profile.mirrored_z = input.mirrored_z;
  profile.warnings = std::move(input.warnings);
  const int last_line = input.lines.empty() ? 1 : input.lines.back();
  RequireEnoughPoints(points, source, last_line, "");

  ScaleAndOrient(points, kind, options, source, profile);
  // A zero-length segment has no direction: repeated points go before anything is judged.
  RemoveDuplicates(points, source, profile.warnings);
  RequireEnoughPoints(points, source, last_line, " after removing duplicates");
  OrderPoints(points, kind, source, profile);
  RemoveDefects(points, options, source, last_line, profile.warnings);
  const double length = Length(points);
  if (!(length >= kMinProfileLength && length <= kMaxProfileLength)) {  // NaN fails too.
    throw InputError(LengthProblem(source, length));
  }
  StorePoints(points, profile);
  // Kinks, found on the repaired points before smoothing could round them; then smoothing,
  // part by part so that the kinks stay sharp.
  profile.kinks = profile_detail::FindKinks(profile.y, profile.z, options);
  if (options.smoothing > 0.0) {
    profile_detail::SmoothPointsBetweenKinks(profile.y, profile.z, options.smoothing,
                                             profile.kinks);
    profile.smoothed = true;
  }
  return profile;
}

Profile MakeProfile(const std::vector<double>& y, const std::vector<double>& z, ProfileKind kind,
                    const ProfileOptions& options, const std::string& name) {
  if (y.size() != z.size()) {
    throw InputError(name + ": " + std::to_string(y.size()) + " y values but " +
                     std::to_string(z.size()) + " z values");
  }
  ProfilePoints points;
  points.format = ProfileFormat::kTable;
  points.source = name;
  points.y = y;
  points.z = z;
  points.lines.resize(y.size());
  for (std::size_t i = 0; i < y.size(); ++i) points.lines[i] = static_cast<int>(i) + 1;
  return RepairProfile(std::move(points), kind, options);
}

}  // namespace wrc
