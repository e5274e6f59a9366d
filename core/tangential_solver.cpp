#include "wrc/core/tangential_solver.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "core/common/portable_simd.h"

namespace wrc {
namespace {

Grid Extended(const Grid& g) {
  Grid e = g;
  e.nx = g.nx + 1;  // one column beyond the leading edge (x > 0), where p = 0
  return e;
}

void Validate(const SteadyRollingOperator& op, const TangentialProblem& pb) {
  const std::size_t n = op.grid().size();
  if (pb.pressure.size() != n || pb.wx.size() != n || pb.wy.size() != n) {
    throw std::invalid_argument("tangential problem: pressure/rigid slip sizes differ from grid");
  }
  if (pb.mu.size() != 1 && pb.mu.size() != n) {
    throw std::invalid_argument("tangential problem: mu must have 1 or grid-size values");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(pb.pressure[i]) || !std::isfinite(pb.wx[i]) || !std::isfinite(pb.wy[i])) {
      throw std::invalid_argument("tangential problem: non-finite pressure or rigid slip");
    }
  }
  for (double m : pb.mu) {
    if (!std::isfinite(m) || m < 0.0) {
      throw std::invalid_argument("tangential problem: friction coefficient " + std::to_string(m) +
                                  " is negative or not finite");
    }
  }
}

// |(x, y)| for tractions and slips, whose magnitudes are far from overflow and underflow:
// std::hypot's rescaling costs ~20 ns a call, a few % of a steady-rolling solve.
inline double Magnitude(double x, double y) { return std::sqrt(x * x + y * y); }

struct LocalResult {
  double px, py;
  bool slip;
};

// The Coulomb problem of one element with local stiffness diag(kx, ky) (the change of its own
// slip per unit change of its own traction) and free slip (sfx, sfy) = slip at zero traction:
// s = sf + K·p. Adhesion if s = 0 is reachable inside the traction bound g; otherwise
// p = −(λI + K)⁻¹·sf with |p| = g and λ >= 0 (then s = −λ·p, opposite to p as Eq. 12e asks).
LocalResult SolveLocal(double sfx, double sfy, double kx, double ky, double bound) {
  const double ax = -sfx / kx, ay = -sfy / ky;
  if (ax * ax + ay * ay <= bound * bound) return {ax, ay, false};
  const double sf = Magnitude(sfx, sfy);
  // f(λ) = |p(λ)|² − g² is convex and decreasing; Newton from a point with f >= 0 converges
  // monotonically. λ0 = |sf|/g − max(k) gives f(λ0) >= 0 (each denominator <= |sf|/g).
  double lambda = std::max(0.0, sf / bound - std::max(kx, ky));
  for (int it = 0; it < 60; ++it) {
    const double dx = lambda + kx, dy = lambda + ky;
    const double qx = sfx / dx, qy = sfy / dy;
    const double f = qx * qx + qy * qy - bound * bound;
    const double df = -2.0 * (qx * qx / dx + qy * qy / dy);
    const double step = -f / df;
    lambda += step;
    if (std::fabs(step) <= 1e-14 * (lambda + kx)) break;
  }
  double px = -sfx / (lambda + kx), py = -sfy / (lambda + ky);
  // Put the traction exactly on the bound (Newton leaves a relative error ~1e-14).
  const double norm = Magnitude(px, py);
  if (norm > 0.0) {
    px *= bound / norm;
    py *= bound / norm;
  }
  return {px, py, true};
}

// The slip change along one row caused by a traction-difference update: the solver's inner
// loop (O(contact) per element update, most of a steady-rolling solve). Built for AVX2 as well
// as the baseline x86-64 ISA, and chosen at load time, so the binary stays portable.
WRC_CLONE_FOR_AVX2
void AddRowSlipChange(const double* __restrict xx0, const double* __restrict xx1,
                      const double* __restrict yy0, const double* __restrict yy1,
                      const double* __restrict xy0, const double* __restrict xy1, double ax,
                      double ay, int count, double* __restrict sx_row, double* __restrict sy_row) {
  for (int t = 0; t < count; ++t) {
    const double cxx = xx0[t] - xx1[t], cyy = yy0[t] - yy1[t], cxy = xy0[t] - xy1[t];
    sx_row[t] += cxx * ax + cxy * ay;
    sy_row[t] += cxy * ax + cyy * ay;
  }
}

// The slip change along one row from all updates of another row:
// s[t] += Σ_u [[xx, xy], [xy, yy]](offset_u + t)·(ax_u, ay_u), with xx, yy, xy pointing at the
// coefficients of the rows' offset dj. One call per pair of rows instead of one per update and
// row: heavy-haul rows are ~15 elements long, and the calls cost as much as the arithmetic.
WRC_CLONE_FOR_AVX2
void AddRowSlipTerms(const double* __restrict xx, const double* __restrict yy,
                     const double* __restrict xy, const int* __restrict offsets,
                     const double* __restrict ax, const double* __restrict ay, int updates,
                     int count, double* __restrict sx_row, double* __restrict sy_row) {
  int t = 0;
#if defined(__GNUC__)
  // Blocks of four slips stay in registers while all updates are added, instead of a load and a
  // store of the row per update. Written with GCC's vector type: the compiler does not
  // vectorise the block loop by itself (four scalar lanes, measured), and the type lowers to
  // AVX2 in the avx2 clone and to SSE2 pairs in the default one.
  typedef double Lanes __attribute__((vector_size(32)));
  // Three blocks at a time share each update's offset and amounts (the sums of each slip are
  // taken in the same order).
  for (; t + 12 <= count; t += 12) {
    Lanes sx0, sy0, sx1, sy1, sx2, sy2;
    std::memcpy(&sx0, sx_row + t, sizeof sx0);
    std::memcpy(&sy0, sy_row + t, sizeof sy0);
    std::memcpy(&sx1, sx_row + t + 4, sizeof sx1);
    std::memcpy(&sy1, sy_row + t + 4, sizeof sy1);
    std::memcpy(&sx2, sx_row + t + 8, sizeof sx2);
    std::memcpy(&sy2, sy_row + t + 8, sizeof sy2);
    for (int u = 0; u < updates; ++u) {
      const int o = offsets[u] + t;
      const double a = ax[u], b = ay[u];
      Lanes cxx, cyy, cxy;
      std::memcpy(&cxx, xx + o, sizeof cxx);
      std::memcpy(&cxy, xy + o, sizeof cxy);
      std::memcpy(&cyy, yy + o, sizeof cyy);
      sx0 += cxx * a + cxy * b;
      sy0 += cxy * a + cyy * b;
      std::memcpy(&cxx, xx + o + 4, sizeof cxx);
      std::memcpy(&cxy, xy + o + 4, sizeof cxy);
      std::memcpy(&cyy, yy + o + 4, sizeof cyy);
      sx1 += cxx * a + cxy * b;
      sy1 += cxy * a + cyy * b;
      std::memcpy(&cxx, xx + o + 8, sizeof cxx);
      std::memcpy(&cxy, xy + o + 8, sizeof cxy);
      std::memcpy(&cyy, yy + o + 8, sizeof cyy);
      sx2 += cxx * a + cxy * b;
      sy2 += cxy * a + cyy * b;
    }
    std::memcpy(sx_row + t, &sx0, sizeof sx0);
    std::memcpy(sy_row + t, &sy0, sizeof sy0);
    std::memcpy(sx_row + t + 4, &sx1, sizeof sx1);
    std::memcpy(sy_row + t + 4, &sy1, sizeof sy1);
    std::memcpy(sx_row + t + 8, &sx2, sizeof sx2);
    std::memcpy(sy_row + t + 8, &sy2, sizeof sy2);
  }
  for (; t + 8 <= count; t += 8) {
    Lanes sx0, sy0, sx1, sy1;
    std::memcpy(&sx0, sx_row + t, sizeof sx0);
    std::memcpy(&sy0, sy_row + t, sizeof sy0);
    std::memcpy(&sx1, sx_row + t + 4, sizeof sx1);
    std::memcpy(&sy1, sy_row + t + 4, sizeof sy1);
    for (int u = 0; u < updates; ++u) {
      const int o = offsets[u] + t;
      Lanes cxx0, cyy0, cxy0, cxx1, cyy1, cxy1;
      std::memcpy(&cxx0, xx + o, sizeof cxx0);
      std::memcpy(&cyy0, yy + o, sizeof cyy0);
      std::memcpy(&cxy0, xy + o, sizeof cxy0);
      std::memcpy(&cxx1, xx + o + 4, sizeof cxx1);
      std::memcpy(&cyy1, yy + o + 4, sizeof cyy1);
      std::memcpy(&cxy1, xy + o + 4, sizeof cxy1);
      const double a = ax[u], b = ay[u];
      sx0 += cxx0 * a + cxy0 * b;
      sy0 += cxy0 * a + cyy0 * b;
      sx1 += cxx1 * a + cxy1 * b;
      sy1 += cxy1 * a + cyy1 * b;
    }
    std::memcpy(sx_row + t, &sx0, sizeof sx0);
    std::memcpy(sy_row + t, &sy0, sizeof sy0);
    std::memcpy(sx_row + t + 4, &sx1, sizeof sx1);
    std::memcpy(sy_row + t + 4, &sy1, sizeof sy1);
  }
  for (; t + 4 <= count; t += 4) {
    Lanes sx, sy;
    std::memcpy(&sx, sx_row + t, sizeof sx);
    std::memcpy(&sy, sy_row + t, sizeof sy);
    for (int u = 0; u < updates; ++u) {
      const int o = offsets[u] + t;
      Lanes cxx, cyy, cxy;
      std::memcpy(&cxx, xx + o, sizeof cxx);
      std::memcpy(&cyy, yy + o, sizeof cyy);
      std::memcpy(&cxy, xy + o, sizeof cxy);
      const double a = ax[u], b = ay[u];
      sx += cxx * a + cxy * b;
      sy += cxy * a + cyy * b;
    }
    std::memcpy(sx_row + t, &sx, sizeof sx);
    std::memcpy(sy_row + t, &sy, sizeof sy);
  }
#endif
  for (; t < count; ++t) {
    double sx = sx_row[t], sy = sy_row[t];
    for (int u = 0; u < updates; ++u) {
      const int o = offsets[u] + t;
      sx += xx[o] * ax[u] + xy[o] * ay[u];
      sy += xy[o] * ax[u] + yy[o] * ay[u];
    }
    sx_row[t] = sx;
    sy_row[t] = sy;
  }
}

// Anderson acceleration (Walker & Ni 2011, SIAM J. Numer. Anal. 49) of the sweep seen as a
// fixed-point map x -> G(x) on the tractions of the contact elements: the next iterate is the
// combination of the last few G(x) whose residuals G(x) − x cancel best in the least-squares
// sense. In the adhesion area the sweep is a linear iteration that contracts by only ~0.7 per
// sweep on the Manchester cases; the combination acts like a Krylov method on it.
class AndersonMixer {
 public:
  AndersonMixer(int depth, Eigen::Index size)
      : depth_(depth),
        df_(size, std::max(depth, 1)),
        dg_(size, std::max(depth, 1)),
        gram_(std::max(depth, 1), std::max(depth, 1)),
        f_(size),
        f_previous_(size),
        g_previous_(size) {}

