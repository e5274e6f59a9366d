#include "wrc/core/normal_solver.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/common/pcg.h"
#include "core/common/portable_simd.h"

namespace wrc {

struct NormalWorkspace::Scratch {
  ConvolutionWorkspace convolution;
  std::vector<double> gap, direction, response, previous, displacement;
  std::vector<double> residual;        ///< the gap on the contact, zero elsewhere
  std::vector<double> preconditioned;  ///< the residual after the preconditioner
  std::vector<double> column_sums;     ///< one grid row (+2): residual above + below
  /// The elements that can carry pressure, one [begin, end) stretch per grid row.
  std::vector<std::pair<std::size_t, std::size_t>> segments;
  /// The deflated phase: the contact set, A·Z on it (column-major), the set as a 0/1 mask of
  /// the grid, and the vectors of its conjugate gradients (on the set).
  std::vector<std::size_t> contact;
  std::vector<double> coarse_response, mask;
  linear::PcgScratch pcg;
  std::vector<std::size_t> corrected;  ///< elements clipped or re-activated in one step
  std::vector<double> correction;      ///< their pressure minus the unclipped step
};

NormalWorkspace::NormalWorkspace() : scratch_(std::make_unique<Scratch>()) {}
NormalWorkspace::~NormalWorkspace() = default;
NormalWorkspace::NormalWorkspace(NormalWorkspace&&) noexcept = default;
NormalWorkspace& NormalWorkspace::operator=(NormalWorkspace&&) noexcept = default;

namespace {

using Scratch = NormalWorkspace::Scratch;

void Validate(const FftInfluenceOperator& op, const std::vector<double>& h,
              const NormalLoad& load) {
  if (!op.has(InfluenceComponent::kNN)) {
    throw std::invalid_argument("normal solve needs the kNN influence component");
  }
  if (h.size() != op.grid().size()) {
    throw std::invalid_argument("undeformed distance has " + std::to_string(h.size()) +
                                " values for a grid of " + std::to_string(op.grid().size()));
  }
  for (double v : h) {
    if (!std::isfinite(v)) throw std::invalid_argument("undeformed distance is not finite");
  }
  if (!std::isfinite(load.value)) throw std::invalid_argument("normal load is not finite");
  if (load.kind == NormalLoad::Kind::kForce && load.value < 0.0) {
    throw std::invalid_argument("prescribed normal force " + std::to_string(load.value) +
                                " N is negative");
  }
}

// `displacement`: A·p when the caller has it at hand (then no product is made), or nullptr.
void Finish(const FftInfluenceOperator& op, const std::vector<double>& h, double approach,
            const std::vector<double>* displacement, Scratch& ws, NormalSolution& sol) {
  const std::size_t n = h.size();
  if (!displacement) {
    op.Apply(InfluenceComponent::kNN, sol.pressure.data(), ws.response.data(), ws.convolution);
    displacement = &ws.response;
  }
  const std::vector<double>& u = *displacement;
  sol.deformed.resize(n);
  sol.approach = approach;
  double sum = 0.0, pmax = 0.0;
  int n_contact = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sol.deformed[i] = h[i] - approach + u[i];
    sum += sol.pressure[i];
    pmax = std::max(pmax, sol.pressure[i]);
    n_contact += sol.pressure[i] > 0.0;
  }
  sol.force = sum * op.grid().element_area();
  sol.pmax = pmax;
  sol.n_contact = n_contact;
}

// One row's stretch of elements that can carry pressure: [begin, end) in grid order.
using Segment = std::pair<std::size_t, std::size_t>;

// z = M·r on the elements in contact (p > 0) of the segments, for the 3 × 3 stencil M (centre
// weight 1) and a residual r that is zero off the contact. `sums`: nx + 2 values of scratch.
inline void ApplyLocalInverse(const LocalInverseStencil& m, const Grid& grid,
                              const std::vector<Segment>& segments, const double* r,
                              const double* p, double* sums, double* z) {
  const int nx = grid.nx, ny = grid.ny;
  // sums[i + 1] = r above + r below at column i; sums[0] and sums[nx + 1] stay zero, as does
  // the grid's outside.
  sums[0] = sums[nx + 1] = 0.0;
  double* vertical = sums + 1;
  for (const auto& [begin, end] : segments) {
    const int j = static_cast<int>(begin / static_cast<std::size_t>(nx));
    const std::size_t row = static_cast<std::size_t>(j) * nx;
    const int lo = static_cast<int>(begin - row), hi = static_cast<int>(end - row);
    const double* mid = r + row;
    const double* below = j > 0 ? mid - nx : nullptr;
    const double* above = j + 1 < ny ? mid + nx : nullptr;
    // The stencil reads columns lo − 1 … hi: set here, or the zero sentinels at −1 and nx.
    const int from = std::max(lo - 1, 0), to = std::min(hi + 1, nx);
    if (below && above) {
      for (int i = from; i < to; ++i) vertical[i] = below[i] + above[i];
    } else if (below || above) {
      const double* only = below ? below : above;
      std::copy(only + from, only + to, vertical + from);
    } else {
      std::fill(vertical + from, vertical + to, 0.0);
    }
    double* out = z + row;
    const double* in_contact = p + row;
    auto at = [&](int i) {
      const double left = i > 0 ? mid[i - 1] : 0.0, right = i + 1 < nx ? mid[i + 1] : 0.0;
      return mid[i] + m.x * (left + right) + m.y * vertical[i] +
             m.diagonal * (vertical[i - 1] + vertical[i + 1]);
    };
    const int inner_lo = std::max(lo, 1), inner_hi = std::min(hi, nx - 1);
    if (lo == 0) out[0] = in_contact[0] > 0.0 ? at(0) : 0.0;
    for (int i = inner_lo; i < inner_hi; ++i) {
      const double v = mid[i] + m.x * (mid[i - 1] + mid[i + 1]) + m.y * vertical[i] +
                       m.diagonal * (vertical[i - 1] + vertical[i + 1]);
      out[i] = in_contact[i] > 0.0 ? v : 0.0;
    }
    if (hi == nx && nx > 1) out[nx - 1] = in_contact[nx - 1] > 0.0 ? at(nx - 1) : 0.0;
  }
}

// u += amount · (column k of A) on the whole grid: the displacement of a pressure change at one
// element, summed directly from the influence coefficients.
void AddColumn(const InfluenceCoefficients& columns, const Grid& grid, std::size_t k, double amount,
               double* u) {
  const int ik = static_cast<int>(k % static_cast<std::size_t>(grid.nx));
  const int jk = static_cast<int>(k / static_cast<std::size_t>(grid.nx));
  for (int j = 0; j < grid.ny; ++j) {
    const double* c = columns.origin() + columns.stride() * (j - jk) - ik;
    double* row = u + static_cast<std::size_t>(j) * grid.nx;
    for (int i = 0; i < grid.nx; ++i) row[i] += amount * c[i];
  }
}

// Corrections of one step above this many elements are cheaper by FFT than column by column (a
// product costs 25–40 ns per element of the box, a column ~0.5).
constexpr std::size_t kMaxDirectColumns = 48;

// Row prefix sums of the coefficients: prefix[dj][d + nx] = Σ_{d' <= d} A(d', dj), with
// prefix[dj][0] = 0 for d = −nx, so that a run of sources lo..hi adds P(i − lo) − P(i − hi − 1)
// at column i of a row dj away. Rows of 2·nx values, dj from −(ny − 1).
std::vector<double> RowPrefixSums(const InfluenceCoefficients& columns, int nx, int ny) {
  const std::size_t width = 2 * static_cast<std::size_t>(nx);
  std::vector<double> prefix(width * (2 * static_cast<std::size_t>(ny) - 1));
  for (int dj = 1 - ny; dj < ny; ++dj) {
    double* row = prefix.data() + width * static_cast<std::size_t>(dj + ny - 1);
    const double* a = columns.origin() + columns.stride() * dj;
    row[0] = 0.0;
    for (int d = 1 - nx; d < nx; ++d) row[d + nx] = row[d + nx - 1] + a[d];
  }
  return prefix;
}

// A contact set C (grid indices in grid order) as runs of consecutive elements per row, and
// cut into the blocks of a block × block tiling of the grid.
struct ContactBlocks {
  struct Run {
    int row, lo, hi;    // columns lo..hi (inclusive) of one grid row
    std::size_t first;  // index in C of column lo (for block runs: the block)
  };
  std::vector<Run> runs, block_runs;
  std::vector<int> block;  // block of each element of C
  int count = 0;
};

ContactBlocks GroupIntoBlocks(const std::vector<std::size_t>& contact, int nx, int ny,
                              int block_size) {
  ContactBlocks b;
  for (std::size_t c = 0; c < contact.size(); ++c) {
    const int row = static_cast<int>(contact[c] / nx), col = static_cast<int>(contact[c] % nx);
    if (b.runs.empty() || b.runs.back().row != row || b.runs.back().hi + 1 != col) {
      b.runs.push_back({row, col, col, c});
    } else {
      b.runs.back().hi = col;
    }
  }
  const int blocks_x = (nx + block_size - 1) / block_size;
  std::vector<int> id_of_tile(
      static_cast<std::size_t>(blocks_x) * ((ny + block_size - 1) / block_size), -1);
  b.block.resize(contact.size());
  for (const ContactBlocks::Run& run : b.runs) {
    for (int lo = run.lo; lo <= run.hi;) {
      const int hi = std::min(run.hi, (lo / block_size + 1) * block_size - 1);
      int& id =
          id_of_tile[static_cast<std::size_t>(run.row / block_size) * blocks_x + lo / block_size];
      if (id < 0) id = b.count++;
      for (int col = lo; col <= hi; ++col) b.block[run.first + (col - run.lo)] = id;
      b.block_runs.push_back({run.row, lo, hi, static_cast<std::size_t>(id)});
      lo = hi + 1;
    }
  }
  return b;
}

// A·Z on C (nc × blocks, column-major) from the row prefix sums: each block's response is the
// sum of its row runs', two prefix values per run and element of C.
void CoarseResponse(const ContactBlocks& b, const std::vector<double>& prefix, int nx, int ny,
                    std::vector<double>& az) {
  const std::size_t nc = b.block.size(), width = 2 * static_cast<std::size_t>(nx);
  az.assign(nc * static_cast<std::size_t>(b.count), 0.0);
  for (const ContactBlocks::Run& source : b.block_runs) {
    double* column = az.data() + source.first * nc;
    for (const ContactBlocks::Run& target : b.runs) {
      const double* p =
          prefix.data() + width * static_cast<std::size_t>(target.row - source.row + ny - 1) + nx;
      double* out = column + target.first - target.lo;
      for (int i = target.lo; i <= target.hi; ++i)
        out[i] += p[i - source.lo] - p[i - source.hi - 1];
    }
  }
}

// out[t] += Σ_k K(lo_t + t − lo_s − k)·d[k] for the target run's t < target_count and the source
// run's k < source_count, where `kernel` points at the coefficient row between the two runs'
// grid rows and offset 0 of that row: the response of one run of the contact set to another.
// Built for AVX2 as well as the baseline ISA like the grid passes (no FMA in either).
WRC_CLONE_FOR_AVX2
void AddRunResponse(const double* kernel, const double* __restrict d, int source_lo,
                    int source_count, int target_lo, int target_count, double* __restrict out) {
  const double* base = kernel + (target_lo - source_lo);  // base[t − k] = K(...)
  int t = 0;
#if defined(__GNUC__)
  // Blocks of responses stay in registers while every source adds to them (as in the
  // tangential solver's AddRowSlipTerms).
  typedef double Lanes __attribute__((vector_size(32)));
  for (; t + 16 <= target_count; t += 16) {
    Lanes a0, a1, a2, a3;
    std::memcpy(&a0, out + t, sizeof a0);
    std::memcpy(&a1, out + t + 4, sizeof a1);
    std::memcpy(&a2, out + t + 8, sizeof a2);
    std::memcpy(&a3, out + t + 12, sizeof a3);
    for (int k = 0; k < source_count; ++k) {
      const double* c = base + t - k;
      Lanes c0, c1, c2, c3;
      std::memcpy(&c0, c, sizeof c0);
      std::memcpy(&c1, c + 4, sizeof c1);
      std::memcpy(&c2, c + 8, sizeof c2);
      std::memcpy(&c3, c + 12, sizeof c3);
      a0 += c0 * d[k];
      a1 += c1 * d[k];
      a2 += c2 * d[k];
      a3 += c3 * d[k];
    }
    std::memcpy(out + t, &a0, sizeof a0);
    std::memcpy(out + t + 4, &a1, sizeof a1);
    std::memcpy(out + t + 8, &a2, sizeof a2);
    std::memcpy(out + t + 12, &a3, sizeof a3);
  }
  for (; t + 8 <= target_count; t += 8) {
    Lanes a0, a1;
    std::memcpy(&a0, out + t, sizeof a0);
    std::memcpy(&a1, out + t + 4, sizeof a1);
    for (int k = 0; k < source_count; ++k) {
      Lanes c0, c1;
      std::memcpy(&c0, base + t - k, sizeof c0);
      std::memcpy(&c1, base + t - k + 4, sizeof c1);
      a0 += c0 * d[k];
      a1 += c1 * d[k];
    }
    std::memcpy(out + t, &a0, sizeof a0);
    std::memcpy(out + t + 4, &a1, sizeof a1);
  }
  for (; t + 4 <= target_count; t += 4) {
    Lanes a;
    std::memcpy(&a, out + t, sizeof a);
    for (int k = 0; k < source_count; ++k) {
      Lanes c;
      std::memcpy(&c, base + t - k, sizeof c);
      a += c * d[k];
    }
    std::memcpy(out + t, &a, sizeof a);
  }
#endif
  for (; t < target_count; ++t) {
    double a = out[t];
    for (int k = 0; k < source_count; ++k) a += base[t - k] * d[k];
    out[t] = a;
  }
}

// A_CC·d on the contact set C (runs of `b`, values in C's order) by direct summation:
// |C|² products, against an FFT product's ~60 instructions per point of the padded grid.
void ContactResponse(const ContactBlocks& b, const InfluenceCoefficients& columns,
                     const std::vector<double>& d, std::vector<double>& out) {
  std::fill(out.begin(), out.end(), 0.0);
  for (const ContactBlocks::Run& source : b.runs) {
    for (const ContactBlocks::Run& target : b.runs) {
      AddRunResponse(columns.origin() + columns.stride() * (target.row - source.row),
                     d.data() + source.first, source.lo, source.hi - source.lo + 1, target.lo,
                     target.hi - target.lo + 1, out.data() + target.first);
    }
  }
}

struct DeflationOutcome {
  bool converged = false;
  int iterations = 0;
  double residual = 0.0;
};

// Blocks of 3 and 4 elements take as many iterations as 6, and 8 one more; 6 has the fewest
// blocks to set up for that (measured on heavy haul).
constexpr int kDeflationBlock = 6;
constexpr int kDeflationRounds = 3;

// C in grid order: the elements of the segments that ws.mask marks.
void CollectContactSet(Scratch& ws) {
  ws.contact.clear();
  for (const auto& [begin, end] : ws.segments) {
    for (std::size_t i = begin; i < end; ++i) {
      if (ws.mask[i] > 0.0) ws.contact.push_back(i);
    }
  }
}

// The deflation space of one round: C's blocks, A·Z on C (ws.coarse_response) and the
// Cholesky factor of E = Zᵀ·A·Z, symmetric positive definite as A_CC is (symmetrised against
// round-off).
struct CoarseSpace {
  ContactBlocks blocks;
  Eigen::LLT<Eigen::MatrixXd> factor;
  Eigen::VectorXd vector;  ///< scratch, one value per block
};

bool BuildCoarseSpace(const std::vector<double>& prefix, int nx, int ny, Scratch& ws,
                      CoarseSpace& space) {
  space.blocks = GroupIntoBlocks(ws.contact, nx, ny, kDeflationBlock);
  const std::vector<int>& block = space.blocks.block;
  const int m = space.blocks.count;
  const std::size_t nc = ws.contact.size();
  CoarseResponse(space.blocks, prefix, nx, ny, ws.coarse_response);
  Eigen::MatrixXd coarse = Eigen::MatrixXd::Zero(m, m);
  const Eigen::Map<const Eigen::MatrixXd> az(ws.coarse_response.data(),
                                             static_cast<Eigen::Index>(nc), m);
  for (std::size_t c = 0; c < nc; ++c) coarse.row(block[c]) += az.row(static_cast<Eigen::Index>(c));
  coarse = 0.5 * (coarse + coarse.transpose()).eval();
  space.factor.compute(coarse);
  space.vector.resize(m);
  return space.factor.info() == Eigen::Success;
}

// A_CC for the conjugate gradients on C, preconditioned by the local inverse with C as the
// contact mask and deflated by the A-orthogonal projection off the blocks.
//
// The products of this phase only need A·d on C. Summed directly they cost |C|² pairs of
// elements, against the FFT's product over the padded grid, which also carries the
// displacement off C; that is only read after the round (complementarity), so the direct way
// refreshes it there with one product. With one refresh per round of ~5 products the
// break-even is 0.8 of a product: heavy_haul_z1.087 (749 elements in a 26 400-point transform,
// 0.63 M instructions against 1.5 M), z1.162 (normal solve −3.5 % in time) and small patches go
// direct, the Manchester patches of ~500 elements and z1.194 keep the FFT. kDirectPairCost:
// instructions per pair of AddRunResponse (measured).
class ContactSetOperator {
 public:
  static constexpr double kDirectPairCost = 1.1;

