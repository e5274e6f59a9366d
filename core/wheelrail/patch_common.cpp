#include "core/wheelrail/patch_common.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "wrc/core/coupled_solver.h"
#include "wrc/core/errors.h"

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

Grid CheckedPatchGrid(const PatchContext& ctx, double x_min, double x_max, double s_min,
                      double s_max) {
  const double dx = ctx.c->grid.dx, ds = ctx.c->grid.ds;
  // Counted in floating point, as PatchGrid lays them out, before any integer or allocation.
  const double nx = std::ceil(x_max / dx) - std::floor(x_min / dx) + 3.0;
  const double ny = std::ceil(s_max / ds) - std::floor(s_min / ds) + 3.0;
  if (!(nx * ny <= static_cast<double>(ctx.options->max_patch_elements))) {
    throw InputError(ctx.c->source_name + ": a contact patch needs " + FormatNumber(nx) + " x " +
                     FormatNumber(ny) + " elements, more than the limit of " +
                     std::to_string(ctx.options->max_patch_elements) +
                     ": coarsen grid.dx/grid.ds or check the pose");
  }
  return PatchGrid(dx, ds, x_min, x_max, s_min, s_max);
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

namespace {

// Elements kept around the interpenetration in the solve box: one would do for the normal
// problem; two more leave the tangential sweep room downstream of the contact.
constexpr int kBoxMargin = 3;
// A new operator is made this much larger than its box needs (capped by the potential contact
// area), so that the slightly larger boxes of the next steps of a force iteration reuse it.
constexpr double kBoxGrowth = 1.25;

// The solve box of a patch: the part of the potential contact area that can carry pressure.
// In contact the deformed distance h + u_n vanishes with u_n > 0 (the Boussinesq kernel is
// positive and so are the pressures), so contact needs h < 0: elements outside the bounding box
// of the interpenetration stay exterior for identical materials (no normal–tangential coupling)
// and the box gives the same solution as the whole area at a fraction of the cost (at a deep
// flange contact the area is 10x the contact). Box dimensions of a cached operator are kept when
// they fit, so the operator is reused.
struct SolveBox {
  int i0 = 0, j0 = 0, nx = 0, ny = 0;
};

SolveBox ChooseBox(const Grid& grid, const std::vector<double>& h, const PatchCache* cache,
                   bool use_box, bool& reuse) {
  int i_lo = grid.nx, i_hi = -1, j_lo = grid.ny, j_hi = -1;
  for (int j = 0; j < grid.ny; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      if (h[grid.index(i, j)] < 0.0) {
        i_lo = std::min(i_lo, i);
        i_hi = std::max(i_hi, i);
        j_lo = std::min(j_lo, j);
        j_hi = std::max(j_hi, j);
      }
    }
  }
  reuse = false;
  if (i_hi < 0 || !use_box) {  // no interpenetration (or no box wanted): the whole area
    i_lo = j_lo = 0;
    i_hi = grid.nx - 1;
    j_hi = grid.ny - 1;
  }
  const int need_x = std::min(grid.nx, i_hi - i_lo + 1 + 2 * kBoxMargin);
  const int need_y = std::min(grid.ny, j_hi - j_lo + 1 + 2 * kBoxMargin);
  SolveBox box;
  const FftInfluenceOperator* op = cache ? cache->normal_operator.get() : nullptr;
  if (op && op->grid().dx == grid.dx && op->grid().dy == grid.dy && op->grid().nx >= need_x &&
      op->grid().nx <= grid.nx && op->grid().ny >= need_y && op->grid().ny <= grid.ny) {
    box.nx = op->grid().nx;
    box.ny = op->grid().ny;
    reuse = true;
  } else {
    box.nx = std::min(grid.nx, static_cast<int>(std::ceil(kBoxGrowth * need_x)));
    box.ny = std::min(grid.ny, static_cast<int>(std::ceil(kBoxGrowth * need_y)));
  }
  // Centred on the interpenetration, shifted to lie inside the potential contact area.
  box.i0 = std::clamp((i_lo + i_hi + 1 - box.nx) / 2, 0, grid.nx - box.nx);
  box.j0 = std::clamp((j_lo + j_hi + 1 - box.ny) / 2, 0, grid.ny - box.ny);
  return box;
}

// Values of `from` (on grid `a`) at the elements of grid `b` with the same centre (offsets
// rounded to whole elements); zero where `a` has none.
void Remap(const Grid& a, const std::vector<double>& from, const Grid& b, std::vector<double>& to) {
  to.assign(b.size(), 0.0);
  if (from.size() != a.size()) return;
  const int di = static_cast<int>(std::lround((b.x0 - a.x0) / a.dx));
  const int dj = static_cast<int>(std::lround((b.y0 - a.y0) / a.dy));
  for (int j = 0; j < b.ny; ++j) {
    const int ja = j + dj;
    if (ja < 0 || ja >= a.ny) continue;
    for (int i = 0; i < b.nx; ++i) {
      const int ia = i + di;
      if (ia >= 0 && ia < a.nx) to[b.index(i, j)] = from[a.index(ia, ja)];
    }
  }
}

}  // namespace