  // x: iterate the sweep started from; g = G(x). Returns false when there is no history to mix
  // with (then g itself is the next iterate); otherwise writes the mixed iterate into `next`.
  bool Mix(const Eigen::VectorXd& x, const Eigen::VectorXd& g, Eigen::VectorXd& next) {
    f_ = g - x;
    const double norm = f_.norm();
    if (has_previous_) {
      if (norm >= previous_norm_) {
        // No progress (the slip/adhesion split moved, or the mix overshot): start afresh from
        // the plain sweep, which converges on its own.
        count_ = 0;
      } else {
        // The differences go into a ring of depth_ columns; the Gram matrix of the ΔF columns
        // is updated by one row, so a sweep costs O(depth·size), not a QR's O(depth²·size).
        const Eigen::Index slot = (first_ + count_) % depth_;
        if (count_ < depth_) {
          ++count_;
        } else {
          first_ = (first_ + 1) % depth_;
        }
        df_.col(slot) = f_ - f_previous_;
        dg_.col(slot) = g - g_previous_;
        for (Eigen::Index c = 0; c < depth_; ++c) {
          if (InUse(c)) gram_(slot, c) = gram_(c, slot) = df_.col(slot).dot(df_.col(c));
        }
      }
    }
    has_previous_ = true;
    previous_norm_ = norm;
    f_previous_ = f_;
    g_previous_ = g;
    if (count_ == 0) return false;
    // γ = argmin |f − ΔF·γ| from the normal equations, regularised at 1e-12 of the largest
    // diagonal: far below the columns' own scale, enough to keep nearly parallel columns from
    // producing huge coefficients.
    Eigen::MatrixXd a(count_, count_);
    Eigen::VectorXd b(count_);
    double largest = 0.0;
    for (Eigen::Index r = 0; r < count_; ++r) {
      const Eigen::Index cr = (first_ + r) % depth_;
      b(r) = df_.col(cr).dot(f_);
      for (Eigen::Index c = 0; c < count_; ++c) a(r, c) = gram_(cr, (first_ + c) % depth_);
      largest = std::max(largest, a(r, r));
    }
    a.diagonal().array() += 1e-12 * largest;
    const Eigen::VectorXd gamma = a.ldlt().solve(b);
    if (!gamma.allFinite()) return false;
    next = g;
    for (Eigen::Index r = 0; r < count_; ++r) next -= gamma(r) * dg_.col((first_ + r) % depth_);
    return true;
  }