  ContactSetOperator(const FftInfluenceOperator& op, const InfluenceCoefficients& columns,
                     const LocalInverseStencil* stencil, CoarseSpace& space, Scratch& ws)
      : op_(op),
        columns_(columns),
        stencil_(stencil),
        space_(space),
        ws_(ws),
        nc_(ws.contact.size()),
        direct_(kDirectPairCost * static_cast<double>(nc_) * static_cast<double>(nc_) <
                0.8 * op.ProductCost()) {}

  bool direct() const { return direct_; }

  // w = A·d on C; with the FFT the whole response stays in ws.response for Stepped.
  void Apply(const std::vector<double>& d, std::vector<double>& w) {
    if (direct_) {
      ContactResponse(space_.blocks, columns_, d, w);
      return;
    }
    for (std::size_t c = 0; c < nc_; ++c) ws_.direction[ws_.contact[c]] = d[c];
    op_.Apply(InfluenceComponent::kNN, ws_.direction.data(), ws_.response.data(), ws_.convolution);
    for (std::size_t c = 0; c < nc_; ++c) w[c] = ws_.response[ws_.contact[c]];
  }

  void Precondition(const std::vector<double>& r, std::vector<double>& z) {
    if (!stencil_) {
      z = r;
    } else {
      for (std::size_t c = 0; c < nc_; ++c) ws_.residual[ws_.contact[c]] = r[c];
      ApplyLocalInverse(*stencil_, op_.grid(), ws_.segments, ws_.residual.data(), ws_.mask.data(),
                        ws_.column_sums.data(), ws_.preconditioned.data());
      for (std::size_t c = 0; c < nc_; ++c) z[c] = ws_.preconditioned[ws_.contact[c]];
    }
    Project(z.data());
  }