namespace {

// Tγ from the local fields: the work of the tractions on the rail against its slip relative to
// the wheel, −Σ (p_x·s_x + p_s·s_s)·dA, per unit rolling distance (N). Tractions and slips of
// an element share its local frame (x, s_j on the curved reference), so the sum needs no
// rotation. Outside the box nothing is in contact.
double SlipWork(const Grid& box, const TangentialSolution& ts) {
  double work = 0.0;
  for (std::size_t k = 0; k < ts.px.size(); ++k) work += ts.px[k] * ts.sx[k] + ts.py[k] * ts.sy[k];
  return -work * box.element_area();
}

}  // namespace

// Dissimilar bodies (K != 0): normal and tangential problems coupled (Panagiotopoulos process,
// coupled_solver.h) on the whole potential contact area. The tangential tractions then move
// the normal displacements, so the interpenetration no longer bounds the contact and the solve
// box of the uncoupled path would not be exact.
namespace {
void SolveCoupledOnGrid(const PatchContext& ctx, const Grid& grid, const std::vector<double>& h,
                        const std::vector<double>& wx, const std::vector<double>& wy,
                        const std::vector<double>& mu, PatchResult& result) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const CoupledContactOperator op(grid, ctx.material);
  const auto t1 = Clock::now();
  CoupledProblem problem;
  problem.h = h;
  problem.load = NormalLoad::Approach(0.0);
  problem.mu = mu;
  problem.wx = wx;
  problem.wy = wy;
  CoupledOptions options;
  options.normal = ctx.options->normal;
  options.tangential = ctx.options->tangential;
  CoupledWorkspace ws;
  CoupledSolution sol;
  const CoupledSummary summary = SolveCoupled(op, problem, options, ws, sol);
  if (ctx.timings) {
    ctx.timings->influence += std::chrono::duration<double>(t1 - t0).count();
    ctx.timings->tangential += std::chrono::duration<double>(Clock::now() - t1).count();
  }
  result.normal_iterations = summary.normal_iterations;
  result.tangential_iterations = summary.tangential_iterations;
  result.status = summary.status;
  result.t_gamma_slip = SlipWork(grid, sol.tangential);
  result.pn = std::move(sol.normal.pressure);
  result.pmax = sol.normal.pmax;
  result.n_contact = sol.normal.n_contact;
  result.contact_area = result.n_contact * grid.element_area();
  result.wx = wx;
  result.ws = wy;
  result.px = std::move(sol.tangential.px);
  result.ps = std::move(sol.tangential.py);
  result.sx = std::move(sol.tangential.sx);
  result.ss = std::move(sol.tangential.sy);
  result.state = std::move(sol.tangential.state);
  result.n_slip = sol.tangential.n_slip;
  result.n_adhesion = sol.tangential.n_adhesion;
}

}  // namespace

namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

// Refuses a potential contact area larger than WheelRailOptions::max_patch_elements.
void RequireSolvableSize(const PatchContext& ctx, const Grid& grid) {
  if (grid.size() > static_cast<std::size_t>(ctx.options->max_patch_elements)) {
    throw InputError(ctx.c->source_name + ": a contact patch needs " + std::to_string(grid.nx) +
                     " x " + std::to_string(grid.ny) + " elements, more than the limit of " +
                     std::to_string(ctx.options->max_patch_elements) +
                     ": coarsen grid.dx/grid.ds or check the pose");
  }
}

// The solve box (SolveBox) as a grid of its own, with the moves of fields between it and the
// potential contact area.
struct BoxOnGrid {
  const Grid& grid;
  SolveBox sb;
  Grid box;

  BoxOnGrid(const Grid& g, const SolveBox& b) : grid(g), sb(b), box(g) {
    box.nx = sb.nx;
    box.ny = sb.ny;
    box.x0 = grid.x(sb.i0);
    box.y0 = grid.y(sb.j0);
  }
  std::vector<double> Crop(const std::vector<double>& v) const {
    std::vector<double> out(box.size());
    for (int j = 0; j < box.ny; ++j) {
      for (int i = 0; i < box.nx; ++i) out[box.index(i, j)] = v[grid.index(sb.i0 + i, sb.j0 + j)];
    }
    return out;
  }
  // Back onto the potential contact area, `out` (the area's size) keeping its values where the
  // box does not reach.
  template <class T>
  std::vector<T> Expand(const std::vector<T>& v, std::vector<T> out) const {
    for (int j = 0; j < box.ny; ++j) {
      for (int i = 0; i < box.nx; ++i) out[grid.index(sb.i0 + i, sb.j0 + j)] = v[box.index(i, j)];
    }
    return out;
  }
  std::vector<double> Zeros() const { return std::vector<double>(grid.size(), 0.0); }
};

// The normal problem on the solve box, warm-started from the patch's previous solution; fills
// the normal fields of `result`.
NormalSummary SolveNormalOnBox(const PatchContext& ctx, const BoxOnGrid& on, bool reuse,
                               const std::vector<double>& h, PatchCache& cache, NormalSolution& ns,
                               PatchResult& result) {
  const auto t0 = Clock::now();
  if (!reuse) {
    cache.normal_operator = std::make_unique<FftInfluenceOperator>(
        on.box, ctx.material, std::vector<InfluenceComponent>{InfluenceComponent::kNN});
    cache.rolling_operator.reset();
  }
  const FftInfluenceOperator& op = *cache.normal_operator;
  op.Prepare();  // every normal solve transforms: its plan and kernel count as influence time
  const std::vector<double> h_box = on.Crop(h);
  NormalOptions normal_options = ctx.options->normal;
  if (cache.has_normal) {
    Remap(cache.normal_box, cache.normal.pressure, on.box, ns.pressure);
    normal_options.warm_start = true;
  }
  const auto t1 = Clock::now();
  const NormalSummary normal =
      SolveNormal(op, h_box, NormalLoad::Approach(0.0), normal_options, cache.normal_workspace, ns);
  if (ctx.timings) {
    ctx.timings->influence += Seconds(t0, t1);
    ctx.timings->normal += Seconds(t1, Clock::now());
  }
  result.normal_iterations = normal.iterations;
  result.status = normal.status;
  result.pn = on.Expand(ns.pressure, on.Zeros());
  result.pmax = ns.pmax;
  result.n_contact = ns.n_contact;
  result.contact_area = result.n_contact * on.box.element_area();
  return normal;
}