 private:
  bool InUse(Eigen::Index slot) const { return ((slot - first_ + depth_) % depth_) < count_; }

  Eigen::Index depth_;
  Eigen::Index first_ = 0, count_ = 0;  // ring of the last count_ differences from first_
  Eigen::MatrixXd df_, dg_, gram_;
  Eigen::VectorXd f_, f_previous_, g_previous_;
  bool has_previous_ = false;
  double previous_norm_ = 0.0;
};

}  // namespace

SteadyRollingOperator::SteadyRollingOperator(const Grid& grid, const CombinedElasticity& material)
    : grid_(grid), material_(material) {
  grid_.Validate();
  // K != 0 is accepted: this operator holds the xx/yy/xy blocks only; the normal–tangential
  // coupling of dissimilar bodies enters through SolveCoupled (coupled_solver.h).
  extended_ = std::make_unique<FftInfluenceOperator>(
      Extended(grid_), material_,
      std::vector<InfluenceComponent>{InfluenceComponent::kXX, InfluenceComponent::kYY,
                                      InfluenceComponent::kXY});
  const Grid ext = Extended(grid_);
  xx_ = std::make_unique<InfluenceCoefficients>(ext, material_, InfluenceComponent::kXX);
  yy_ = std::make_unique<InfluenceCoefficients>(ext, material_, InfluenceComponent::kYY);
  xy_ = std::make_unique<InfluenceCoefficients>(ext, material_, InfluenceComponent::kXY);
}