  // With the FFT, the displacement follows the step: u += α·A·d.
  void Stepped(double alpha) {
    if (direct_) return;
    for (std::size_t i = 0; i < ws_.displacement.size(); ++i) {
      ws_.displacement[i] += alpha * ws_.response[i];
    }
  }

  // z ← z − Z·E⁻¹·(AZ)ᵀ·z: the A-orthogonal projection off the blocks.
  void Project(double* z) {
    const Eigen::Map<const Eigen::MatrixXd> az(ws_.coarse_response.data(),
                                               static_cast<Eigen::Index>(nc_), space_.blocks.count);
    space_.vector.noalias() =
        az.transpose() * Eigen::Map<const Eigen::VectorXd>(z, static_cast<Eigen::Index>(nc_));
    space_.factor.solveInPlace(space_.vector);
    for (std::size_t c = 0; c < nc_; ++c) z[c] -= space_.vector(space_.blocks.block[c]);
  }

 private:
  const FftInfluenceOperator& op_;
  const InfluenceCoefficients& columns_;
  const LocalInverseStencil* stencil_;
  CoarseSpace& space_;
  Scratch& ws_;
  std::size_t nc_;
  bool direct_;
};

// The start of a round: x = p on C plus the coarse correction Z·E⁻¹·Zᵀ·r, whose displacement
// takes one product; r = δ − h − A·x on C.
void StartOnContactSet(const std::vector<double>& h, double approach, ContactSetOperator& a,
                       CoarseSpace& space, Scratch& ws, const NormalSolution& sol) {
  linear::PcgScratch& s = ws.pcg;
  const std::size_t nc = ws.contact.size();
  const std::vector<int>& block = space.blocks.block;
  s.Resize(nc);
  space.vector.setZero();
  for (std::size_t c = 0; c < nc; ++c) {
    const std::size_t i = ws.contact[c];
    s.x[c] = sol.pressure[i];
    space.vector(block[c]) += approach - h[i] - ws.displacement[i];
  }
  space.factor.solveInPlace(space.vector);
  if (!a.direct()) std::fill(ws.direction.begin(), ws.direction.end(), 0.0);
  for (std::size_t c = 0; c < nc; ++c) {
    s.x[c] += space.vector(block[c]);
    s.d[c] = space.vector(block[c]);
  }
  a.Apply(s.d, s.w);
  a.Stepped(1.0);
  for (std::size_t c = 0; c < nc; ++c) {
    const std::size_t i = ws.contact[c];
    s.r[c] = approach - h[i] - (a.direct() ? ws.displacement[i] + s.w[c] : ws.displacement[i]);
  }
}

// Complementarity after a round: p > 0 on C and open gaps off it, or else the next C (ws.mask)
// without the elements where p <= 0 and with those where the gap is negative. The displacement
// loses the dropped pressures column by column, or is marked stale (`current` false) when they
// are too many. Returns whether C was the solution's contact set.
bool UpdateContactSet(const InfluenceCoefficients& columns, const Grid& grid,
                      const std::vector<double>& h, double approach, Scratch& ws,
                      NormalSolution& sol, bool* current) {
  const std::vector<double>& x = ws.pcg.x;
  ws.corrected.clear();
  ws.correction.clear();
  for (std::size_t c = 0; c < ws.contact.size(); ++c) {
    if (x[c] <= 0.0) {
      const std::size_t i = ws.contact[c];
      ws.mask[i] = 0.0;
      ws.corrected.push_back(i);
      ws.correction.push_back(-x[c]);  // back to p = 0
      sol.pressure[i] = 0.0;
    }
  }
  bool added = false;
  for (const auto& [begin, end] : ws.segments) {
    for (std::size_t i = begin; i < end; ++i) {
      if (ws.mask[i] == 0.0 && ws.displacement[i] + h[i] - approach < 0.0) {
        ws.mask[i] = 1.0;  // joins with p = 0 for now
        added = true;
      }
    }
  }
  if (ws.corrected.empty() && !added) return true;
  if (ws.corrected.size() <= kMaxDirectColumns) {
    for (std::size_t k = 0; k < ws.corrected.size(); ++k) {
      AddColumn(columns, grid, ws.corrected[k], ws.correction[k], ws.displacement.data());
    }
  } else {
    *current = false;
  }
  return false;
}

// The last phase of a solve under approach control, once the contact set C has stopped
// changing: A_CC·p = δ − h on C is then linear, and deflated PCG (A-DEF2 in Tang, Nabben, Vuik &
// Erlangga 2009, J. Sci. Comput. 39) solves it in about half the iterations the active-set
// method takes from there. The smooth modes of a large contact are what a local preconditioner
// leaves slow; Z holds them as the indicator vectors of kDeflationBlock × kDeflationBlock blocks of
// C, and A·Z comes from row prefix sums of the influence coefficients (two per block row and
// target), so that no product per block is needed. Should the solution leave p < 0 on C or a
// negative gap off it, C drops and takes those elements and is solved again (a primal–dual
// active-set step, as in semismooth Newton methods), up to kDeflationRounds times. Measured on
// heavy haul: 22/27/29 products become 17/20/22, and the pressures end 100× closer to the exact
// solution (the stopping rule is the same relative change of the pressures). Expects
// ws.displacement = A·p; returns whether it converged, and otherwise leaves p >= 0 (the caller
// resumes) with the displacement no longer A·p.
DeflationOutcome SolveOnContactSet(const FftInfluenceOperator& op,
                                   const InfluenceCoefficients& columns,
                                   const std::vector<double>& h, double approach,
                                   const NormalOptions& options, int max_iterations,
                                   const LocalInverseStencil* stencil, Scratch& ws,
                                   NormalSolution& sol) {
  const Grid& grid = op.grid();
  const std::size_t n = h.size();
  DeflationOutcome outcome;
  const std::vector<double> prefix = RowPrefixSums(columns, grid.nx, grid.ny);
  // C as a 0/1 mask of the grid (also the preconditioner's contact mask).
  ws.mask.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) ws.mask[i] = sol.pressure[i] > 0.0 ? 1.0 : 0.0;
  std::fill(ws.residual.begin(), ws.residual.end(), 0.0);
  bool displacement_current = true;  // ws.displacement = A·p
  for (int round = 0; round < kDeflationRounds && displacement_current; ++round) {
    CollectContactSet(ws);
    if (ws.contact.empty()) break;
    CoarseSpace space;
    if (!BuildCoarseSpace(prefix, grid.nx, grid.ny, ws, space)) break;
    ContactSetOperator a(op, columns, stencil, space, ws);
    StartOnContactSet(h, approach, a, space, ws, sol);
    ++outcome.iterations;
    const linear::PcgOutcome pcg =
        linear::SolvePcg(a, options.tolerance, max_iterations - outcome.iterations, ws.pcg);
    outcome.iterations += pcg.iterations;
    if (pcg.iterations > 0) outcome.residual = pcg.residual;
    for (std::size_t c = 0; c < ws.contact.size(); ++c) sol.pressure[ws.contact[c]] = ws.pcg.x[c];
    if (!pcg.converged) break;
    if (a.direct()) {
      op.Apply(InfluenceComponent::kNN, sol.pressure.data(), ws.displacement.data(),
               ws.convolution);
    }
    if (UpdateContactSet(columns, grid, h, approach, ws, sol, &displacement_current)) {
      outcome.converged = true;
      return outcome;
    }
  }
  for (double& p : sol.pressure) p = std::max(0.0, p);
  return outcome;
}

