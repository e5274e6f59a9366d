#include "core/wheelrail/patch_common.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "wrc/errors.h"

namespace wrc::wr {

PatchReference FindReference(const PatchContext& ctx, const PatchExtent& extent) {
  const Method& m = ctx.c->method;
  const auto& samples = ctx.search->samples;
  const bool quadratic = m.weights == ReferenceWeights::kQuadratic;
  PatchReference ref;
  // Deepest interpenetration: the initial contact point.
  int deepest = extent.first;
  for (int k = extent.first; k <= extent.last; ++k) {
    if (samples[k].valid && samples[k].gap < samples[deepest].gap) deepest = k;
  }
  // Weights of Eq. 13/14 over the horizontal plane: ∫ w(g) dx per sample times dy = cos δ ds.
  double sum_w = 0.0, sum_y = 0.0, sum_x = 0.0, sum_a = 0.0;
  for (int k = extent.first; k <= extent.last; ++k) {
    const double w = LocusWeight(samples[k], ctx.dz, quadratic) * std::cos(samples[k].alpha);
    sum_w += w;
    sum_y += w * samples[k].y;
    sum_x += w * samples[k].x;
    sum_a += w * samples[k].alpha;
  }
  if (m.position == ReferencePosition::kInitial || !(sum_w > 0.0)) {
    ref.s = samples[deepest].s;
    ref.x = samples[deepest].x;
  } else {
    // The weighted centre (x_c, y_c), placed on the rail surface: the rail point with y = y_c
    // within the patch, by linear interpolation between samples and a Newton refinement.
    const double y_c = sum_y / sum_w;
    ref.x = sum_x / sum_w;
    ref.s = samples[deepest].s;
    double best = 1e300;
    for (int k = extent.first; k < extent.last; ++k) {
      const double y0 = samples[k].y, y1 = samples[k + 1].y;
      if ((y0 - y_c) * (y1 - y_c) <= 0.0 && y0 != y1) {
        const double s = samples[k].s + (y_c - y0) / (y1 - y0) * (samples[k + 1].s - samples[k].s);
        const double dist = std::fabs(s - samples[deepest].s);
        if (dist < best) {
          best = dist;
          ref.s = s;
        }
      }
    }
    for (int it = 0; it < 20; ++it) {
      const double f = ctx.rail->PositionAt(ref.s)(0) - y_c;
      const double df = ctx.rail->TangentAt(ref.s)(0);
      if (std::fabs(df) < 1e-9) break;
      const double step = std::clamp(-f / df, -0.5, 0.5);
      ref.s = std::clamp(ref.s + step, 0.0, ctx.rail->length());
      if (std::fabs(step) < 1e-12) break;
    }
  }
  ref.angle = m.angle == ReferenceAngle::kWeighted && sum_w > 0.0 ? sum_a / sum_w
                                                                  : ctx.rail->InclinationAt(ref.s);
  return ref;
}

Grid PatchGrid(double dx, double ds, double x_min, double x_max, double s_min, double s_max) {
  const int i0 = static_cast<int>(std::floor(x_min / dx)) - 1;
  const int i1 = static_cast<int>(std::ceil(x_max / dx)) + 1;
  const int j0 = static_cast<int>(std::floor(s_min / ds)) - 1;
  const int j1 = static_cast<int>(std::ceil(s_max / ds)) + 1;
  Grid g;
  g.nx = i1 - i0 + 1;
  g.ny = j1 - j0 + 1;
  g.dx = dx;
  g.dy = ds;
  g.x0 = i0 * dx;
  g.y0 = j0 * ds;
  return g;
}

void SolveOnGrid(const PatchContext& ctx, const Grid& grid, const std::vector<double>& h,
                 const std::vector<double>& wx, const std::vector<double>& wy,
                 const std::vector<double>& mu, PatchResult& result) {
  if (grid.size() > static_cast<std::size_t>(ctx.options->max_patch_elements)) {
    throw InputError(ctx.c->source_name + ": a contact patch needs " + std::to_string(grid.nx) +
                     " x " + std::to_string(grid.ny) + " elements, more than the limit of " +
                     std::to_string(ctx.options->max_patch_elements) +
                     ": coarsen grid.dx/grid.ds or check the pose");
  }
  result.grid = grid;
  result.n_pot = static_cast<int>(grid.size());
  result.h = h;
  double hmin = 0.0;
  for (double v : h) hmin = std::min(hmin, v);
  result.approach = -hmin;

  using Clock = std::chrono::steady_clock;
  auto seconds = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  const auto t0 = Clock::now();
  const FftInfluenceOperator op(grid, ctx.material, {InfluenceComponent::kNN});
  const auto t1 = Clock::now();
  NormalWorkspace nws;
  NormalSolution ns;
  const NormalSummary normal =
      SolveNormal(op, h, NormalLoad::Approach(0.0), ctx.options->normal, nws, ns);
  const auto t2 = Clock::now();
  if (ctx.timings) {
    ctx.timings->influence += seconds(t0, t1);
    ctx.timings->normal += seconds(t1, t2);
  }
  result.normal_iterations = normal.iterations;
  result.status = normal.status;
  result.pn = std::move(ns.pressure);
  result.pmax = ns.pmax;
  result.n_contact = ns.n_contact;

  const bool tangential = ctx.tangential && normal.status != SolverStatus::kNoContact;
  if (!tangential) {
    result.state.assign(grid.size(), ElementState::kExterior);
    for (std::size_t k = 0; k < grid.size(); ++k) {
      if (result.pn[k] > 0.0) result.state[k] = ElementState::kSlip;  // frictionless: all slip
    }
    result.n_slip = result.n_contact;
    return;
  }
  const auto t3 = Clock::now();
  const SteadyRollingOperator rolling(grid, ctx.material);
  const auto t4 = Clock::now();
  TangentialProblem tp;
  tp.pressure = result.pn;
  tp.mu = mu;
  tp.wx = wx;
  tp.wy = wy;
  result.wx = wx;
  result.ws = wy;
  TangentialWorkspace tws;
  TangentialSolution ts;
  const TangentialSummary summary = SolveTangential(rolling, tp, ctx.options->tangential, tws, ts);
  result.tangential_iterations = summary.iterations;
  if (ctx.timings) {
    ctx.timings->influence += seconds(t3, t4);
    ctx.timings->tangential += seconds(t4, Clock::now());
  }
  if (summary.status == SolverStatus::kNotConverged) result.status = SolverStatus::kNotConverged;
  result.px = std::move(ts.px);
  result.ps = std::move(ts.py);
  result.sx = std::move(ts.sx);
  result.ss = std::move(ts.sy);
  result.state = std::move(ts.state);
  result.n_slip = ts.n_slip;
  result.n_adhesion = ts.n_adhesion;
}

void FillReferenceOutputs(const PatchContext& ctx, const PatchReference& ref,
                          const Eigen::Vector3d& p_T, PatchResult& result) {
  result.contact_angle = ref.angle;
  result.reference_T = p_T;
  result.reference_rail = ctx.rail->ToRail(p_T.tail<2>());
  const Eigen::Vector3d q = ctx.wheel->R_TW().transpose() * (p_T - ctx.wheel->p_TWo_T());
  const Eigen::Vector2d yz = ctx.wheel->ToWheelProfile(p_T);
  result.reference_wheel = {q(0), yz(0), yz(1)};
}

void ClearFields(PatchResult& result) {
  for (auto* v : {&result.h, &result.pn, &result.px, &result.ps, &result.sx, &result.ss, &result.wx,
                  &result.ws, &result.curve_y, &result.curve_z, &result.curve_angle}) {
    v->clear();
    v->shrink_to_fit();
  }
  result.state.clear();
}

}  // namespace wrc::wr
