#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "core/wheelrail/contact_search.h"
#include "core/wheelrail/fz_iteration.h"
#include "core/wheelrail/geometry.h"
#include "core/wheelrail/patch.h"
#include "wrc/core/errors.h"
#include "wrc/core/hertz.h"
#include "wrc/core/wheelrail.h"

namespace wrc {
namespace {

using wr::ContactSearch;
using wr::PatchExtent;
using wr::PlacedRail;
using wr::PlacedWheel;
using wr::WheelsetKinematics;

// Arc-length step of the contact search along the rail. The weighted reference and the patch
// extents are integrals over these samples; 0.05 mm keeps their error far below the element
// sizes (>= 0.1 mm) at a cost of a few thousand wheel evaluations.
constexpr double kSearchStep = 0.05;
// The first contact search of a prescribed-fz solve covers wheelset heights up to this far
// below first contact, mm: tread contact approaches are 0.01-0.2 mm and flange contacts up to
// ~70° stay within 1 mm vertically (every reference case does). A deeper z of the iteration
// (at 76° the vertical interpenetration is four times the normal one) searches again, further
// (CoverHeight).
constexpr double kInitialReach = 1.0;

void Validate(const Case& c) {
  if (c.type != CaseType::kWheelRail) throw InputError("not a wheel-rail case");
  const WheelsetState& st = c.state;
  for (double v : {st.y, st.roll, st.yaw, st.velocity, st.omega, st.vy, st.vroll, st.vyaw}) {
    if (!std::isfinite(v)) throw InputError(c.source_name + ": [state] holds a non-finite value");
  }
  if (c.effects.tangential && !(st.velocity > 0.0)) {
    throw InputError(c.source_name + ": state.velocity = " + FormatNumber(st.velocity) +
                     ": steady rolling needs a positive forward velocity");
  }
  // Beyond 0.1 rad the wheelset is no longer on the track (a roll of 0.1 rad lifts a wheel by
  // some 75 mm, twice a flange's height; yaw in the tightest curves stays under 0.03 rad): the
  // contact search along the rail profile and the planar/curved references assume a wheel
  // standing on the rail, and fail there with messages about other inputs.
  for (const auto& [key, value] : {std::pair<const char*, double>{"state.roll", st.roll},
                                   std::pair<const char*, double>{"state.yaw", st.yaw}}) {
    if (std::fabs(value) > 0.1) {
      throw InputError(c.source_name + ": " + key + " = " + FormatNumber(value) +
                       ": more than 0.1 rad is outside the range of wheelset-on-track contact");
    }
  }
}

struct Problem {
  const Case* c = nullptr;
  const WheelRailOptions* options = nullptr;
  std::shared_ptr<const ProfileSpline> rail_spline;
  std::unique_ptr<PlacedRail> rail;
  std::shared_ptr<const ProfileSpline> wheel_spline;
  WheelsetKinematics kin;  // right-side equivalent
  ContactSearch search;    // at kin.z = 0
  double reach = 0.0;      // the search covers z up to first contact + reach
  CombinedElasticity material;
  double mirror = 1.0;  // −1 for a left case solved as its mirror image
  // Per patch, keyed by the rail arc length at the middle of its extent: operators and warm
  // starts for the next solve of the same patch at another wheelset height.
  mutable std::vector<std::pair<double, std::unique_ptr<wr::PatchCache>>> caches;