// ---- the active-set iteration (Polonsky & Keer 1999), in named steps -------------------------
//
// Its grid passes are a third of an iteration on a large box. They are inlined into the cloned
// SolveNormal, so that each of its variants compiles them for its own instruction set.
#define WRC_GRID_PASS inline __attribute__((always_inline))

// The displacement u = A·p is carried from one iteration to the next: a step changes the
// pressure by −τ·d, plus a correction at the few elements it clipped to zero or re-activated,
// so u ← s·(u − τ·A·d + A·c) with the response A·d already at hand and A·c summed directly
// from the influence coefficients (one column per corrected element). That saves one of the
// two FFT products per iteration, also while the contact area still changes. With more than
// kMaxDirectColumns corrections the FFT is cheaper, and u is recomputed. It is recomputed at
// least every kRefreshIterations anyway, so that round-off cannot accumulate: each carried
// update adds ~1e-16 of u, so 64 of them stay near 1e-14, six orders below the tolerance
// (measured: the heavy-haul forces move by 5e-16 of the load against a refresh every 16).
constexpr int kRefreshIterations = 64;

// What every step reads: the problem and the parts of it that do not change.
struct ActiveSetProblem {
  const FftInfluenceOperator& op;
  const std::vector<double>& h;
  const NormalLoad& load;
  const InfluenceCoefficients& columns;
  const LocalInverseStencil* stencil;  ///< nullptr: not preconditioned
  std::size_t n;
  double area;
};