struct TangentialWorkspace::Scratch {
  ConvolutionWorkspace convolution;
  std::vector<double> px_ext, py_ext, ux_ext, uy_ext, sx_box, sy_box;
  std::vector<int> offsets;                  ///< one row's updates: offsets of their kernels
  std::vector<double> amounts_x, amounts_y;  ///< and their traction changes / δq
  /// A sweep's updates for the rows swept before theirs, applied when the next sweep starts:
  /// the row, and the range of its updates in deferred_offsets/_x/_y.
  std::vector<std::array<int, 3>> deferred_rows;
  std::vector<int> deferred_offsets;
  std::vector<double> deferred_x, deferred_y;
};

TangentialWorkspace::TangentialWorkspace() : scratch_(std::make_unique<Scratch>()) {}
TangentialWorkspace::~TangentialWorkspace() = default;
TangentialWorkspace::TangentialWorkspace(TangentialWorkspace&&) noexcept = default;
TangentialWorkspace& TangentialWorkspace::operator=(TangentialWorkspace&&) noexcept = default;

namespace {

using Scratch = TangentialWorkspace::Scratch;

// Exterior elements downstream of each row's contact that take part in the sweep (see
// SteadyRollingSweep::SweepRow).
constexpr int kSinkElements = 4;

// Two ways to keep the slips of the contact current between sweeps:
//  - fast contraction (full slip: ~0.1 per sweep): each update also corrects the rows already
//    swept, which leaves every slip current, so the next sweep needs no FFT product; a fresh
//    product every kRefreshSweeps sweeps keeps round-off from drifting;
//  - otherwise a fresh product starts every sweep. Before mixing (see below), an update
//    corrects only the rows within kNearRows after its own: the slip responds to a traction
//    through the difference of two influence coefficients, which decays as 1/r², so farther
//    rows take the update from the next product at the cost of no extra sweep in full slip
//    (measured on heavy haul; 4 rows cost z1.194 a sweep). While mixing (slow contraction:
//    partial slip, 0.6–0.7) all rows after it do: there the lag stalls the combination on
//    tall contacts (Manchester at 300 kN: 24 sweeps became 323 with 8 rows).
// The first pays while its direct work, ~3.3 instructions per pair of contact elements,
// costs less than the product (~115 per transform point) and the near rows' pairs together:
// an instruction ratio of ~35, less in time because the large products wait on memory.
// kDirectMargin = 24 (timed): heavy_haul_z1.087 and z1.162 are direct (z1.162's
// tangential solve 8.2 → 5.6 ms against 16), z1.194 takes the product (64 would make it
// direct and cost it 4 ms), the Manchester cases are within ±0.2 ms of 16.
// Mixing starts once a sweep contracts the change by less than kSlowContraction.
constexpr int kRefreshSweeps = 8;
constexpr double kSlowContraction = 0.3;
constexpr double kDirectMargin = 24.0;
constexpr int kNearRows = 8;

double FrictionAt(const TangentialProblem& pb, std::size_t i) {
  return pb.mu.size() == 1 ? pb.mu[0] : pb.mu[i];
}

// u = A·p on the extended grid. The workspace (and the operator's plan and spectra) are made
// at the first product: a solve that keeps its slips current by direct updates may need none.
void ApplyTangential(const FftInfluenceOperator& ext, Scratch& ws) {
  if (!ext.Fits(ws.convolution)) ws.convolution = ext.MakeWorkspace();
  ext.ApplyTangential(ws.px_ext.data(), ws.py_ext.data(), ws.ux_ext.data(), ws.uy_ext.data(),
                      ws.convolution);
}

// The tractions on the extended grid: zero, or the warm start's on the elements in contact
// (the sweep never visits the others). Returns whether they are all zero (then the slips are
// the rigid slips, without a product).
bool StartTractions(const Grid& g, const TangentialProblem& pb, const TangentialOptions& options,
                    const TangentialSolution& sol, Scratch& ws) {
  const int nx = g.nx, ny = g.ny, nxe = nx + 1;
  const std::size_t n = g.size(), ne = static_cast<std::size_t>(nxe) * ny;
  ws.px_ext.assign(ne, 0.0);
  ws.py_ext.assign(ne, 0.0);
  ws.ux_ext.resize(ne);
  ws.uy_ext.resize(ne);
  if (!options.warm_start || sol.px.size() != n || sol.py.size() != n) return true;
  bool tractions_zero = true;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const std::size_t I = g.index(i, j);
      if (pb.pressure[I] > 0.0) {
        ws.px_ext[static_cast<std::size_t>(i) + static_cast<std::size_t>(nxe) * j] = sol.px[I];
        ws.py_ext[static_cast<std::size_t>(i) + static_cast<std::size_t>(nxe) * j] = sol.py[I];
        tractions_zero = tractions_zero && sol.px[I] == 0.0 && sol.py[I] == 0.0;
      }
    }
  }
  return tractions_zero;
}

