// The curved reference surface of the paper (§3.2–3.7).

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/wheelrail/patch.h"
#include "core/wheelrail/patch_common.h"

namespace wrc::wr {
namespace {

// Track-frame point of the wheel surface at profile arc length s_w that lies in the plane
// x = x_target (paper §3.3): the wheel particle found there is not in the principal profile
// (x_w = 0) when the wheelset yaws, so its x in wheelset coordinates is corrected by the
// mismatch until it lands in the plane.
std::optional<Eigen::Vector3d> WheelPointInPlane(const PlacedWheel& wheel, double s_w,
                                                 double x_target) {
  const ProfileSpline& sp = wheel.spline();
  if (s_w < 0.0 || s_w > sp.length()) return std::nullopt;
  const ProfileVector pw = sp.PositionAt(s_w);
  const double radius = wheel.nominal_radius() + pw.z;
  const double axial = wheel.profile_offset() + pw.y;
  double x_w = x_target - wheel.p_TWo_T()(0);
  for (int it = 0; it < 30; ++it) {
    if (std::fabs(x_w) >= radius) return std::nullopt;
    const Eigen::Vector3d q(x_w, axial, std::sqrt(radius * radius - x_w * x_w));
    const Eigen::Vector3d p = wheel.p_TWo_T() + wheel.R_TW() * q;
    const double mismatch = p(0) - x_target;
    if (std::fabs(mismatch) < 1e-12) return p;
    x_w -= mismatch;
  }
  return std::nullopt;
}

// Fraction θ of the rail in the mean surface, Eq. 18b: the share of the normal displacement
// that body 1 (the rail) takes, (1 − ν1)/G1 against (1 − ν2)/G2.
double RailShare(const Case& c) {
  const double a = (1.0 - c.rail_material.poisson) * c.wheel_material.shear_modulus;
  const double b = (1.0 - c.wheel_material.poisson) * c.rail_material.shear_modulus;
  return a / (a + b);
}

// The reference point and the planar reference frame (x̄, s̄, n̄) at it, in which the forces are
// aggregated (§3.7).
struct ReferenceFrame {
  PatchReference ref;
  Eigen::Vector2d p_c;   // reference point on the rail, track (y, z)
  Eigen::Vector3d p_c3;  // and with its x
  Eigen::Vector2d t_bar, n_bar;
  Eigen::Vector3d t_bar3, n_bar3;
};

ReferenceFrame MakeReferenceFrame(const PatchContext& ctx, const PatchExtent& extent) {
  ReferenceFrame f;
  f.ref = FindReference(ctx, extent);
  f.p_c = ctx.rail->PositionAt(f.ref.s);
  f.p_c3 = Eigen::Vector3d(f.ref.x, f.p_c(0), f.p_c(1));
  f.t_bar = Eigen::Vector2d(std::cos(f.ref.angle), std::sin(f.ref.angle));
  f.n_bar = Eigen::Vector2d(-std::sin(f.ref.angle), std::cos(f.ref.angle));
  f.t_bar3 = Eigen::Vector3d(0.0, f.t_bar(0), f.t_bar(1));
  f.n_bar3 = Eigen::Vector3d(0.0, f.n_bar(0), f.n_bar(1));
  return f;
}

// The wheel point opposite the reference: the wheel surface vertically above/below the rail
// reference point, as the contact search measures the gap (CONTACT pairs them this way: the
// pairing along n̄ instead shifts the mean surface's angle by ~5 mrad at a 69° flange contact,
// which moves the lateral force by 3 % of the load).
struct WheelOpposite {
  Eigen::Vector3d q_c;  // track frame
  double s = 0.0;       // wheel profile arc length
};

WheelOpposite FindWheelOpposite(const PlacedWheel& wheel, const Eigen::Vector3d& p_c3) {
  WheelOpposite w;
  const auto t_q = wheel.IntersectLine(p_c3, Eigen::Vector3d::UnitZ(), 0.0);
  w.q_c = p_c3 + (t_q ? *t_q : 0.0) * Eigen::Vector3d::UnitZ();
  const ProfileHeight wheel_ref = wheel.spline().ZAtY(wheel.ToWheelProfile(w.q_c)(0));
  w.s = wheel_ref.found() ? wheel_ref.s : 0.0;
  return w;
}

// The curved reference (§3.3, Eq. 18) per grid row: the mean of rail and wheel at equal
// arc-length steps, its tangent, normal and inclination. Where the wheel has no point opposite
// (or the row lies beyond the rail's ends) the rail's own surface stands in and `valid` is false.
struct MeanSurface {
  std::vector<Eigen::Vector2d> m, t, n;
  std::vector<double> delta, s_rail;
  std::vector<bool> valid;
};

MeanSurface BuildMeanSurface(const PatchContext& ctx, const Grid& grid, const PatchReference& ref,
                             double s_cp_wheel) {
  const PlacedRail& rail = *ctx.rail;
  const PlacedWheel& wheel = *ctx.wheel;
  const double theta = RailShare(*ctx.c);
  const int ny = grid.ny;
  MeanSurface ms;
  ms.m.resize(ny);
  ms.t.resize(ny);
  ms.n.resize(ny);
  ms.delta.resize(ny);
  ms.s_rail.resize(ny);
  ms.valid.assign(ny, false);
  const double eps = 1e-4;  // mm, finite-difference step for the wheel's tangent
  for (int j = 0; j < ny; ++j) {
    const double s_off = grid.y(j);
    ms.s_rail[j] = std::clamp(ref.s + s_off, 0.0, rail.length());
    const Eigen::Vector2d pr = rail.PositionAt(ms.s_rail[j]);
    const Eigen::Vector2d tr = rail.TangentAt(ms.s_rail[j]);
    // Wheel profiles run with y descending, so the same physical direction is −s on the wheel.
    const double s_w = s_cp_wheel - s_off;
    const auto pw = WheelPointInPlane(wheel, s_w, ref.x);
    const auto pw_a = WheelPointInPlane(wheel, s_w + eps, ref.x);
    const auto pw_b = WheelPointInPlane(wheel, s_w - eps, ref.x);
    const bool inside = ref.s + s_off >= 0.0 && ref.s + s_off <= rail.length();
    if (inside && pw && pw_a && pw_b) {
      const Eigen::Vector2d tw = (pw_b->tail<2>() - pw_a->tail<2>()).normalized();
      ms.m[j] = theta * pr + (1.0 - theta) * pw->tail<2>();
      ms.t[j] = (theta * tr + (1.0 - theta) * tw).normalized();
      ms.valid[j] = true;
    } else {
      ms.m[j] = pr;
      ms.t[j] = tr;
    }
    ms.n[j] = Eigen::Vector2d(-ms.t[j](1), ms.t[j](0));
    ms.delta[j] = std::atan2(ms.t[j](1), ms.t[j](0));
  }
  return ms;
}

// What the solver takes per element: undeformed distance, rigid slip and friction.
struct GridInputs {
  std::vector<double> h, wx, wy, mu;
};

// The grid-based rigid slip (§3.5) of the element whose rail point is on the mean surface at
// m3 and whose wheel point q lies along the normal n3; the mid-plane correction (§3.6, Eq. 20)
// when the case asks for it. Velocities are material velocities in the track frame that
// travels with the wheelset (the rail moves by −V).
void RigidSlip(const PatchContext& ctx, const Eigen::Vector3d& q, const Eigen::Vector3d& t3,
               const Eigen::Vector3d& n3, double& wx, double& wy) {
  const double v = ctx.velocity;
  const Eigen::Vector3d v_p(-v, 0.0, 0.0);
  const Eigen::Vector3d v_q = ctx.wheel->MaterialVelocity(q);
  double w_x;
  if (ctx.c->effects.midplane_correction) {
    // Eq. 20: measure the longitudinal slip along the direction half-way between the two
    // velocities, which removes the artificial slip −V(1 − cos θ) of a prismatic surface.
    const Eigen::Vector3d v_mid = 0.5 * (v_p.normalized() + v_q.normalized());
    const Eigen::Vector3d tx_prime = -v_mid.normalized();
    const double cs = tx_prime.dot(Eigen::Vector3d::UnitX());
    const double sn = tx_prime.dot(n3);
    auto along = [&](const Eigen::Vector3d& vel) {
      return cs * vel(0) + sn * vel.dot(n3);  // x' component of R^T·v, Eq. 20d
    };
    w_x = along(v_p) - along(v_q);
  } else {
    w_x = v_p(0) - v_q(0);
  }
  wx = w_x / v;
  wy = (v_p - v_q).dot(t3) / v;
}

// One grid row j: the undeformed distance along the local normal n_j (Eq. 10a; Eq. 19 is its
// first-order form h̄·cos(δ_j − δ̄)) and the rigid slip of every element.
void FillRow(const PatchContext& ctx, const Grid& grid, double ref_x, const MeanSurface& ms, int j,
             GridInputs& in) {
  const PlacedRail& rail = *ctx.rail;
  const Eigen::Vector3d t3(0.0, ms.t[j](0), ms.t[j](1)), n3(0.0, ms.n[j](0), ms.n[j](1));
  const double mu_j = ctx.c->friction.MuAt(ms.delta[j]);
  std::optional<double> sr;
  if (ms.valid[j]) sr = rail.IntersectLine(ms.m[j], ms.n[j], ms.s_rail[j]);
  const double t_rail = sr ? (rail.PositionAt(*sr) - ms.m[j]).dot(ms.n[j]) : 0.0;
  // Newton for the wheel starts from the intersections of the row's previous elements,
  // extrapolated: along x the intersection follows the wheel's circle, so a quadratic through
  // the last three is within ~dx³·x/R³ (1e-9 mm) and one Newton step suffices, against ~x·dx/R
  // from the neighbour alone and up to the whole interpenetration from the rail's.
  double t_guess = t_rail;
  double t_prev[3] = {0.0, 0.0, 0.0};
  int n_prev = 0;  // consecutive intersections found just before element i (up to 3)
  for (int i = 0; i < grid.nx; ++i) {
    const std::size_t k = grid.index(i, j);
    in.mu[k] = mu_j;
    if (!sr) continue;
    if (n_prev == 3) {
      t_guess = 3.0 * t_prev[0] - 3.0 * t_prev[1] + t_prev[2];
    } else if (n_prev == 2) {
      t_guess = 2.0 * t_prev[0] - t_prev[1];
    } else if (n_prev == 1) {
      t_guess = t_prev[0];
    }
    const Eigen::Vector3d m3(ref_x + grid.x(i), ms.m[j](0), ms.m[j](1));
    const auto t_wheel = ctx.wheel->IntersectLine(m3, n3, t_guess);
    if (!t_wheel) {
      n_prev = 0;
      continue;
    }
    t_prev[2] = t_prev[1];
    t_prev[1] = t_prev[0];
    t_prev[0] = *t_wheel;
    n_prev = std::min(n_prev + 1, 3);
    in.h[k] = t_rail - *t_wheel;
    if (ctx.tangential) RigidSlip(ctx, m3 + *t_wheel * n3, t3, n3, in.wx[k], in.wy[k]);
  }
}

GridInputs FillGridInputs(const PatchContext& ctx, const Grid& grid, double ref_x,
                          const MeanSurface& ms) {
  GridInputs in;
  in.h.assign(grid.size(), kNoContactDistance);
  in.wx.assign(grid.size(), 0.0);
  in.wy.assign(grid.size(), 0.0);
  in.mu.resize(grid.size());
  for (int j = 0; j < grid.ny; ++j) FillRow(ctx, grid, ref_x, ms, j, in);
  return in;
}

// Creepages at the reference, for information (the solve uses the grid-based rigid slip).
void ReferenceCreepages(const PatchContext& ctx, const ReferenceFrame& f,
                        const Eigen::Vector3d& q_c, PatchResult& result) {
  const double v = ctx.velocity;
  const Eigen::Vector3d w = Eigen::Vector3d(-v, 0.0, 0.0) - ctx.wheel->MaterialVelocity(q_c);
  result.cksi = w(0) / v;
  result.ceta = w.dot(f.t_bar3) / v;
  result.cphi = -ctx.wheel->AngularVelocity().dot(f.n_bar3) / v;
}

// Aggregation (§3.7, Eq. 21–23): tractions rotated from the local (x, s_j, n_j) directions to
// the reference frame (x̄, s̄, n̄), moments with the lever arm of each element on the curved
// reference surface relative to the reference point.
void AggregateForces(const Grid& grid, const MeanSurface& ms, const ReferenceFrame& f,
                     PatchResult& result) {
  const double area = grid.element_area();
  Eigen::Vector3d force_bar = Eigen::Vector3d::Zero(), moment_bar = Eigen::Vector3d::Zero();
  for (int j = 0; j < grid.ny; ++j) {
    const Eigen::Vector2d d = ms.m[j] - f.p_c;
    const double s_lever = d.dot(f.t_bar), n_lever = d.dot(f.n_bar);
    const double cos_d = std::cos(ms.delta[j] - f.ref.angle);
    const double sin_d = std::sin(ms.delta[j] - f.ref.angle);
    for (int i = 0; i < grid.nx; ++i) {
      const std::size_t k = grid.index(i, j);
      const double pn = result.pn[k];
      const double px = result.px.empty() ? 0.0 : result.px[k];
      const double ps = result.ps.empty() ? 0.0 : result.ps[k];
      // Local s_j, n_j expressed in s̄, n̄: s_j = cos·s̄ + sin·n̄, n_j = −sin·s̄ + cos·n̄.
      const Eigen::Vector3d p(px, cos_d * ps - sin_d * pn, sin_d * ps + cos_d * pn);
      const Eigen::Vector3d r(grid.x(i), s_lever, n_lever);
      force_bar += p * area;
      moment_bar += r.cross(p) * area;
    }
  }
  result.fx = force_bar(0);
  result.fs = force_bar(1);
  result.fn = force_bar(2);
  result.mn = moment_bar(2);
  result.force_T =
      force_bar(0) * Eigen::Vector3d::UnitX() + force_bar(1) * f.t_bar3 + force_bar(2) * f.n_bar3;
  result.moment_T = moment_bar(0) * Eigen::Vector3d::UnitX() + moment_bar(1) * f.t_bar3 +
                    moment_bar(2) * f.n_bar3;
}

}  // namespace

PatchResult SolveCurvedPatch(const PatchContext& ctx, const PatchExtent& extent) {
  const ReferenceFrame f = MakeReferenceFrame(ctx, extent);
  const WheelOpposite opposite = FindWheelOpposite(*ctx.wheel, f.p_c3);
  // Lateral extent along the rail, relative to the reference.
  const auto& samples = ctx.search->samples;
  const Grid grid =
      CheckedPatchGrid(ctx, extent.x_min - f.ref.x, extent.x_max - f.ref.x,
                       samples[extent.first].s - f.ref.s, samples[extent.last].s - f.ref.s);
  const MeanSurface ms = BuildMeanSurface(ctx, grid, f.ref, opposite.s);
  const GridInputs in = FillGridInputs(ctx, grid, f.ref.x, ms);

  PatchResult result;
  if (ctx.tangential) ReferenceCreepages(ctx, f, opposite.q_c, result);
  SolveOnGrid(ctx, grid, in.h, in.wx, in.wy, in.mu, result);
  AggregateForces(grid, ms, f, result);
  FillReferenceOutputs(ctx, f.ref, f.p_c3, result);
  if (ctx.options->keep_fields) {
    result.curve_y.reserve(grid.ny);
    for (int j = 0; j < grid.ny; ++j) {
      result.curve_y.push_back(ms.m[j](0));
      result.curve_z.push_back(ms.m[j](1));
      result.curve_angle.push_back(ms.delta[j]);
    }
  } else {
    ClearFields(result);
  }
  return result;
}

}  // namespace wrc::wr