// What the iteration carries from one step to the next.
struct ActiveSetState {
  double rz_old = 1.0;
  bool conjugate = false;
  double mean_gap = 0.0;  ///< Under force control: the approach estimate of the last step.
  bool displacement_valid = false;  ///< ws.displacement = A·p
  int stable_steps = 0, deflations = 0, since_refresh = 0;
};

struct GapSums {
  double sum = 0.0, sum_of_squares = 0.0;
  int n_active = 0;
};

struct StepSums {
  double sum = 0.0, change = 0.0;  ///< Σ p and Σ |Δp| after the step
  bool overlap = false;            ///< an element outside the contact was re-activated
};

// The two load controls: everything the active-set iteration does differently when the approach
// δ is prescribed and when the total force F is. The steps below are templates over them.
//
// Approach control: the gap is u + h − δ, only elements with h < δ can carry pressure (A·p >= 0
// keeps every other gap open), and the pressures are free.
struct ApproachControl {
  // Shaped like Hertz's p ∝ sqrt(δ − h) on the interpenetration; scaled to the least elastic
  // energy along that shape once its displacement is known (RefreshDisplacement).
  static constexpr bool kHertzStart = true;
  // Deflation solves A·p = δ − h on a fixed contact set: only with δ known.
  static constexpr bool kDeflates = true;

  static bool NothingToSolve(const NormalLoad& load, double hmin) {
    return hmin - load.value >= 0.0;
  }
  static double ApproachWithoutContact(const NormalLoad& load, double) { return load.value; }

  WRC_GRID_PASS static void ColdStart(const ActiveSetProblem& pb, NormalSolution& sol) {
    for (std::size_t i = 0; i < pb.n; ++i) {
      sol.pressure[i] = std::sqrt(std::max(0.0, pb.load.value - pb.h[i]));
    }
  }
  WRC_GRID_PASS static void ImposeForce(const ActiveSetProblem&, NormalSolution&) {}

  // One stretch per row around the interpenetrating elements (on the combined heavy-haul
  // patches the passes then skip two thirds of the box or more).
  WRC_GRID_PASS static void FindSegments(const ActiveSetProblem& pb, Scratch& ws,
                                         NormalSolution& sol) {
    const std::size_t nx = static_cast<std::size_t>(pb.op.grid().nx);
    for (std::size_t row = 0; row < pb.n; row += nx) {
      std::size_t lo = row + nx, hi = row;
      for (std::size_t i = row; i < row + nx; ++i) {
        if (pb.h[i] < pb.load.value) {
          lo = std::min(lo, i);
          hi = i + 1;
        }
      }
      if (hi > lo) ws.segments.emplace_back(lo, hi);
    }
    // A warm start may carry pressure where the gap is now open for good.
    std::size_t open_from = 0;
    for (const auto& [begin, end] : ws.segments) {
      std::fill(sol.pressure.begin() + open_from, sol.pressure.begin() + begin, 0.0);
      open_from = end;
    }
    std::fill(sol.pressure.begin() + open_from, sol.pressure.end(), 0.0);
  }

  static double GapShift(const ActiveSetProblem& pb) { return pb.load.value; }
  WRC_GRID_PASS static double CentreGap(const ActiveSetProblem&, const GapSums& sums,
                                        ActiveSetState&, Scratch&, const NormalSolution&) {
    return sums.sum_of_squares;
  }
  WRC_GRID_PASS static void CentrePreconditioned(const ActiveSetProblem&, int, Scratch&,
                                                 const NormalSolution&) {}
  static double MeanResponse(double, int) { return 0.0; }
  WRC_GRID_PASS static void KeepPressures(Scratch&, const NormalSolution&) {}
  WRC_GRID_PASS static double ReimposeForce(const ActiveSetProblem&, StepSums&, const Scratch&,
                                            NormalSolution&) {
    return 1.0;
  }
  static double FinalApproach(const ActiveSetProblem& pb, const ActiveSetState&,
                              const std::vector<double>**, Scratch&, const NormalSolution&) {
    return pb.load.value;
  }
};

// Force control: the approach is unknown. It is estimated as the mean gap over the contact and
// subtracted from the residual and the step (which keeps the step within Σp = F/dA); every
// element may carry pressure, and the total force is re-imposed after each step.
struct ForceControl {
  static constexpr bool kHertzStart = false;
  static constexpr bool kDeflates = false;

  static bool NothingToSolve(const NormalLoad& load, double) { return load.value == 0.0; }
  static double ApproachWithoutContact(const NormalLoad&, double hmin) { return hmin; }

  WRC_GRID_PASS static void ColdStart(const ActiveSetProblem& pb, NormalSolution& sol) {
    std::fill(sol.pressure.begin(), sol.pressure.end(), pb.load.value / (pb.area * pb.n));
  }
  WRC_GRID_PASS static void ImposeForce(const ActiveSetProblem& pb, NormalSolution& sol) {
    double sum = 0.0;
    for (double p : sol.pressure) sum += p;
    const double scale = pb.load.value / (pb.area * sum);
    for (double& p : sol.pressure) p *= scale;
  }

  WRC_GRID_PASS static void FindSegments(const ActiveSetProblem& pb, Scratch& ws, NormalSolution&) {
    const std::size_t nx = static_cast<std::size_t>(pb.op.grid().nx);
    for (std::size_t row = 0; row < pb.n; row += nx) ws.segments.emplace_back(row, row + nx);
  }