// Without friction every element in contact slips.
void FrictionlessStates(const Grid& grid, PatchResult& result) {
  result.state.assign(grid.size(), ElementState::kExterior);
  for (std::size_t k = 0; k < grid.size(); ++k) {
    if (result.pn[k] > 0.0) result.state[k] = ElementState::kSlip;
  }
  result.n_slip = result.n_contact;
}

// The previous tractions of this patch moved onto the box, as the start of the next solve.
// Slip tractions are μ·p_n and adhesion tractions grow with the load too: scaled by the change
// of pressure, the previous solution starts the next step of a force iteration closer than
// unscaled.
void WarmTractions(const PatchCache& cache, const Grid& box, const std::vector<double>& pressure,
                   TangentialSolution& ts) {
  Remap(cache.tangential_box, cache.tangential.px, box, ts.px);
  Remap(cache.tangential_box, cache.tangential.py, box, ts.py);
  std::vector<double> p_old;
  Remap(cache.tangential_box, cache.tangential_pressure, box, p_old);
  for (std::size_t k = 0; k < p_old.size(); ++k) {
    if (p_old[k] > 0.0) {
      const double ratio = pressure[k] / p_old[k];
      ts.px[k] *= ratio;
      ts.py[k] *= ratio;
    }
  }
}

// The steady-rolling problem on the solve box under the pressure ns; fills the tangential
// fields of `result`.
TangentialSummary SolveTangentialOnBox(const PatchContext& ctx, const BoxOnGrid& on,
                                       const NormalSolution& ns, const std::vector<double>& wx,
                                       const std::vector<double>& wy, const std::vector<double>& mu,
                                       PatchCache& cache, TangentialSolution& ts,
                                       PatchResult& result) {
  const auto t0 = Clock::now();
  if (!cache.rolling_operator) {
    cache.rolling_operator = std::make_unique<SteadyRollingOperator>(on.box, ctx.material);
  }
  const SteadyRollingOperator& rolling = *cache.rolling_operator;
  const auto t1 = Clock::now();
  TangentialProblem tp;
  tp.pressure = ns.pressure;
  tp.mu = mu.size() == on.grid.size() ? on.Crop(mu) : mu;  // or one value for the whole patch
  tp.wx = on.Crop(wx);
  tp.wy = on.Crop(wy);
  result.wx = wx;
  result.ws = wy;
  TangentialOptions tangential_options = ctx.options->tangential;
  tangential_options.final_slip = ctx.options->keep_fields;  // only the fields show the slip
  if (cache.has_tangential) {
    WarmTractions(cache, on.box, ns.pressure, ts);
    tangential_options.warm_start = true;
  }
  const TangentialSummary summary =
      SolveTangential(rolling, tp, tangential_options, cache.tangential_workspace, ts);
  if (ctx.timings) {
    ctx.timings->influence += Seconds(t0, t1);
    ctx.timings->tangential += Seconds(t1, Clock::now());
  }
  result.tangential_iterations = summary.iterations;
  if (summary.status == SolverStatus::kNotConverged) result.status = SolverStatus::kNotConverged;
  result.t_gamma_slip = SlipWork(on.box, ts);
  result.px = on.Expand(ts.px, on.Zeros());
  result.ps = on.Expand(ts.py, on.Zeros());
  // Outside the box nothing is in contact; the slip reported there is the rigid slip.
  result.sx = on.Expand(ts.sx, wx);
  result.ss = on.Expand(ts.sy, wy);
  result.state =
      on.Expand(ts.state, std::vector<ElementState>(on.grid.size(), ElementState::kExterior));
  result.n_slip = ts.n_slip;
  result.n_adhesion = ts.n_adhesion;
  return summary;
}