// No contact or μ = 0: zero tractions; the slip is then the rigid slip.
TangentialSummary SolveWithoutTraction(const TangentialProblem& pb, TangentialSolution& sol) {
  TangentialSummary summary;
  sol.sx = pb.wx;
  sol.sy = pb.wy;
  summary.status =
      std::any_of(pb.pressure.begin(), pb.pressure.end(), [](double p) { return p > 0.0; })
          ? SolverStatus::kConverged
          : SolverStatus::kNoContact;
  for (std::size_t i = 0; i < pb.pressure.size(); ++i) {
    if (pb.pressure[i] > 0.0) sol.state[i] = ElementState::kSlip;
  }
  sol.fx = sol.fy = sol.mz = 0.0;
  sol.n_adhesion = 0;
  sol.n_slip =
      static_cast<int>(std::count(sol.state.begin(), sol.state.end(), ElementState::kSlip));
  return summary;
}

// Where the sweep works: the bounding box of the contact (plus the column upstream of it,
// where u' is read), each row's contact range, and the elements in contact in sweep order (the
// unknowns of the acceleration; the others stay zero) with their traction bounds.
struct ContactBox {
  int i0, i1, j0, j1;
  std::vector<int> row_lo, row_hi;
  std::vector<std::size_t> contact;  ///< extended-grid indices
  std::vector<double> bound;

  int lo(int j) const { return row_lo[j - j0]; }
  int hi(int j) const { return row_hi[j - j0]; }
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(i - i0) + static_cast<std::size_t>(i1 - i0 + 1) * (j - j0);
  }
};

ContactBox FindContactBox(const Grid& g, const TangentialProblem& pb) {
  const int nx = g.nx, ny = g.ny, nxe = nx + 1;
  ContactBox box{nx, -1, ny, -1, {}, {}, {}, {}};
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      if (pb.pressure[g.index(i, j)] > 0.0) {
        box.i0 = std::min(box.i0, i);
        box.i1 = std::max(box.i1, i + 1);
        box.j0 = std::min(box.j0, j);
        box.j1 = std::max(box.j1, j);
      }
    }
  }
  box.row_lo.assign(box.j1 - box.j0 + 1, nx);
  box.row_hi.assign(box.j1 - box.j0 + 1, -1);
  for (int j = box.j0; j <= box.j1; ++j) {
    for (int i = 0; i < nx; ++i) {
      if (pb.pressure[g.index(i, j)] > 0.0) {
        box.row_lo[j - box.j0] = std::min(box.row_lo[j - box.j0], i);
        box.row_hi[j - box.j0] = std::max(box.row_hi[j - box.j0], i);
      }
    }
  }
  for (int j = box.j0; j <= box.j1; ++j) {
    for (int i = box.lo(j); i <= box.hi(j); ++i) {
      const std::size_t I = g.index(i, j);
      if (pb.pressure[I] > 0.0) {
        box.contact.push_back(static_cast<std::size_t>(i) + static_cast<std::size_t>(nxe) * j);
        box.bound.push_back(FrictionAt(pb, I) * pb.pressure[I]);
      }
    }
  }
  return box;
}

// Whether keeping every slip current by direct updates pays (see kDirectMargin).
bool DirectUpdatesPay(const ContactBox& box, const FftInfluenceOperator& ext,
                      const TangentialOptions& options) {
  const double n_contact = static_cast<double>(box.contact.size());
  double near_pairs = 0.0;  // pairs of contact-range elements in rows at most kNearRows apart
  for (int j = box.j0; j <= box.j1; ++j) {
    const double len = std::max(0, box.hi(j) - box.lo(j) + 1);
    for (int l = j + 1; l <= std::min(box.j1, j + kNearRows); ++l) {
      near_pairs += len * std::max(0, box.hi(l) - box.lo(l) + 1);
    }
  }
  return options.direct_refresh && n_contact * n_contact - near_pairs <
                                       kDirectMargin * static_cast<double>(ext.transform_points());
}

// The Gauss–Seidel sweeps of SolveTangential (see tangential_solver.h) over the contact box.
class SteadyRollingSweep {
 public:
  SteadyRollingSweep(const SteadyRollingOperator& op, const TangentialProblem& pb,
                     const ContactBox& box, Scratch& ws, TangentialSolution& sol)
      : op_(op), g_(op.grid()), pb_(pb), box_(box), ws_(ws), sol_(sol), inv_dq_(1.0 / g_.dx) {
    ws_.sx_box.resize(static_cast<std::size_t>(box.i1 - box.i0 + 1) * (box.j1 - box.j0 + 1));
    ws_.sy_box.resize(ws_.sx_box.size());
  }