  static double GapShift(const ActiveSetProblem&) { return 0.0; }

  // The mean gap over the contact is the approach estimate: subtracted from gap and residual,
  // in a pass of its own, since Σg² − n·mean² would cancel (the gaps sit near the approach and
  // differ from it by far less). Returns |r|².
  WRC_GRID_PASS static double CentreGap(const ActiveSetProblem& pb, const GapSums& sums,
                                        ActiveSetState& state, Scratch& ws,
                                        const NormalSolution& sol) {
    state.mean_gap = sums.sum / sums.n_active;
    double norm = 0.0;
    for (std::size_t i = 0; i < pb.n; ++i) {  // the segments: the whole grid
      ws.gap[i] -= state.mean_gap;
      const bool active = sol.pressure[i] > 0.0;
      ws.residual[i] = active ? ws.gap[i] : 0.0;
      if (active) norm += ws.gap[i] * ws.gap[i];
    }
    return norm;
  }
  // z centred like r.
  WRC_GRID_PASS static void CentrePreconditioned(const ActiveSetProblem& pb, int n_active,
                                                 Scratch& ws, const NormalSolution& sol) {
    double sum_z = 0.0;
    for (std::size_t i = 0; i < pb.n; ++i) sum_z += ws.preconditioned[i];
    const double mean_z = sum_z / n_active;
    for (std::size_t i = 0; i < pb.n; ++i) {
      if (sol.pressure[i] > 0.0) ws.preconditioned[i] -= mean_z;
    }
  }
  // A·d centred like r in the step length's denominator.
  static double MeanResponse(double sum_response, int n_active) { return sum_response / n_active; }
  // The pressures before the step, against which ReimposeForce counts the change.
  WRC_GRID_PASS static void KeepPressures(Scratch& ws, const NormalSolution& sol) {
    ws.previous = sol.pressure;
  }
  // Σp = F/dA again after the projection; returns the scale applied.
  WRC_GRID_PASS static double ReimposeForce(const ActiveSetProblem& pb, StepSums& step,
                                            const Scratch& ws, NormalSolution& sol) {
    if (!(step.sum > 0.0)) return 1.0;
    const double scale = pb.load.value / (pb.area * step.sum);
    for (double& p : sol.pressure) p *= scale;
    step.sum = pb.load.value / pb.area;
    step.change = 0.0;
    for (std::size_t i = 0; i < pb.n; ++i) {
      step.change += std::fabs(sol.pressure[i] - ws.previous[i]);
    }
    return scale;
  }
  // The mean gap over the final contact area. `displacement` is A·p, or nullptr (then made
  // into ws.gap).
  static double FinalApproach(const ActiveSetProblem& pb, const ActiveSetState& state,
                              const std::vector<double>** displacement, Scratch& ws,
                              const NormalSolution& sol) {
    if (!*displacement) {
      pb.op.Apply(InfluenceComponent::kNN, sol.pressure.data(), ws.gap.data(), ws.convolution);
      *displacement = &ws.gap;
    }
    const std::vector<double>& u = **displacement;
    double sum_gap = 0.0;
    int n_active = 0;
    for (std::size_t i = 0; i < pb.n; ++i) {
      if (sol.pressure[i] > 0.0) {
        sum_gap += u[i] + pb.h[i];
        ++n_active;
      }
    }
    return n_active > 0 ? sum_gap / n_active : state.mean_gap;
  }
};

// Initial guess: the warm start, or the control's cold start; under force control scaled to F.
// The Hertz start of approach control, measured on heavy haul: 27/29/31 iterations become
// 21/26/28; pressures proportional to the interpenetration (with the element's own stiffness,
// the earlier start, or scaled the same way) take 26–31. Returns whether the Hertz shape was
// used (its scale comes with the first product).
template <class Control>
WRC_GRID_PASS bool StartPressure(const ActiveSetProblem& pb, const NormalOptions& options,
                                 NormalSolution& sol) {
  const bool warm =
      options.warm_start && sol.pressure.size() == pb.n &&
      std::any_of(sol.pressure.begin(), sol.pressure.end(), [](double p) { return p > 0.0; });
  if (!warm) {
    sol.pressure.assign(pb.n, 0.0);
    Control::ColdStart(pb, sol);
  }
  Control::ImposeForce(pb, sol);
  return !warm && Control::kHertzStart;
}

// The elements that can carry pressure, kept as one stretch per row so that the passes of an
// iteration skip the rest of the box.
template <class Control>
WRC_GRID_PASS void FindSegments(const ActiveSetProblem& pb, Scratch& ws, NormalSolution& sol) {
  ws.segments.clear();
  Control::FindSegments(pb, ws, sol);
}

// u = A·p afresh when the carried one is not valid or due for a refresh; after the Hertz start
// also its scale c = argmin ½c²·pᵀAp − c·pᵀ(δ − h), for p and A·p alike.
WRC_GRID_PASS void RefreshDisplacement(const ActiveSetProblem& pb, bool scale_hertz_start,
                                       ActiveSetState& state, Scratch& ws, NormalSolution& sol) {
  if (state.displacement_valid && state.since_refresh < kRefreshIterations) {
    ++state.since_refresh;
    return;
  }
  pb.op.Apply(InfluenceComponent::kNN, sol.pressure.data(), ws.displacement.data(), ws.convolution);
  state.since_refresh = 1;
  if (!scale_hertz_start) return;
  double work = 0.0, energy = 0.0;
  for (std::size_t i = 0; i < pb.n; ++i) {
    work += sol.pressure[i] * (pb.load.value - pb.h[i]);
    energy += sol.pressure[i] * ws.displacement[i];
  }
  const double scale = energy > 0.0 ? work / energy : 0.0;
  for (std::size_t i = 0; i < pb.n; ++i) {
    sol.pressure[i] *= scale;
    ws.displacement[i] *= scale;
  }
}

// The gap g = u + h − δ (δ = 0 under force control) on the segments, the residual (g on the
// contact, 0 elsewhere) and the sums of g and g² over the contact.
WRC_GRID_PASS GapSums GapPass(const ActiveSetProblem& pb, double shift, Scratch& ws,
                              const NormalSolution& sol) {
  GapSums sums;
  for (const auto& [begin, end] : ws.segments) {
    for (std::size_t i = begin; i < end; ++i) {
      const double g = ws.displacement[i] + pb.h[i] - shift;
      ws.gap[i] = g;
      const bool active = sol.pressure[i] > 0.0;
      ws.residual[i] = active ? g : 0.0;
      if (active) {
        sums.sum += g;
        sums.sum_of_squares += g * g;
        ++sums.n_active;
      }
    }
  }
  return sums;
}

