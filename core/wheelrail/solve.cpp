#include <chrono>
#include <cmath>
#include <memory>

#include "core/gsl/roots.h"
#include "core/wheelrail/contact_search.h"
#include "core/wheelrail/geometry.h"
#include "core/wheelrail/patch.h"
#include "wrc/errors.h"
#include "wrc/wheelrail.h"

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

void Validate(const Case& c) {
  if (c.type != CaseType::kWheelRail) throw InputError("not a wheel-rail case");
  const WheelsetState& st = c.state;
  for (double v : {st.y, st.roll, st.yaw, st.velocity, st.omega, st.vy, st.vroll, st.vyaw}) {
    if (!std::isfinite(v)) throw InputError(c.source_name + ": [state] holds a non-finite value");
  }
  if (c.effects.tangential && !(st.velocity > 0.0)) {
    throw InputError(c.source_name + ": state.velocity = " + std::to_string(st.velocity) +
                     ": steady rolling needs a positive forward velocity");
  }
  if (std::fabs(st.roll) > 0.2 || std::fabs(st.yaw) > 0.2) {
    throw InputError(c.source_name + ": roll/yaw of more than 0.2 rad is outside the range " +
                     "of wheelset-on-track contact");
  }
}

struct Problem {
  const Case* c = nullptr;
  const WheelRailOptions* options = nullptr;
  std::unique_ptr<PlacedRail> rail;
  std::shared_ptr<const ProfileSpline> wheel_spline;
  WheelsetKinematics kin;  // right-side equivalent
  ContactSearch search;    // at kin.z = 0
  CombinedElasticity material;
  double mirror = 1.0;  // −1 for a left case solved as its mirror image
};

// Solves the patches at wheelset height z (right-side equivalent).
WheelRailResult SolveAt(const Problem& pb, double z) {
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
  ctx.options = pb.options;

  WheelRailResult result;
  result.z = z;
  const auto extents = wr::FindPatches(pb.search, z, pb.c->method.combine_distance);
  const Eigen::Vector3d rail_origin(0.0, pb.rail->origin()(0), pb.rail->origin()(1));
  for (const PatchExtent& e : extents) {
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
    for (double& v : p.curve_y) v = -v;
    for (double& v : p.curve_angle) v = -v;
  }
}

}  // namespace

WheelRailResult SolveWheelRail(const Case& c, const WheelRailOptions& options) {
  Validate(c);
  Problem pb;
  pb.c = &c;
  pb.options = &options;
  pb.material = CombinedElasticity::FromBodies(c.rail_material, c.wheel_material);
  ProfileOptions rail_options, wheel_options;
  rail_options.mirror_y = c.rail.mirror_y;
  wheel_options.mirror_y = c.wheel.mirror_y;
  pb.rail = std::make_unique<PlacedRail>(
      ReadProfile(c.rail.path.string(), ProfileKind::kRail, rail_options), c.track);
  pb.wheel_spline = std::make_shared<const ProfileSpline>(
      ReadProfile(c.wheel.path.string(), ProfileKind::kWheel, wheel_options));

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
  {
    const PlacedWheel wheel0(pb.wheel_spline, c.wheelset, pb.kin);
    pb.search = wr::SearchContact(*pb.rail, wheel0, kSearchStep);
  }
  bool any_valid = false;
  double first_contact = 1e300;  // wheelset z at which the surfaces first touch
  for (const auto& s : pb.search.samples) {
    if (!s.valid) continue;
    any_valid = true;
    first_contact = std::min(first_contact, s.gap);
  }
  if (!any_valid) {
    throw InputError(c.source_name + ": at y = " + std::to_string(st.y) +
                     " mm the wheel profile lies nowhere above the rail profile");
  }

  WheelRailResult result;
  int iterations = 0;
  if (st.z) {
    result = SolveAt(pb, *st.z);
  } else {
    // Prescribed vertical force FZ(TR) on the rail: find z with Brent's method between the
    // height of first contact (force 0) and a height that overshoots, found by doubling. The
    // best solution seen is kept, so the answer needs no extra solve.
    const double fz = *st.fz;
    double best_error = 1e300;
    auto residual = [&](double z) {
      ++iterations;
      WheelRailResult r = SolveAt(pb, z);
      const double f = r.force_T(2) - fz;
      if (std::fabs(f) < best_error) {
        best_error = std::fabs(f);
        result = std::move(r);
      }
      return f;
    };
    double lo = first_contact, hi = first_contact + 0.01;
    double f_lo = -fz;
    double f_hi = residual(hi);
    for (int k = 0; k < 40 && f_hi < 0.0; ++k) {
      lo = hi;
      f_lo = f_hi;
      hi = first_contact + 2.0 * (hi - first_contact);
      f_hi = residual(hi);
    }
    if (f_hi < 0.0) {
      throw InputError(c.source_name + ": state.fz = " + std::to_string(fz) +
                       " N cannot be reached within 10 m of wheelset travel");
    }
    if (best_error > options.fz_tolerance * fz) {
      // F(z) is convex (Hertz: F ∝ δ^1.5), so the secant stiffness over the bracket is below
      // the stiffness at the root and this z tolerance meets the force tolerance.
      const double stiffness = (f_hi - f_lo) / (hi - lo);
      gsl::RootOptions ro;
      ro.abs_tolerance = options.fz_tolerance * fz / stiffness;
      ro.rel_tolerance = 0.0;
      ro.max_iterations = options.max_fz_iterations;
      gsl::FindRootBrent(residual, lo, hi, ro);
    }
    if (best_error > 10.0 * options.fz_tolerance * fz) {
      result.status = SolverStatus::kNotConverged;
      result.message = "vertical force iteration did not meet state.fz = " + std::to_string(fz);
    }
  }
  result.fz_iterations = iterations;
  result.y = st.y;
  result.roll = st.roll;
  result.yaw = st.yaw;
  result.omega = st.omega;
  if (pb.mirror < 0.0) MirrorResult(result);
  return result;
}

}  // namespace wrc