  // The nearest cache not yet taken by another patch of this solve (`taken` has one flag per
  // cache), or a new one.
  wr::PatchCache* CacheFor(const PatchExtent& e, std::vector<bool>& taken) const {
    // A patch moves by far less than this along the rail between the steps of an fz iteration.
    constexpr double kSameArcLength = 5.0;
    const double key = 0.5 * (search.samples[e.first].s + search.samples[e.last].s);
    int best = -1;
    for (std::size_t k = 0; k < caches.size(); ++k) {
      const double d = std::fabs(caches[k].first - key);
      if (!taken[k] && d < kSameArcLength &&
          (best < 0 || d < std::fabs(caches[best].first - key))) {
        best = static_cast<int>(k);
      }
    }
    if (best < 0) {
      caches.emplace_back(key, std::make_unique<wr::PatchCache>());
      taken.push_back(false);
      best = static_cast<int>(caches.size()) - 1;
    }
    taken[best] = true;
    caches[best].first = key;
    return caches[best].second.get();
  }
};

// A first wheelset height for the vertical force iteration from Hertz theory at the deepest
// point of the contact locus: its curvatures along x (the wheel's, from the search) and along
// the rail (the second difference of the gap over ±0.2 mm), projected on the surface normal
// there; the normal force that carries fz, and the vertical shift that gives its approach.
// Within 1-15 % of the final approach on the Manchester cases (the old guess, 0.01 mm into
// contact, carried 5-30 % of the load): the first normal solve is then on a box of about the
// final size, so its FFT plan and kernels serve the whole iteration. NaN where Hertz does not
// apply (conformal contact: no lateral curvature).
double HertzGuess(const Problem& pb, double fz, double first_contact) {
  const auto& samples = pb.search.samples;
  int deepest = -1;
  for (int k = 0; k < static_cast<int>(samples.size()); ++k) {
    if (samples[k].valid && (deepest < 0 || samples[k].gap < samples[deepest].gap)) deepest = k;
  }
  constexpr int kSpan = 4;  // samples either side: 0.2 mm
  if (deepest < kSpan || deepest + kSpan >= static_cast<int>(samples.size())) return NAN;
  const wr::LocusSample& before = samples[deepest - kSpan];
  const wr::LocusSample& at = samples[deepest];
  const wr::LocusSample& after = samples[deepest + kSpan];
  if (!before.valid || !after.valid) return NAN;
  const double ds = 0.5 * (after.s - before.s);
  const double gap_curvature = (after.gap - 2.0 * at.gap + before.gap) / (ds * ds);
  const double cos_a = std::cos(at.alpha);
  const double a1 = 0.5 * cos_a * at.curvature, b1 = 0.5 * cos_a * gap_curvature;
  if (!(cos_a > 0.1 && a1 > 0.0 && b1 > 0.0 && b1 < 1e4 * a1 && a1 < 1e4 * b1)) return NAN;
  const HertzContact hertz(a1, b1, pb.material.EffectiveModulus());
  // Kept within half the first search's reach: a deeper guess (steep flanges, where cos_a is
  // small and the Hertz curvatures least reliable) would search again and solve a first
  // patch larger than the final one, where the secant from a shallower start costs less.
  const double sink = hertz.ApproachForForce(fz / cos_a) / cos_a;
  return first_contact + std::min(sink, 0.5 * kInitialReach);
}

}  // namespace

// The inputs of a contact search or a placement check, compared exactly. The profiles are held,
// not only pointed to, so that an address cannot be reused by another profile while cached.
struct PoseKey {
  std::shared_ptr<const ProfileSpline> rail, wheel;
  Track track;
  Wheelset wheelset;
  double y = 0.0, roll = 0.0, yaw = 0.0, reach = 0.0, z_limit = 0.0;
  bool operator==(const PoseKey& o) const {
    return rail == o.rail && wheel == o.wheel && track.gauge_height == o.track.gauge_height &&
           track.gauge_width == o.track.gauge_width && track.cant == o.track.cant &&
           track.rail_y == o.track.rail_y && track.rail_z == o.track.rail_z &&
           wheelset.side == o.wheelset.side &&
           wheelset.flange_back_distance == o.wheelset.flange_back_distance &&
           wheelset.flange_back_position == o.wheelset.flange_back_position &&
           wheelset.nominal_radius == o.wheelset.nominal_radius && y == o.y && roll == o.roll &&
           yaw == o.yaw && reach == o.reach && z_limit == o.z_limit;
  }
};

struct WheelRailCache::Impl {
  // The searches of the last pose: the first one and the deeper ones an fz iteration adds.
  static constexpr std::size_t kSearches = 4;
  std::vector<std::pair<PoseKey, wr::ContactSearch>> searches;
  // AddPlacementWarning's, one per pair and placement (a few at most).
  static constexpr std::size_t kNominalContacts = 8;
  std::vector<std::pair<PoseKey, double>> nominal_contacts;
};

WheelRailCache::WheelRailCache() : impl_(std::make_unique<Impl>()) {}
WheelRailCache::~WheelRailCache() = default;

namespace {

PoseKey KeyOf(const Problem& pb, const WheelsetKinematics& kin, double reach, double z_limit) {
  return PoseKey{pb.rail_spline, pb.wheel_spline, pb.c->track, pb.c->wheelset, kin.y,
                 kin.roll,       kin.yaw,         reach,       z_limit};
}

// The contact search at z = 0 with its samples located wherever the gap comes within `reach`
// of first contact (and below z_limit, when z is prescribed); from the cache when it holds
// the same search.
void Search(Problem& pb, double reach, double z_limit) {
  pb.reach = reach;
  WheelRailCache* cache = pb.options->cache;
  if (cache == nullptr) {
    const PlacedWheel wheel0(pb.wheel_spline, pb.c->wheelset, pb.kin);
    pb.search = wr::SearchContact(*pb.rail, wheel0, kSearchStep, reach, z_limit);
    return;
  }
  auto& searches = cache->impl().searches;
  PoseKey key = KeyOf(pb, pb.kin, reach, z_limit);
  for (const auto& [stored, search] : searches) {
    if (stored == key) {
      pb.search = search;
      return;
    }
  }
  const PlacedWheel wheel0(pb.wheel_spline, pb.c->wheelset, pb.kin);
  pb.search = wr::SearchContact(*pb.rail, wheel0, kSearchStep, reach, z_limit);
  // Another pose: the searches of the last one are of no more use.
  if (!searches.empty() &&
      (searches.front().first.y != key.y || searches.front().first.roll != key.roll ||
       searches.front().first.yaw != key.yaw)) {
    searches.clear();
  }
  if (searches.size() == WheelRailCache::Impl::kSearches) searches.erase(searches.begin());
  searches.emplace_back(std::move(key), pb.search);
}

// Wheelset height z below the heights the search covers: searches again with a reach that
// covers it with a margin. Samples that do not interpenetrate at z enter no patch, so the
// results at the heights already solved are the same with either search.
void CoverHeight(Problem& pb, double z, double first_contact) {
  if (z - first_contact < pb.reach) return;
  // Sunk deeper than the wheel's radius, the wheel has passed through the rail: no contact
  // geometry exists there (it would not even be finite), so the height cannot be solved, as
  // one whose patch is too large. Only a far-off start of the fz iteration comes here.
  const double radius = pb.c->wheelset.nominal_radius;
  if (!(z - first_contact <= radius)) {
    throw InputError(pb.c->source_name + ": at wheelset z = " + FormatNumber(z) +
                     " mm the wheel would sink more than its radius (" + FormatNumber(radius) +
                     " mm) into the rail");
  }
  // Half as far again: the secant steps of the iteration that follow stay inside.
  Search(pb, std::max(2.0 * pb.reach, 1.5 * (z - first_contact)),
         std::numeric_limits<double>::infinity());
}

// `value` with `decimals` digits after the point, for messages.
std::string Fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

// Whether the half-space influence coefficients fit the patch (paper §2.4, §3.3: they take
// each body as a half-space, flat across the contact). With a the half-size of the contact
// and R a radius of curvature of the surface there, the surfaces turn by about 2a/R across
// it. Hertz theory, and with it the half-space approximation, asks for a ≪ R (Johnson,
// Contact Mechanics §4.1); a/R = 0.1 is taken here as the edge of "small", the order of the
// relative error the flat-body influence coefficients then make. So a region across which
// the rail turns by more than 0.2 rad, or whose length along x exceeds 0.1 of the wheel's
// radius there, is solved but flagged: the elastic part is a coarse approximation there.
void AddHalfSpaceWarnings(const Problem& pb, double z, WheelRailResult& result) {
  constexpr double kMaxSizeOverRadius = 0.1;
  const auto& samples = pb.search.samples;
  const int n = static_cast<int>(samples.size());
  for (int k = 0; k < n;) {
    if (wr::LocusHalfLength(samples[k], z) == 0.0) {
      ++k;
      continue;
    }
    double alpha_min = samples[k].alpha, alpha_max = samples[k].alpha, size_over_radius = 0.0;
    const double y_first = samples[k].y;
    for (; k < n && wr::LocusHalfLength(samples[k], z) > 0.0; ++k) {
      alpha_min = std::min(alpha_min, samples[k].alpha);
      alpha_max = std::max(alpha_max, samples[k].alpha);
      size_over_radius =
          std::max(size_over_radius, wr::LocusHalfLength(samples[k], z) * samples[k].curvature);
    }
    const std::string where = "the interpenetration at y = " + Fixed(pb.mirror * y_first, 2) +
                              " to " + Fixed(pb.mirror * samples[k - 1].y, 2) + " mm (track frame)";
    if (alpha_max - alpha_min > 2.0 * kMaxSizeOverRadius) {
      result.warnings.push_back(where + ": the rail turns by " + Fixed(alpha_max - alpha_min, 3) +
                                " rad across it (more than 0.2 rad): the half-space "
                                "influence coefficients take it as flat");
    }
    if (size_over_radius > kMaxSizeOverRadius) {
      result.warnings.push_back(where + ": its half-length along the track is " +
                                Fixed(size_over_radius, 3) +
                                " of the wheel radius (more than 0.1): the half-space "
                                "influence coefficients take the wheel as flat");
    }
  }
}

// Where the interpenetration reaches an end of the rail profile, or a rail point above which
// the wheel profile has ended (the flange tip, the field-side chamfer), the contact would
// continue on surface that the profiles do not describe: the result is that of the bodies cut
// off there, and says so. Not an error: the geometry inside is exact,
// and test geometries (a ball in a conforming groove) are in contact across their whole width.
void AddTruncationWarnings(const Problem& pb, double z, WheelRailResult& result) {
  const auto& samples = pb.search.samples;
  const int n = static_cast<int>(samples.size());
  for (int k = 0; k < n; ++k) {
    if (!samples[k].valid || samples[k].gap >= z) continue;
    const bool rail_end = k == 0 || k == n - 1;
    const bool wheel_end = !rail_end && (samples[k - 1].off_wheel || samples[k + 1].off_wheel);
    if (!rail_end && !wheel_end) continue;
    result.warnings.push_back(
        std::string("the interpenetration reaches ") +
        (rail_end ? "an end of the rail profile" : "the end of the wheel profile") +
        " at y = " + Fixed(pb.mirror * samples[k].y, 2) +
        " mm (track frame): contact beyond it, on surface the profiles do "
        "not describe, is not in the result");
  }
}

// Fewest elements across a patch, along x and along s, for a result worth trusting: with four
// the pressure's peak and edges are each resolved by about one element, and the force error is
// of the order of 10 % (the half-space solve asks the same).
constexpr int kMinElementsAcross = 4;

// What the patch's grid says about its solution: too few elements across it, or pressure on
// the outermost elements of the potential contact area (the patch was cut off by its grid).
void AddResolutionWarnings(WheelRailResult& result) {
  for (std::size_t n = 0; n < result.patches.size(); ++n) {
    const PatchResult& p = result.patches[n];
    if (p.n_contact == 0) continue;
    const std::string patch = "patch " + std::to_string(n + 1);
    if (p.contact_columns < kMinElementsAcross || p.contact_rows < kMinElementsAcross) {
      result.warnings.push_back(patch + " has only " + std::to_string(p.contact_columns) + " x " +
                                std::to_string(p.contact_rows) +
                                " elements across it (fewer than 4 along x or s): grid.dx/grid.ds "
                                "are too coarse for it");
    }
    if (p.contact_at_border) {
      result.warnings.push_back(patch +
                                " carries pressure on the border of its potential contact area: "
                                "the contact may extend beyond it, and the forces are those of a "
                                "cut-off patch");
    }
  }
}

// Bounds beyond which a result describes no wheel on a rail, only the numbers of a placement
// or load error; each is far outside what a real wheel–rail contact reaches.
//
// Peak pressure. Hertz gives pmax ∝ F^(1/3): the sharpest contact of the Manchester pair
// (flange root on gauge corner, 10 kN) has pmax ≈ 3000 N/mm², so even 250 kN (a heavy-haul
// wheel load with its dynamic part) on such radii gives about 3000·25^(1/3) ≈ 8800 N/mm².
// Steel cannot carry more: its hardness (the mean pressure of fully plastic indentation) is
// 2500–4000 N/mm² for wheel and rail steels. 1e4 N/mm² is above both.
constexpr double kMaxPlausiblePressure = 1e4;
// Interpenetration of the undeformed surfaces. Hertz gives δ ∝ F^(2/3): tread contacts of the
// Manchester pair reach 0.03 mm and its flange contact 0.05 mm at 10 kN, a worn heavy-haul pair
// 0.1 mm at 40 kN; 1 mm is (1/0.05)^1.5 ≈ 90 times the load of the sharpest of them, about
// 1 MN, four times any wheel load.
constexpr double kMaxPlausibleApproach = 1.0;
// First contact at the nominal position (y = roll = yaw = 0), mm from z = 0. z = 0 puts the
// wheel's nominal rolling circle on the track plane, so a matching pair first touches within
// the height differences of tread and rail crown across their lateral offset: 1:40 cones over
// ±30 mm give 0.75 mm, hollow-worn treads up to about 3 mm (the Manchester pair: 0.27 mm).
// 10 mm from z = 0 the wheel rests on its flange or hangs beside the rail: a profile mirrored
// the wrong way (mirror_y), a profile in other units or a wrong placement key.
constexpr double kMaxNominalContactHeight = 10.0;

void AddPressureWarnings(WheelRailResult& result) {
  for (std::size_t n = 0; n < result.patches.size(); ++n) {
    const PatchResult& p = result.patches[n];
    const std::string patch = "patch " + std::to_string(n + 1);
    if (p.pmax > kMaxPlausiblePressure) {
      result.warnings.push_back(patch + ": peak pressure " + Fixed(p.pmax, 0) +
                                " N/mm² is implausible (more than 1e4, above what steel "
                                "carries): check state.z and the profiles' placement");
    }
    if (p.approach > kMaxPlausibleApproach) {
      result.warnings.push_back(patch + ": the undeformed surfaces interpenetrate by " +
                                Fixed(p.approach, 3) +
                                " mm (more than 1 mm, far beyond any wheel load): check state.z "
                                "and the profiles' placement");
    }
  }
}

// The smallest gap of a search: the wheelset height z at which the surfaces first touch
// (+inf where the wheel lies nowhere above the rail).
double FirstContact(const ContactSearch& search) {
  double first = std::numeric_limits<double>::infinity();
  for (const auto& s : search.samples) {
    if (s.valid) first = std::min(first, s.gap);
  }
  return first;
}

// The first contact at the nominal pose `kin`, from the cache when it has it.
double NominalFirstContact(const Problem& pb, const WheelsetKinematics& kin) {
  const auto search = [&]() {
    const PlacedWheel wheel(pb.wheel_spline, pb.c->wheelset, kin);
    return FirstContact(wr::SearchContact(*pb.rail, wheel, kSearchStep, 0.0));
  };
  WheelRailCache* cache = pb.options->cache;
  if (cache == nullptr) return search();
  auto& known = cache->impl().nominal_contacts;
  PoseKey key = KeyOf(pb, kin, 0.0, std::numeric_limits<double>::infinity());
  for (const auto& [stored, first] : known) {
    if (stored == key) return first;
  }
  const double first = search();
  if (known.size() == WheelRailCache::Impl::kNominalContacts) known.erase(known.begin());
  known.emplace_back(std::move(key), first);
  return first;
}

// Whether the profiles, as placed, first touch near z = 0 at the nominal position
// (kMaxNominalContactHeight); `first_contact` is that of the case's own pose, which is the
// nominal one when y, roll and yaw are all 0 (no second search then).
void AddPlacementWarning(const Problem& pb, double first_contact, WheelRailResult& result) {
  double nominal = first_contact;
  if (pb.kin.y != 0.0 || pb.kin.roll != 0.0 || pb.kin.yaw != 0.0) {
    WheelsetKinematics kin = pb.kin;
    kin.y = kin.roll = kin.yaw = kin.z = 0.0;
    nominal = NominalFirstContact(pb, kin);
  }
  if (std::fabs(nominal) <= kMaxNominalContactHeight) return;
  const std::string where = std::isfinite(nominal)
                                ? "first touch at z = " + Fixed(nominal, 2) + " mm"
                                : "do not touch at all (the wheel lies nowhere above the rail)";
  result.warnings.push_back(
      "at the nominal position (y = roll = yaw = 0) the profiles as placed " + where +
      ", more than 10 mm from z = 0: a profile mirrored the wrong way (mirror_y), in other "
      "units, or a wrong [track]/[wheelset] placement; the result is that of this placement");
}

// Every repair made to the profiles while reading them: the result rests on the repaired
// geometry, so it says so.
void AddProfileWarnings(const Problem& pb, WheelRailResult& result) {
  for (const ProfileSpline* spline : {&pb.rail->spline(), pb.wheel_spline.get()}) {
    for (const std::string& w : spline->warnings()) result.warnings.push_back("profile: " + w);
  }
}

// Measured wheel profiles may leave out up to this much (mm) of the flange back where it meets
// the inner rim face; a larger distance between the flange back found in the profile and
// wheelset.flange_back_position is a wrong origin convention (0 for MiniProf, −70 for S1002 in
// Simpack files), which shifts the wheel by tens of millimetres.
constexpr double kFlangeBackTolerance = 5.0;

// A sentence naming the flange_back_position that fits the wheel profile, or empty when the
// given one fits (or the profile has no flange to judge by).
std::string FlangeBackHint(const ProfileSpline& wheel, const Wheelset& wheelset) {
  const std::optional<double> found = FlangeBackY(wheel);
  if (!found || std::fabs(*found - wheelset.flange_back_position) <= kFlangeBackTolerance)
    return "";
  // Within the tolerance of 0 the origin is at the flange back, as MiniProf puts it.
  const double suggested = std::fabs(*found) <= kFlangeBackTolerance ? 0.0 : std::round(*found);
  return "the flange back of wheel profile " + wheel.source() +
         " lies at y = " + FormatNumber(std::round(*found * 10.0) / 10.0) +
         " mm in the profile's coordinates, but wheelset.flange_back_position = " +
         FormatNumber(wheelset.flange_back_position) +
         " mm: set flange_back_position = " + FormatNumber(suggested) +
         " (MiniProf .whl files have their origin at the flange back, 0; Simpack S1002-type "
         "files at the tape circle line, -70)";
}

// Beyond this distance (mm) the flange back given and the one in the profile cannot both be
// meant: the wheel would stand that far beside its design position, a different wheelset.
constexpr double kFlangeBackMismatch = 25.0;

// Refuses a flange_back_position that misses the profile's flange back by more than
// kFlangeBackMismatch; returns the warning for a smaller mismatch (empty when none).
std::string CheckFlangeBack(const Case& c, const ProfileSpline& wheel) {
  const std::string hint = FlangeBackHint(wheel, c.wheelset);
  const std::optional<double> found = FlangeBackY(wheel);
  if (!hint.empty() && std::fabs(*found - c.wheelset.flange_back_position) > kFlangeBackMismatch) {
    throw InputError(c.source_name + ": " + hint);
  }
  return hint;
}

// Every key that places the wheel sideways against its rail, with its value: any of them can
// put the profiles side by side instead of one above the other.
std::string LateralPlacement(const Case& c) {
  const auto mm = [](double v) { return FormatNumber(v) + " mm"; };
  std::string text = "placed by state.y = " + mm(c.state.y);
  if (c.track.absolute_placement()) {
    text += ", track.rail_y = " + mm(c.track.rail_y) + ", track.rail_z = " + mm(c.track.rail_z);
  } else {
    text += ", track.gauge_width = " + mm(c.track.gauge_width) +
            ", track.gauge_height = " + mm(c.track.gauge_height);
  }
  return text + ", wheelset.flange_back_distance = " + mm(c.wheelset.flange_back_distance) +
         " and wheelset.flange_back_position = " + mm(c.wheelset.flange_back_position);
}

// The profiles' orientation doubts, for an error that a misoriented profile can cause.
std::string OrientationDoubts(const Problem& pb) {
  std::string doubts;
  for (const ProfileSpline* spline : {&pb.rail->spline(), pb.wheel_spline.get()}) {
    for (const std::string& doubt : spline->orientation_doubts()) doubts += "; " + doubt;
  }
  return doubts;
}

// A solution with a non-finite force or position is no solution: status not converged, with
// the reason, instead of numbers that are not numbers.
void RequireFiniteResult(WheelRailResult& result) {
  bool finite = std::isfinite(result.z);
  for (int i = 0; i < 3; ++i) finite = finite && std::isfinite(result.force_T(i));
  for (const PatchResult& p : result.patches) {
    finite = finite && std::isfinite(p.fn) && std::isfinite(p.fx) && std::isfinite(p.fs) &&
             std::isfinite(p.pmax);
  }
  if (finite) return;
  result.status = SolverStatus::kNotConverged;
  result.message =
      "the solution is not finite (forces or position overflowed): check the "
      "magnitudes of the state and creepage inputs";
  result.warnings.push_back(result.message);
}

// Solves the patches at wheelset height z (right-side equivalent); with tangential = false
// only the normal problems (for the vertical force iteration).
WheelRailResult SolveAt(const Problem& pb, double z, bool tangential, WheelRailTimings* timings,
                        double normal_tolerance = 0.0, double tangential_tolerance = 0.0) {
  WheelRailOptions options = *pb.options;
  if (normal_tolerance > 0.0) options.normal.tolerance = normal_tolerance;
  if (tangential_tolerance > 0.0) options.tangential.tolerance = tangential_tolerance;
  WheelsetKinematics kin = pb.kin;
  kin.z = z;
  const PlacedWheel wheel(pb.wheel_spline, pb.c->wheelset, kin);
  wr::PatchContext ctx;
  ctx.c = pb.c;
  ctx.rail = pb.rail.get();
  ctx.wheel = &wheel;
  ctx.search = &pb.search;
  ctx.dz = z;
  ctx.velocity = kin.velocity;
  ctx.material = pb.material;
  ctx.options = &options;
  ctx.tangential = tangential && pb.c->effects.tangential;
  ctx.timings = timings;

  WheelRailResult result;
  result.z = z;
  const auto extents = wr::FindPatches(pb.search, z, pb.c->method.combine_distance);
  const Eigen::Vector3d rail_origin(0.0, pb.rail->origin()(0), pb.rail->origin()(1));
  std::vector<bool> taken(pb.caches.size(), false);
  for (const PatchExtent& e : extents) {
    ctx.cache = pb.CacheFor(e, taken);
    PatchResult p = pb.c->method.reference == ReferenceSurface::kCurved
                        ? wr::SolveCurvedPatch(ctx, e)
                        : wr::SolvePlanarPatch(ctx, e);
    if (p.status == SolverStatus::kNoContact) continue;
    if (p.status == SolverStatus::kNotConverged) result.status = SolverStatus::kNotConverged;
    result.force_T += p.force_T;
    result.moment_T += p.moment_T + (p.reference_T - rail_origin).cross(p.force_T);
    result.patches.push_back(std::move(p));
  }
  if (result.patches.empty()) result.status = SolverStatus::kNoContact;
  result.force_W = wheel.R_TW().transpose() * result.force_T;
  return result;
}

// The location x_av of paper Eq. 25–27 where the total force acts with the smallest moment,
// shifted along F onto the rail surface (which changes neither force nor moment). With M the
// moment of the tractions about the rail origin (M = Σ r × F), the force's line of action
// passes through x_av = F × M⊥/(F·F) = F × M/(F·F); the paper writes M × F for the couple that
// compensates the shift, which has the opposite sign.
void LocateResultant(const Problem& pb, WheelRailResult& r) {
  const Eigen::Vector3d& f = r.force_T;
  if (r.patches.empty() || !(f.squaredNorm() > 0.0)) return;
  const Eigen::Vector3d origin(0.0, pb.rail->origin()(0), pb.rail->origin()(1));
  const Eigen::Vector3d x_av = origin + f.cross(r.moment_T) / f.squaredNorm();
  const Eigen::Vector2d d = f.tail<2>();
  if (!(d.norm() > 1e-9 * f.norm())) return;
  // Start from the reference of the patch that carries most of the load.
  const PatchResult* main = &r.patches[0];
  for (const PatchResult& p : r.patches) {
    if (p.fn > main->fn) main = &p;
  }
  const Eigen::Vector2d on_rail = main->reference_T.tail<2>();
  const auto s = pb.rail->IntersectLine(x_av.tail<2>(), d.normalized(),
                                        pb.rail->spline().ZAtY(pb.rail->ToRail(on_rail)(0)).s);
  if (!s) return;
  const Eigen::Vector2d p = pb.rail->PositionAt(*s);
  const double lambda = (p - x_av.tail<2>()).dot(d) / d.squaredNorm();
  r.force_location_T = x_av + lambda * f;
  r.has_force_location = true;
  r.contact_y = pb.rail->ToRail(p)(0);
  r.contact_angle = pb.rail->InclinationAt(*s);
}

// Undoes the mirroring of a left case: y components of forces and positions change sign, and
// so do the x and z components of moments (pseudo-vectors).
void MirrorResult(WheelRailResult& r) {
  auto mirror_force = [](Eigen::Vector3d& f) { f(1) = -f(1); };
  auto mirror_moment = [](Eigen::Vector3d& m) {
    m(0) = -m(0);
    m(2) = -m(2);
  };
  mirror_force(r.force_T);
  mirror_force(r.force_W);
  mirror_moment(r.moment_T);
  r.force_location_T(1) = -r.force_location_T(1);
  r.rail_origin_T(1) = -r.rail_origin_T(1);
  r.contact_y = -r.contact_y;
  r.contact_angle = -r.contact_angle;
  for (PatchResult& p : r.patches) {
    mirror_force(p.force_T);
    mirror_moment(p.moment_T);
    p.reference_T(1) = -p.reference_T(1);
    p.reference_rail(0) = -p.reference_rail(0);
    p.reference_wheel(1) = -p.reference_wheel(1);
    p.contact_angle = -p.contact_angle;
    p.fs = -p.fs;
    p.mn = -p.mn;
    p.ceta = -p.ceta;
    p.cphi = -p.cphi;
    for (double& v : p.ps) v = -v;
    for (double& v : p.ss) v = -v;
    for (double& v : p.ws) v = -v;  // the rigid part of ss, mirrored with it
    for (double& v : p.curve_y) v = -v;
    for (double& v : p.curve_angle) v = -v;
  }
}

// The contact's vertical force at wheelset heights, for the fz iteration; keeps the last result
// of each kind of solve.
class ContactVerticalForce : public wr::VerticalForce {
 public:
  ContactVerticalForce(Problem& pb, double first_contact, WheelRailTimings* timings)
      : pb_(pb), first_contact_(first_contact), timings_(timings) {}
  double Normal(double z, double tolerance) override {
    CoverHeight(pb_, z, first_contact_);
    normal = SolveAt(pb_, z, false, timings_, tolerance);
    return normal.force_T(2);
  }
  double Full(double z, double tangential_tolerance) override {
    CoverHeight(pb_, z, first_contact_);
    full = SolveAt(pb_, z, true, timings_, 0.0, tangential_tolerance);
    return full.force_T(2);
  }
  WheelRailResult normal, full;