// z = M·r (or r), centred like r under force control; returns r·z for β.
template <class Control>
WRC_GRID_PASS double Precondition(const ActiveSetProblem& pb, int n_active, double residual_norm,
                                  Scratch& ws, const NormalSolution& sol, const double** z) {
  *z = ws.residual.data();
  if (!pb.stencil) return residual_norm;
  ApplyLocalInverse(*pb.stencil, pb.op.grid(), ws.segments, ws.residual.data(), sol.pressure.data(),
                    ws.column_sums.data(), ws.preconditioned.data());
  Control::CentrePreconditioned(pb, n_active, ws, sol);
  double rz = 0.0;
  for (const auto& [begin, end] : ws.segments) {
    for (std::size_t i = begin; i < end; ++i) rz += ws.residual[i] * ws.preconditioned[i];
  }
  *z = ws.preconditioned.data();
  return rz;
}

// d ← z + β·d on the contact, zero elsewhere (and off the segments, where it stays zero).
WRC_GRID_PASS void UpdateDirection(const double* z, double beta, Scratch& ws,
                                   const NormalSolution& sol) {
  for (const auto& [begin, end] : ws.segments) {
    for (std::size_t i = begin; i < end; ++i) {
      ws.direction[i] = sol.pressure[i] > 0.0 ? z[i] + beta * ws.direction[i] : 0.0;
    }
  }
}

// τ = r·d / (A·d)·d over the contact, with r and A·d centred under force control:
// den = Σ (w − mean w)·d = Σ w·d − mean w·Σ d.
template <class Control>
WRC_GRID_PASS double StepLength(int n_active, const Scratch& ws, const NormalSolution& sol) {
  double num = 0.0, rd = 0.0, sum_response = 0.0, sum_direction = 0.0;
  for (const auto& [begin, end] : ws.segments) {
    for (std::size_t i = begin; i < end; ++i) {
      if (sol.pressure[i] > 0.0) {
        num += ws.gap[i] * ws.direction[i];
        rd += ws.response[i] * ws.direction[i];
        sum_response += ws.response[i];
        sum_direction += ws.direction[i];
      }
    }
  }
  const double den = rd - Control::MeanResponse(sum_response, n_active) * sum_direction;
  return den > 0.0 ? num / den : 0.0;
}

// p ← max(0, p − τ·d) on the contact, and p = max(0, −τ·g) where the gap is negative outside
// it; the elements clipped or re-activated go to ws.corrected with the pressure they got
// beyond the plain step, and u follows the plain step: u −= τ·A·d.
WRC_GRID_PASS StepSums ProjectedStep(const ActiveSetProblem& pb, double tau, Scratch& ws,
                                     NormalSolution& sol) {
  StepSums step;
  ws.corrected.clear();
  ws.correction.clear();
  for (const auto& [begin, end] : ws.segments) {
    for (std::size_t i = begin; i < end; ++i) {
      const double old = sol.pressure[i];
      double p = old;
      if (old > 0.0) {
        const double stepped = old - tau * ws.direction[i];
        p = std::max(0.0, stepped);
        if (stepped < 0.0) {
          ws.corrected.push_back(i);
          ws.correction.push_back(-stepped);  // the set pressure minus the −τ·d step
        }
      } else if (ws.gap[i] < 0.0) {
        // Interpenetration outside the contact: let the element carry load again.
        p = std::max(0.0, -tau * ws.gap[i]);
        if (p > 0.0) {
          step.overlap = true;
          ws.corrected.push_back(i);
          ws.correction.push_back(p);
        }
      }
      sol.pressure[i] = p;
      step.sum += p;
      step.change += std::fabs(p - old);
    }
  }
  for (std::size_t i = 0; i < pb.n; ++i) ws.displacement[i] -= tau * ws.response[i];
  return step;
}

// u += A·c for the corrections of the step, then u ← s·u; or u invalid when the corrections
// are too many to add column by column (the next iteration makes a product).
WRC_GRID_PASS void CarryDisplacement(const ActiveSetProblem& pb, double scale,
                                     ActiveSetState& state, Scratch& ws) {
  state.displacement_valid = ws.corrected.size() <= kMaxDirectColumns;
  if (!state.displacement_valid) return;
  for (std::size_t c = 0; c < ws.corrected.size(); ++c) {
    AddColumn(pb.columns, pb.op.grid(), ws.corrected[c], ws.correction[c], ws.displacement.data());
  }
  if (scale != 1.0) {
    for (std::size_t i = 0; i < pb.n; ++i) ws.displacement[i] *= scale;
  }
}

// Everything lifted off (only possible under approach control when the initial guess
// overshot): restart from the interpenetration.
WRC_GRID_PASS void RestartFromInterpenetration(ActiveSetState& state, Scratch& ws,
                                               NormalSolution& sol) {
  for (const auto& [begin, end] : ws.segments) {
    for (std::size_t i = begin; i < end; ++i) sol.pressure[i] = std::max(0.0, -ws.gap[i]);
  }
  state.conjugate = false;
  state.displacement_valid = false;
}

enum class StepOutcome { kContinue, kRestarted, kConverged };

// One iteration: gap, preconditioned residual, conjugate direction, its response, the
// projected step and the carried displacement.
template <class Control>
WRC_GRID_PASS StepOutcome ActiveSetStep(const ActiveSetProblem& pb, const NormalOptions& options,
                                        bool scale_hertz_start, ActiveSetState& state, Scratch& ws,
                                        NormalSolution& sol, NormalSummary& summary) {
  RefreshDisplacement(pb, scale_hertz_start, state, ws, sol);
  const GapSums gaps = GapPass(pb, Control::GapShift(pb), ws, sol);
  if (gaps.n_active == 0) {
    RestartFromInterpenetration(state, ws, sol);
    return StepOutcome::kRestarted;
  }
  const double residual_norm = Control::CentreGap(pb, gaps, state, ws, sol);
  const double* z = nullptr;
  const double rz = Precondition<Control>(pb, gaps.n_active, residual_norm, ws, sol, &z);
  UpdateDirection(z, state.conjugate ? rz / state.rz_old : 0.0, ws, sol);
  state.rz_old = rz;
  pb.op.Apply(InfluenceComponent::kNN, ws.direction.data(), ws.response.data(), ws.convolution);
  const double tau = StepLength<Control>(gaps.n_active, ws, sol);
  Control::KeepPressures(ws, sol);
  StepSums step = ProjectedStep(pb, tau, ws, sol);
  state.conjugate = !step.overlap;
  const double scale = Control::ReimposeForce(pb, step, ws, sol);
  CarryDisplacement(pb, scale, state, ws);
  summary.residual = step.sum > 0.0 ? step.change / step.sum : 0.0;
  return summary.residual < options.tolerance ? StepOutcome::kConverged : StepOutcome::kContinue;
}