  // The slips of the box from a fresh product, or (a cold start, no tractions yet, so no
  // displacements) the rigid ones.
  void RefreshSlips(bool tractions_zero) {
    if (!tractions_zero) ApplyTangential(op_.extended(), ws_);
    for (int l = box_.j0; l <= box_.j1; ++l) {
      for (int k = box_.i0; k < box_.i1; ++k) {
        const std::size_t E = Ext(k, l);
        const std::size_t I = g_.index(k, l);
        double ex = 0.0, ey = 0.0;  // elastic part of the slip
        if (!tractions_zero) {
          ex = (ws_.ux_ext[E] - ws_.ux_ext[E + 1]) * inv_dq_;
          ey = (ws_.uy_ext[E] - ws_.uy_ext[E + 1]) * inv_dq_;
        }
        ws_.sx_box[box_.index(k, l)] = pb_.wx[I] + ex;
        ws_.sy_box[box_.index(k, l)] = pb_.wy[I] + ey;
      }
    }
  }

  // The last sweep's updates of the rows it had already swept (see Sweep), in its order.
  void ApplyDeferredUpdates() {
    for (const auto& [j, begin, end] : ws_.deferred_rows) {
      for (int l = box_.j0; l < j; ++l) {
        const int lo = box_.lo(l), hi = box_.hi(l);
        if (hi < lo) continue;
        const int dj = l - j;
        AddRowSlipTerms(Xx(lo, dj), Yy(lo, dj), Xy(lo, dj), ws_.deferred_offsets.data() + begin,
                        ws_.deferred_x.data() + begin, ws_.deferred_y.data() + begin, end - begin,
                        hi - lo + 1, ws_.sx_box.data() + box_.index(lo, l),
                        ws_.sy_box.data() + box_.index(lo, l));
      }
    }
  }

  // One sweep over the rows of the box; returns the largest traction change. `update_all`:
  // every update corrects every row (those already swept when the next sweep starts), so the
  // slips stay current; `mixing`: the rows after the update's all take it.
  double Sweep(bool update_all, bool mixing) {
    ws_.deferred_rows.clear();
    ws_.deferred_offsets.clear();
    ws_.deferred_x.clear();
    ws_.deferred_y.clear();
    double max_change = 0.0;
    for (int j = box_.j0; j <= box_.j1; ++j) {
      const int updates = SweepRow(j, &max_change);
      if (updates > 0) UpdateOtherRows(j, updates, update_all, mixing);
    }
    return max_change;
  }

 private:
  // Coefficient rows (one dj, contiguous in di) of the three kernels.
  const double* Xx(int di, int dj) const { return op_.xx().origin() + di + op_.xx().stride() * dj; }
  const double* Yy(int di, int dj) const { return op_.yy().origin() + di + op_.yy().stride() * dj; }
  const double* Xy(int di, int dj) const { return op_.xy().origin() + di + op_.xy().stride() * dj; }
  std::size_t Ext(int i, int j) const {
    return static_cast<std::size_t>(i) + static_cast<std::size_t>(g_.nx + 1) * j;
  }

  // Elements b..hi of row j: its contact range and a few exterior elements downstream of it.
  // Shifts that reach those exterior elements are undone when they are solved (p = 0); letting
  // them absorb the shifts converges 2–3x faster on a Carter strip than ending the cumulative
  // sum at the row's last contact element, while each one costs an update of the slip field,
  // so only kSinkElements of them are used. Leaves the row's updates for the other rows in
  // ws.offsets / amounts_x / amounts_y and returns their number.
  int SweepRow(int j, double* max_change) {
    const InfluenceCoefficients& axx = op_.xx();
    const InfluenceCoefficients& ayy = op_.yy();
    const int b = std::max(box_.i0, box_.lo(j) - kSinkElements);
    double row_change_x = 0.0, row_change_y = 0.0;
    ws_.offsets.clear();
    ws_.amounts_x.clear();
    ws_.amounts_y.clear();
    for (int i = box_.hi(j); i >= b; --i) {
      const std::size_t I = g_.index(i, j);
      const std::size_t E = Ext(i, j);
      // The update shifts the tractions of elements b..i of this row alike (a change of the
      // difference d_i = p_i − p_(i+1)); the elements downstream are solved after this one.
      // The shifts of the updates so far (row_change) are added to an element when it is
      // reached, which leaves its traction final (later updates shift elements below it).
      const double old_px = ws_.px_ext[E] + row_change_x, old_py = ws_.py_ext[E] + row_change_y;
      // Its effect on the own slip: (A(0) − A(i − b + 1))/δq.
      const double kx = (axx.at(0, 0) - axx.at(i - b + 1, 0)) * inv_dq_;
      const double ky = (ayy.at(0, 0) - ayy.at(i - b + 1, 0)) * inv_dq_;
      double new_px = 0.0, new_py = 0.0;
      if (pb_.pressure[I] > 0.0) {
        const double sx = ws_.sx_box[box_.index(i, j)], sy = ws_.sy_box[box_.index(i, j)];
        const LocalResult r = SolveLocal(sx - kx * old_px, sy - ky * old_py, kx, ky,
                                         FrictionAt(pb_, I) * pb_.pressure[I]);
        new_px = r.px;
        new_py = r.py;
        sol_.state[I] = r.slip ? ElementState::kSlip : ElementState::kAdhesion;
      }
      const double dpx = new_px - old_px, dpy = new_py - old_py;
      ws_.px_ext[E] = new_px;
      ws_.py_ext[E] = new_py;
      if (dpx == 0.0 && dpy == 0.0) continue;
      *max_change = std::max(*max_change, Magnitude(dpx, dpy));
      // Slip change at (k, l): Σ_(m=b..i) [A(k−m) − A(k+1−m)]·Δ/δq = [A(k−i) − A(k−b+1)]·Δ/δq.
      // Only the slip of elements in contact is read before the next FFT refresh, so only the
      // contact range of each row is corrected (its coefficients are contiguous), and only in
      // this row and the rows after it: rows already swept are not read again before the
      // refresh. This row needs both terms at once (its next element reads them); for later
      // rows the A(k−b+1) term of every update of this row is one kernel times the sum of the
      // changes, added once when the row is done.
      row_change_x += dpx;
      row_change_y += dpy;
      const double ax = dpx * inv_dq_, ay = dpy * inv_dq_;
      const int lo = box_.lo(j), hi = box_.hi(j);
      const int d0 = lo - i, d1 = lo - b + 1;
      AddRowSlipChange(Xx(d0, 0), Xx(d1, 0), Yy(d0, 0), Yy(d1, 0), Xy(d0, 0), Xy(d1, 0), ax, ay,
                       hi - lo + 1, ws_.sx_box.data() + box_.index(lo, j),
                       ws_.sy_box.data() + box_.index(lo, j));
      // Other rows take the update when the row is done: offset i of the A(k − i) term,
      // relative to the first element of the target row's contact range.
      ws_.offsets.push_back(-i);
      ws_.amounts_x.push_back(ax);
      ws_.amounts_y.push_back(ay);
    }
    if (row_change_x != 0.0 || row_change_y != 0.0) {
      // The A(k − b + 1) term of all of the row's updates at once.
      ws_.offsets.push_back(-(b - 1));
      ws_.amounts_x.push_back(-row_change_x * inv_dq_);
      ws_.amounts_y.push_back(-row_change_y * inv_dq_);
    }
    return static_cast<int>(ws_.offsets.size());
  }