 private:
  Problem& pb_;
  const double first_contact_;
  WheelRailTimings* timings_;
};

// Prescribed vertical force FZ(TR) on the rail: the height is found on normal-only solves (the
// tangential tractions add only a small part, fs·sin δ, to FZ(TR)), then full solves correct
// for that part (core/wheelrail/fz_iteration.h). It starts from the caller's guess or the Hertz
// estimate.
WheelRailResult SolveForPrescribedFz(Problem& pb, double first_contact, WheelRailTimings* timings,
                                     int* iterations) {
  const Case& c = *pb.c;
  const WheelRailOptions& options = *pb.options;
  const double fz = *c.state.fz;
  // A guess deeper than the wheel's radius is no start at all (CoverHeight): the cold start.
  const bool usable_guess = options.z_guess > first_contact &&
                            options.z_guess - first_contact <= c.wheelset.nominal_radius;
  double z0 = usable_guess ? options.z_guess : HertzGuess(pb, fz, first_contact);
  if (!(z0 > first_contact)) z0 = first_contact + 0.01;
  wr::FzIterationOptions iteration;
  iteration.fz_tolerance = options.fz_tolerance;
  iteration.normal_tolerance = options.normal.tolerance;
  iteration.tangential_tolerance = options.tangential.tolerance;
  iteration.max_normal_steps = options.max_fz_iterations;
  iteration.tangential = c.effects.tangential;
  ContactVerticalForce force(pb, first_contact, timings);
  const wr::FzIterationSummary s = wr::SolveForFz(force, fz, first_contact, z0, iteration);
  *iterations = s.solves;
  const std::string not_reached =
      c.source_name + ": state.fz = " + FormatNumber(fz) + " N is not reached";
  if (s.outcome == wr::FzOutcome::kNoSupport) {
    throw InputError(not_reached + ": the wheel finds no support on the rail");
  }
  if (s.outcome == wr::FzOutcome::kUnsolvable) {
    throw InputError(not_reached + " before the contact can no longer be solved (" + s.unsolvable +
                     ")");
  }
  WheelRailResult result = std::move(s.last_was_full ? force.full : force.normal);
  if (s.outcome != wr::FzOutcome::kMet) {
    result.status = SolverStatus::kNotConverged;
    result.message = "vertical force iteration did not meet state.fz = " + FormatNumber(fz);
  }
  return result;
}

}  // namespace

WheelRailResult SolveWheelRail(const Case& c, const WheelRailOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto t_start = Clock::now();
  auto since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  WheelRailTimings timings;
  Validate(c);
  Problem pb;
  pb.c = &c;
  pb.options = &options;
  pb.material = CombinedElasticity::FromBodies(c.rail_material, c.wheel_material);
  // Profiles already read by LoadCase / LoadScene are shared; a case built in code is read here.
  pb.rail_spline = SplineOf(c.rail, ProfileKind::kRail);
  pb.rail = std::make_unique<PlacedRail>(pb.rail_spline, c.track);
  pb.wheel_spline = SplineOf(c.wheel, ProfileKind::kWheel);

  const std::string flange_back_hint = CheckFlangeBack(c, *pb.wheel_spline);

  // A left case is solved as the mirror image of a right one (CONTACT does the same).
  pb.mirror = c.wheelset.side == WheelSide::kLeft ? -1.0 : 1.0;
  const WheelsetState& st = c.state;
  pb.kin.y = pb.mirror * st.y;
  pb.kin.roll = pb.mirror * st.roll;
  pb.kin.yaw = pb.mirror * st.yaw;
  pb.kin.velocity = st.velocity;
  pb.kin.omega = st.omega;
  pb.kin.vy = pb.mirror * st.vy;
  pb.kin.vroll = pb.mirror * st.vroll;
  pb.kin.vyaw = pb.mirror * st.vyaw;
  pb.kin.z = 0.0;
  timings.profiles = since(t_start);
  {
    const auto t_search = Clock::now();
    // With z prescribed only samples that interpenetrate at that z matter.
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    if (st.z) {
      Search(pb, kInfinity, *st.z);
    } else {
      Search(pb, kInitialReach, kInfinity);
    }
    timings.search = since(t_search);
  }
  const double first_contact = FirstContact(pb.search);  // wheelset z of first touch
  if (!std::isfinite(first_contact)) {
    throw InputError(
        c.source_name + ": the wheel profile lies nowhere above the rail profile, as " +
        LateralPlacement(c) + (flange_back_hint.empty() ? "" : "; " + flange_back_hint) +
        OrientationDoubts(pb));
  }

  WheelRailResult result;
  int iterations = 0;
  if (st.z) {
    result = SolveAt(pb, *st.z, true, &timings);
  } else {
    result = SolveForPrescribedFz(pb, first_contact, &timings, &iterations);
  }
  result.rail_origin_T = {0.0, pb.rail->origin()(0), pb.rail->origin()(1)};
  AddProfileWarnings(pb, result);
  if (!flange_back_hint.empty()) result.warnings.push_back("placement: " + flange_back_hint);
  RequireFiniteResult(result);
  if (!result.patches.empty()) {
    AddTruncationWarnings(pb, result.z, result);
    AddHalfSpaceWarnings(pb, result.z, result);
    AddResolutionWarnings(result);
    AddPressureWarnings(result);
  }
  AddPlacementWarning(pb, first_contact, result);
  LocateResultant(pb, result);
  result.fz_iterations = iterations;
  timings.total = since(t_start);
  timings.geometry = std::max(0.0, timings.total - timings.profiles - timings.search -
                                       timings.influence - timings.normal - timings.tangential);
  result.timings = timings;
  result.y = st.y;
  result.roll = st.roll;
  result.yaw = st.yaw;
  result.omega = st.omega;
  result.velocity = st.velocity;
  for (PatchResult& patch : result.patches) {
    patch.fi_surf_rail = SurfaceFatigueIndex(patch, c.rail_material.shear_yield);
    patch.fi_surf_wheel = SurfaceFatigueIndex(patch, c.wheel_material.shear_yield);
  }
  if (pb.mirror < 0.0) MirrorResult(result);
  return result;
}

}  // namespace wrc