// Two steps without clipping or re-activation: the contact set has settled (it rarely moves
// again), and the rest is a linear solve on it. Only with three decades or more still to go
// (closer to the end the setup costs more than it saves: warm-started Manchester solves lost
// 1 % at two decades), and at most twice, should the set move after all.
template <class Control>
bool DeflationDue(const NormalOptions& options, const ActiveSetState& state,
                  const NormalSummary& summary) {
  return options.deflate && Control::kDeflates && state.stable_steps >= 2 && state.deflations < 2 &&
         state.displacement_valid && summary.residual > 1000.0 * options.tolerance;
}

void SizeWorkspace(const FftInfluenceOperator& op, std::size_t n, bool preconditioned,
                   Scratch& ws) {
  ws.gap.resize(n);
  ws.direction.assign(n, 0.0);
  ws.response.resize(n);
  ws.previous.resize(n);
  ws.displacement.resize(n);
  if (!op.Fits(ws.convolution)) ws.convolution = op.MakeWorkspace();
  if (preconditioned) {
    ws.preconditioned.resize(n);
    ws.column_sums.resize(static_cast<std::size_t>(op.grid().nx) + 2);
  }
}

// The active-set iteration under one load control, from the start to the final approach, with
// the hand-over to SolveOnContactSet once the contact set settles.
template <class Control>
WRC_GRID_PASS void SolveActiveSet(const ActiveSetProblem& pb, const NormalOptions& options,
                                  Scratch& ws, NormalSolution& sol, NormalSummary& summary) {
  SizeWorkspace(pb.op, pb.n, pb.stencil != nullptr, ws);
  const bool hertz_start = StartPressure<Control>(pb, options, sol);
  FindSegments<Control>(pb, ws, sol);
  ws.residual.assign(pb.n, 0.0);  // zero off the segments, where the stencil reads it too
  ActiveSetState state;
  for (int it = 1; it <= options.max_iterations; ++it) {
    const StepOutcome outcome =
        ActiveSetStep<Control>(pb, options, it == 1 && hertz_start, state, ws, sol, summary);
    if (outcome == StepOutcome::kRestarted) continue;
    summary.iterations = it;
    if (outcome == StepOutcome::kConverged) {
      summary.status = SolverStatus::kConverged;
      break;
    }
    state.stable_steps = ws.corrected.empty() ? state.stable_steps + 1 : 0;
    if (!DeflationDue<Control>(options, state, summary)) continue;
    ++state.deflations;
    const DeflationOutcome deflation =
        SolveOnContactSet(pb.op, pb.columns, pb.h, pb.load.value, options,
                          options.max_iterations - it, pb.stencil, ws, sol);
    it += deflation.iterations;
    summary.iterations = it;
    if (deflation.converged) {
      summary.residual = deflation.residual;
      summary.status = SolverStatus::kConverged;
      break;
    }
    state.displacement_valid = false;  // the pressures were clipped
    state.conjugate = false;
    state.stable_steps = 0;
  }
  // The carried displacement is A·p of the final pressures when the last step kept it (it
  // differs from a fresh product by the round-off of at most kRefreshIterations updates,
  // ~1e-14 relative), and saves the product of the deformed distance.
  const std::vector<double>* displacement = state.displacement_valid ? &ws.displacement : nullptr;
  const double approach = Control::FinalApproach(pb, state, &displacement, ws, sol);
  Finish(pb.op, pb.h, approach, displacement, ws, sol);
}

// Zero force, or no interpenetration at the given approach: zero pressure.
template <class Control>
bool SolvedWithoutContact(const FftInfluenceOperator& op, const std::vector<double>& h,
                          const NormalLoad& load, Scratch& ws, NormalSolution& sol,
                          NormalSummary& summary) {
  const double hmin = *std::min_element(h.begin(), h.end());
  if (!Control::NothingToSolve(load, hmin)) return false;
  SizeWorkspace(op, h.size(), false, ws);
  sol.pressure.assign(h.size(), 0.0);
  Finish(op, h, Control::ApproachWithoutContact(load, hmin), nullptr, ws, sol);
  summary.status = SolverStatus::kNoContact;
  return true;
}

template <class Control>
WRC_GRID_PASS NormalSummary SolveUnder(const FftInfluenceOperator& op, const std::vector<double>& h,
                                       const NormalLoad& load, const NormalOptions& options,
                                       Scratch& ws, NormalSolution& sol) {
  NormalSummary summary;
  if (SolvedWithoutContact<Control>(op, h, load, ws, sol, summary)) return summary;
  const std::optional<LocalInverseStencil> local_inverse =
      options.precondition ? op.LocalInverse(InfluenceComponent::kNN) : std::nullopt;
  const InfluenceCoefficients columns(op.grid(), op.material(), InfluenceComponent::kNN);
  const ActiveSetProblem pb{op,
                            h,
                            load,
                            columns,
                            local_inverse ? &*local_inverse : nullptr,
                            h.size(),
                            op.grid().element_area()};
  SolveActiveSet<Control>(pb, options, ws, sol, summary);
  return summary;
}

}  // namespace

// Polonsky & Keer (1999), Wear 231: CG restricted to the elements in contact, with the
// projection p >= 0 after each step and re-activation of elements where the gap is negative.
// Under force control the mean gap over the contact is the (unknown) approach, so it is
// subtracted from the residual and the step, and the total force is re-imposed every step
// (ForceControl; ApproachControl is the other load control).
//
// Preconditioned with the 3 × 3 centre M of the inverse influence matrix (as NormCG's FFT
// preconditioner, Vollebregt 2014, but local). The full inverse has a symbol that vanishes for
// smooth fields, which restricted to a narrow contact leaves the smooth modes as badly
// conditioned as before (tried: no gain on the multi-region heavy-haul patches); the truncated
// stencil keeps a positive symbol there and halves the iterations on every heavy-haul case. M
// restricted to the contact is positive definite (LocalInverse checks the symbol), so this is
// PCG on the contact set; under force control z is centred like r. Once the contact set
// settles, SolveOnContactSet takes over (approach control).
//
// Built for AVX2 as well as the baseline ISA, chosen at load time (no FMA in either, so both
// give the same results).
WRC_CLONE_FOR_AVX2
NormalSummary SolveNormal(const FftInfluenceOperator& op, const std::vector<double>& h,
                          const NormalLoad& load, const NormalOptions& options,
                          NormalWorkspace& workspace, NormalSolution& sol) {
  Validate(op, h, load);
  Scratch& ws = workspace.scratch();
  return load.kind == NormalLoad::Kind::kForce
             ? SolveUnder<ForceControl>(op, h, load, options, ws, sol)
             : SolveUnder<ApproachControl>(op, h, load, options, ws, sol);
}

}  // namespace wrc