  // Row j's updates for the rows after it (all, or the kNearRows next), and with every slip
  // kept current, deferred for the rows already swept until the next sweep starts (the same
  // additions in the same order): a sweep that converges, or one followed by a fresh product,
  // never needs them.
  void UpdateOtherRows(int j, int updates, bool update_all, bool mixing) {
    if (update_all && j > box_.j0) {
      const int begin = static_cast<int>(ws_.deferred_offsets.size());
      ws_.deferred_offsets.insert(ws_.deferred_offsets.end(), ws_.offsets.begin(),
                                  ws_.offsets.end());
      ws_.deferred_x.insert(ws_.deferred_x.end(), ws_.amounts_x.begin(), ws_.amounts_x.end());
      ws_.deferred_y.insert(ws_.deferred_y.end(), ws_.amounts_y.begin(), ws_.amounts_y.end());
      ws_.deferred_rows.push_back({j, begin, begin + updates});
    }
    const int last = update_all || mixing ? box_.j1 : std::min(box_.j1, j + kNearRows);
    for (int l = j + 1; l <= last; ++l) {
      const int lo = box_.lo(l), hi = box_.hi(l);
      if (hi < lo) continue;
      const int dj = l - j;
      AddRowSlipTerms(Xx(lo, dj), Yy(lo, dj), Xy(lo, dj), ws_.offsets.data(), ws_.amounts_x.data(),
                      ws_.amounts_y.data(), updates, hi - lo + 1,
                      ws_.sx_box.data() + box_.index(lo, l), ws_.sy_box.data() + box_.index(lo, l));
    }
  }

  const SteadyRollingOperator& op_;
  const Grid& g_;
  const TangentialProblem& pb_;
  const ContactBox& box_;
  Scratch& ws_;
  TangentialSolution& sol_;
  double inv_dq_;  ///< Local stiffness: s_I changes with p_I through u_I and u'_I = u_(I+1).
};

// The tractions of the contact elements as the acceleration's unknowns, (px, py) per element.
void GatherTractions(const ContactBox& box, const Scratch& ws, Eigen::VectorXd& v) {
  for (std::size_t c = 0; c < box.contact.size(); ++c) {
    v(2 * c) = ws.px_ext[box.contact[c]];
    v(2 * c + 1) = ws.py_ext[box.contact[c]];
  }
}

// The mixed tractions, brought back inside the Coulomb bound where the combination left it;
// the next sweep starts from them and its own change decides convergence, so the result is a
// plain sweep's.
void ScatterBoundedTractions(const ContactBox& box, const Eigen::VectorXd& v, Scratch& ws) {
  for (std::size_t c = 0; c < box.contact.size(); ++c) {
    double px = v(2 * c), py = v(2 * c + 1);
    const double magnitude = Magnitude(px, py);
    if (magnitude > box.bound[c]) {
      px *= box.bound[c] / magnitude;
      py *= box.bound[c] / magnitude;
    }
    ws.px_ext[box.contact[c]] = px;
    ws.py_ext[box.contact[c]] = py;
  }
}