// The normal and tangential solution on the potential contact area (SolveOnGrid without the
// measurement of the contact's extent). Converged solutions are kept in the patch's cache as
// the warm start of its next solve.
void SolveFields(const PatchContext& ctx, const Grid& grid, const std::vector<double>& h,
                 const std::vector<double>& wx, const std::vector<double>& wy,
                 const std::vector<double>& mu, PatchResult& result) {
  RequireSolvableSize(ctx, grid);
  result.grid = grid;
  result.n_pot = static_cast<int>(grid.size());
  result.h = h;
  double hmin = 0.0;
  for (double v : h) hmin = std::min(hmin, v);
  result.approach = -hmin;
  if (ctx.tangential && ctx.material.kappa != 0.0) {
    SolveCoupledOnGrid(ctx, grid, h, wx, wy, mu, result);
    return;
  }
  PatchCache local;
  PatchCache& cache = ctx.cache ? *ctx.cache : local;
  bool reuse = false;
  const BoxOnGrid on(grid, ChooseBox(grid, h, ctx.cache, ctx.options->solve_box, reuse));
  NormalSolution ns;
  const NormalSummary normal = SolveNormalOnBox(ctx, on, reuse, h, cache, ns, result);
  const bool normal_converged = normal.status != SolverStatus::kNotConverged;
  if (!ctx.tangential || normal.status == SolverStatus::kNoContact) {
    FrictionlessStates(grid, result);
    if (normal_converged) {
      cache.normal = std::move(ns);
      cache.normal_box = on.box;
      cache.has_normal = true;
    }
    return;
  }
  TangentialSolution ts;
  const TangentialSummary tangential =
      SolveTangentialOnBox(ctx, on, ns, wx, wy, mu, cache, ts, result);
  if (normal_converged && tangential.status != SolverStatus::kNotConverged) {
    cache.tangential_pressure = ns.pressure;
    cache.normal = std::move(ns);
    cache.tangential = std::move(ts);
    cache.normal_box = cache.tangential_box = on.box;
    cache.has_normal = cache.has_tangential = true;
  }
}

// Where the pressure lies on the grid: how many columns and rows the contact spans, and
// whether it reaches the grid's outermost elements. The grid is laid out one element beyond the
// interpenetration found by the contact search, and pressure needs interpenetration (h < 0)
// for identical bodies, so pressure there means that the search missed part of the
// interpenetration or (dissimilar bodies) that the coupling carried the contact past it.
void MeasureContact(const Grid& grid, PatchResult& result) {
  int i_lo = grid.nx, i_hi = -1, j_lo = grid.ny, j_hi = -1;
  for (int j = 0; j < grid.ny; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      if (!(result.pn[grid.index(i, j)] > 0.0)) continue;
      i_lo = std::min(i_lo, i);
      i_hi = std::max(i_hi, i);
      j_lo = std::min(j_lo, j);
      j_hi = std::max(j_hi, j);
    }
  }
  if (i_hi < 0) return;
  result.contact_columns = i_hi - i_lo + 1;
  result.contact_rows = j_hi - j_lo + 1;
  result.contact_at_border = i_lo == 0 || j_lo == 0 || i_hi == grid.nx - 1 || j_hi == grid.ny - 1;
}

}  // namespace

void SolveOnGrid(const PatchContext& ctx, const Grid& grid, const std::vector<double>& h,
                 const std::vector<double>& wx, const std::vector<double>& wy,
                 const std::vector<double>& mu, PatchResult& result) {
  SolveFields(ctx, grid, h, wx, wy, mu, result);
  MeasureContact(grid, result);
}

void FillReferenceOutputs(const PatchContext& ctx, const PatchReference& ref,
                          const Eigen::Vector3d& p_T, PatchResult& result) {
  result.contact_angle = ref.angle;
  result.reference_T = p_T;
  result.reference_rail = ctx.rail->ToRail(p_T.tail<2>());
  const Eigen::Vector3d q = ctx.wheel->R_TW().transpose() * (p_T - ctx.wheel->p_TWo_T());
  const Eigen::Vector2d yz = ctx.wheel->ToWheelProfile(p_T);
  result.reference_wheel = {q(0), yz(0), yz(1)};
  result.rolling_radius = ctx.wheel->nominal_radius() + yz(1);
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
