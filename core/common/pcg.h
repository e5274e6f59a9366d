#pragma once
/// @file pcg.h
/// Preconditioned conjugate gradients for A·x = b with A symmetric positive definite, over an
/// operator the caller supplies and in scratch the caller owns (no allocation once the scratch
/// has its size). The stopping rule is the solvers' own: the relative change of the solution,
/// Σ|Δx| / Σ|x|, below a tolerance (the normal solver's rule for every phase, so that a hand-over
/// from one phase to the next stops at the same accuracy).

#include <cmath>
#include <cstddef>
#include <vector>

namespace wrc::linear {

/// The vectors of one solve; x and r (= b − A·x) are set by the caller before SolvePcg.
struct PcgScratch {
  std::vector<double> x, r, z, d, w;
  void Resize(std::size_t n) {
    x.resize(n);
    r.resize(n);
    z.resize(n);
    d.resize(n);
    w.resize(n);
  }
};

struct PcgOutcome {
  bool converged = false;
  int iterations = 0;     ///< Products A·d made.
  double residual = 0.0;  ///< The last relative change Σ|Δx| / Σ|x|.
};

/// The operator, as a type with
///   void Apply(const std::vector<double>& d, std::vector<double>& w);        // w = A·d
///   void Precondition(const std::vector<double>& r, std::vector<double>& z); // z ≈ A⁻¹·r
///   void Stepped(double alpha);  // x += alpha·d was taken (for state the caller carries)
/// Runs from the caller's x and r until the tolerance or `max_iterations` products.
template <class Operator>
PcgOutcome SolvePcg(Operator& op, double tolerance, int max_iterations, PcgScratch& s) {
  const std::size_t n = s.x.size();
  PcgOutcome outcome;
  op.Precondition(s.r, s.z);
  s.d = s.z;
  double rz = 0.0;
  for (std::size_t c = 0; c < n; ++c) rz += s.r[c] * s.z[c];
  while (outcome.iterations < max_iterations) {
    op.Apply(s.d, s.w);
    ++outcome.iterations;
    double dw = 0.0;
    for (std::size_t c = 0; c < n; ++c) dw += s.d[c] * s.w[c];
    const double alpha = dw > 0.0 ? rz / dw : 0.0;
    double change = 0.0, sum = 0.0;
    for (std::size_t c = 0; c < n; ++c) {
      s.x[c] += alpha * s.d[c];
      s.r[c] -= alpha * s.w[c];
      change += std::fabs(alpha * s.d[c]);
      sum += std::fabs(s.x[c]);
    }
    op.Stepped(alpha);
    outcome.residual = sum > 0.0 ? change / sum : 0.0;
    if (outcome.residual < tolerance) {
      outcome.converged = true;
      return outcome;
    }
    op.Precondition(s.r, s.z);
    double rz_new = 0.0;
    for (std::size_t c = 0; c < n; ++c) rz_new += s.r[c] * s.z[c];
    const double beta = rz_new / rz;
    rz = rz_new;
    for (std::size_t c = 0; c < n; ++c) s.d[c] = s.z[c] + beta * s.d[c];
  }
  return outcome;
}

}  // namespace wrc::linear