// Tractions, slips (from a fresh product, or as the last sweep saw them) and the totals.
void FinishTangential(const SteadyRollingOperator& op, const TangentialProblem& pb,
                      const TangentialOptions& options, const ContactBox& box,
                      const TangentialSummary& summary, Scratch& ws, TangentialSolution& sol) {
  const Grid& g = op.grid();
  const std::size_t nxe = static_cast<std::size_t>(g.nx) + 1;
  const double inv_dq = 1.0 / g.dx;
  if (options.final_slip) ApplyTangential(op.extended(), ws);
  const double area = g.element_area();
  sol.fx = sol.fy = sol.mz = 0.0;
  sol.n_adhesion = sol.n_slip = 0;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t I = g.index(i, j);
      const std::size_t E = static_cast<std::size_t>(i) + nxe * j;
      sol.px[I] = ws.px_ext[E];
      sol.py[I] = ws.py_ext[E];
      if (options.final_slip) {
        sol.sx[I] = pb.wx[I] + (ws.ux_ext[E] - ws.ux_ext[E + 1]) * inv_dq;
        sol.sy[I] = pb.wy[I] + (ws.uy_ext[E] - ws.uy_ext[E + 1]) * inv_dq;
      } else if (summary.iterations > 0 && j >= box.j0 && j <= box.j1 && i >= box.i0 &&
                 i < box.i1) {
        sol.sx[I] = ws.sx_box[box.index(i, j)];
        sol.sy[I] = ws.sy_box[box.index(i, j)];
      } else {
        sol.sx[I] = pb.wx[I];
        sol.sy[I] = pb.wy[I];
      }
      sol.fx += sol.px[I] * area;
      sol.fy += sol.py[I] * area;
      sol.mz += (g.x(i) * sol.py[I] - g.y(j) * sol.px[I]) * area;
      sol.n_adhesion += sol.state[I] == ElementState::kAdhesion;
      sol.n_slip += sol.state[I] == ElementState::kSlip;
    }
  }
}

}  // namespace

TangentialSummary SolveTangential(const SteadyRollingOperator& op, const TangentialProblem& pb,
                                  const TangentialOptions& options, TangentialWorkspace& workspace,
                                  TangentialSolution& sol) {
  Validate(op, pb);
  Scratch& ws = workspace.scratch();
  const std::size_t n = op.grid().size();
  bool tractions_zero = StartTractions(op.grid(), pb, options, sol, ws);
  sol.px.assign(n, 0.0);
  sol.py.assign(n, 0.0);
  sol.sx.assign(n, 0.0);
  sol.sy.assign(n, 0.0);
  sol.state.assign(n, ElementState::kExterior);
  double max_bound = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    max_bound = std::max(max_bound, FrictionAt(pb, i) * pb.pressure[i]);
  }
  if (max_bound == 0.0) return SolveWithoutTraction(pb, sol);

  const ContactBox box = FindContactBox(op.grid(), pb);
  const Eigen::Index n_unknowns = 2 * static_cast<Eigen::Index>(box.contact.size());
  Eigen::VectorXd x_start(n_unknowns), x_swept(n_unknowns), x_next(n_unknowns);
  AndersonMixer mixer(options.acceleration_depth, n_unknowns);
  const bool direct_pays = DirectUpdatesPay(box, op.extended(), options);
  SteadyRollingSweep sweep(op, pb, box, ws, sol);
  TangentialSummary summary;
  bool slips_current = false;
  bool mixing = false;
  int since_refresh = 0;
  double previous_residual = 0.0;
  for (int it = 1; it <= options.max_iterations; ++it) {
    if (options.acceleration_depth > 0) GatherTractions(box, ws, x_start);
    if (tractions_zero || !slips_current || since_refresh >= kRefreshSweeps) {
      sweep.RefreshSlips(tractions_zero);
      tractions_zero = false;
      since_refresh = 0;
    } else {
      sweep.ApplyDeferredUpdates();
    }
    ++since_refresh;
    const bool update_all = !mixing && direct_pays;
    const double max_change = sweep.Sweep(update_all, mixing);
    summary.iterations = it;
    summary.residual = max_change / max_bound;
    if (summary.residual < options.tolerance) {
      summary.status = SolverStatus::kConverged;
      break;
    }
    slips_current = update_all;
    if (options.acceleration_depth > 0 && !mixing && it > 1 &&
        summary.residual > kSlowContraction * previous_residual) {
      mixing = true;
    }
    previous_residual = summary.residual;
    if (options.acceleration_depth == 0) continue;
    // The history is kept from the first sweep, so that mixing, once on, combines at once.
    GatherTractions(box, ws, x_swept);
    if (mixer.Mix(x_start, x_swept, x_next) && mixing) {
      slips_current = false;
      ScatterBoundedTractions(box, x_next, ws);
    }
  }
  FinishTangential(op, pb, options, box, summary, ws, sol);
  return summary;
}

}  // namespace wrc
