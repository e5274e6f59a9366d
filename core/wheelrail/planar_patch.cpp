#include <algorithm>
#include <cmath>

#include "core/wheelrail/patch.h"
#include "core/wheelrail/patch_common.h"

namespace wrc::wr {

PatchResult SolvePlanarPatch(const PatchContext& ctx, const PatchExtent& extent) {
  const Case& c = *ctx.c;
  const PlacedRail& rail = *ctx.rail;
  const PlacedWheel& wheel = *ctx.wheel;
  const PatchReference ref = FindReference(ctx, extent);

  // Contact plane: tangent t (lateral) and normal n (into the rail) in the y–z plane.
  const Eigen::Vector2d t(std::cos(ref.angle), std::sin(ref.angle));
  const Eigen::Vector2d n(-std::sin(ref.angle), std::cos(ref.angle));
  const Eigen::Vector3d t3(0.0, t(0), t(1)), n3(0.0, n(0), n(1));
  const Eigen::Vector2d p_c = rail.PositionAt(ref.s);
  const Eigen::Vector3d p_c3(ref.x, p_c(0), p_c(1));

  // Potential contact area: the patch's extent projected onto the plane, plus a margin.
  double s_min = 1e300, s_max = -1e300;
  for (int k = extent.first; k <= extent.last; ++k) {
    const LocusSample& sample = ctx.search->samples[k];
    const double s_loc = (Eigen::Vector2d(sample.y, sample.z) - p_c).dot(t);
    s_min = std::min(s_min, s_loc);
    s_max = std::max(s_max, s_loc);
  }
  const Grid grid = CheckedPatchGrid(ctx, extent.x_min - ref.x, extent.x_max - ref.x, s_min, s_max);

  // Undeformed distance along n at every element (Fig. 4d): h = t_rail − t_wheel, the
  // distances along n from the plane to the rail and to the wheel surface.
  std::vector<double> h(grid.size());
  for (int j = 0; j < grid.ny; ++j) {
    const double s_loc = grid.y(j);
    const Eigen::Vector2d p0 = p_c + s_loc * t;
    const auto s_rail = rail.IntersectLine(p0, n, ref.s + s_loc);
    const double t_rail = s_rail ? (rail.PositionAt(*s_rail) - p0).dot(n) : 0.0;
    for (int i = 0; i < grid.nx; ++i) {
      double value = kNoContactDistance;
      if (s_rail) {
        const Eigen::Vector3d q0(ref.x + grid.x(i), p0(0), p0(1));
        const auto t_wheel = wheel.IntersectLine(q0, n3, t_rail);
        if (t_wheel) value = t_rail - *t_wheel;
      }
      h[grid.index(i, j)] = value;
    }
  }

  // Creepages from the velocities of the rail and wheel material points at the reference
  // (paper §2.6, Eq. 15): P on the rail, Q on the wheel along the normal.
  PatchResult result;
  const auto t_q = wheel.IntersectLine(p_c3, n3, 0.0);
  const Eigen::Vector3d q = p_c3 + (t_q ? *t_q : 0.0) * n3;
  const double v = ctx.velocity;
  if (ctx.tangential) {
    const Eigen::Vector3d w = Eigen::Vector3d(-v, 0.0, 0.0) - wheel.MaterialVelocity(q);
    result.cksi = w(0) / v;
    result.ceta = w.dot(t3) / v;
    result.cphi = -wheel.AngularVelocity().dot(n3) / v;
  }
  std::vector<double> wx(grid.size()), wy(grid.size());
  for (int j = 0; j < grid.ny; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      // Eq. 15 with CONTACT's δq/6 correction of the spin term for steady rolling.
      wx[grid.index(i, j)] = result.cksi - result.cphi * grid.y(j);
      wy[grid.index(i, j)] = result.ceta + result.cphi * (grid.x(i) + grid.dx / 6.0);
    }
  }
  const std::vector<double> mu(1, c.friction.MuAt(ref.angle));

  SolveOnGrid(ctx, grid, h, wx, wy, mu, result);

  // Totals in the contact frame, then in the track frame (paper Eq. 21–24 with n̄ = 0).
  const double area = grid.element_area();
  double fn = 0, fx = 0, fs = 0, mx = 0, ms = 0, mn = 0;
  for (int j = 0; j < grid.ny; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      const std::size_t k = grid.index(i, j);
      const double px = result.px.empty() ? 0.0 : result.px[k];
      const double ps = result.ps.empty() ? 0.0 : result.ps[k];
      fn += result.pn[k] * area;
      fx += px * area;
      fs += ps * area;
      mx += grid.y(j) * result.pn[k] * area;
      ms -= grid.x(i) * result.pn[k] * area;
      mn += (grid.x(i) * ps - grid.y(j) * px) * area;
    }
  }
  result.fn = fn;
  result.fx = fx;
  result.fs = fs;
  result.mn = mn;
  result.force_T = fx * Eigen::Vector3d::UnitX() + fs * t3 + fn * n3;
  result.moment_T = mx * Eigen::Vector3d::UnitX() + ms * t3 + mn * n3;
  FillReferenceOutputs(ctx, ref, p_c3, result);
  if (!ctx.options->keep_fields) ClearFields(result);
  return result;
}

}  // namespace wrc::wr
