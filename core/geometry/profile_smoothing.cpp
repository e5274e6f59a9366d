// Weighted cubic smoothing spline of a profile (CONTACT's ISMOOTH = 1), Reinsch's algorithm.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include <Eigen/Sparse>

#include "core/geometry/profile_internal.h"
#include "wrc/core/errors.h"

namespace wrc::profile_detail {

// For points x_i at parameters s_i (the chord length) the smoothing spline f minimises
//   Σ w_i (x_i − f(s_i))² + λ ∫ f''(s)² ds,   w_i = (s_{i+1} − s_{i−1})/2,  λ = (L/2π)⁴.
// The minimiser is a natural cubic spline with knots s_i. With g = f(s_i), γ = f''(s_i) at the
// interior knots (zero at the ends), h_i = s_{i+1} − s_i, the spline conditions are Qᵀg = Rγ
// and the penalty is γᵀRγ, where R is tridiagonal, R_jj = (h_{j−1} + h_j)/3, R_j,j+1 = h_j/6,
// and Q is n×(n−2) with Q_{j−1,j} = 1/h_{j−1}, Q_{j,j} = −1/h_{j−1} − 1/h_j, Q_{j+1,j} = 1/h_j.
// Minimising gives (R + λ QᵀW⁻¹Q) γ = Qᵀx and g = x − λ W⁻¹Qγ (Reinsch 1967; Green & Silverman,
// "Nonparametric regression and generalized linear models", §3.5). The matrix is pentadiagonal
// and positive definite, so a sparse LDLᵀ solves it in O(n). In the continuum limit the weights
// turn the sum into ∫(x − f)² ds and a sine of wavelength ℓ is damped by 1/(1 + λ(2π/ℓ)⁴): half
// at ℓ = L, the meaning CONTACT gives to L_filt.
void SmoothPoints(std::vector<double>& y, std::vector<double>& z, double wavelength, bool pin_first,
                  bool pin_last) {
  const std::size_t n = y.size();
  if (n < 3 || z.size() != n) throw std::invalid_argument("SmoothPoints: need 3 or more points");
  std::vector<double> h(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    h[i] = std::hypot(y[i + 1] - y[i], z[i + 1] - z[i]);
    if (!(h[i] > 0.0)) throw std::invalid_argument("SmoothPoints: coincident successive points");
  }
  std::vector<double> inverse_weight(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double before = i > 0 ? h[i - 1] : 0.0;
    const double after = i + 1 < n ? h[i] : 0.0;
    inverse_weight[i] = 2.0 / (before + after);
  }
  // An infinite weight forces f(s_i) = x_i: g = x − λW⁻¹Qγ leaves the point unchanged, and the
  // system matrix stays positive definite (R alone is).
  if (pin_first) inverse_weight.front() = 0.0;
  if (pin_last) inverse_weight.back() = 0.0;
  constexpr double kTwoPi = 6.28318530717958647692;
  const double lambda = std::pow(wavelength / kTwoPi, 4);

  const auto m = static_cast<Eigen::Index>(n - 2);
  // Column j of Q (interior knot j + 1) has entries in rows j, j + 1, j + 2.
  const auto q = [&h](std::size_t j, int offset) {
    const double left = 1.0 / h[j];
    const double right = 1.0 / h[j + 1];
    return offset == 0 ? left : offset == 1 ? -left - right : right;
  };
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(5 * m));
  for (Eigen::Index a = 0; a < m; ++a) {
    const auto ja = static_cast<std::size_t>(a);
    for (Eigen::Index b = std::max<Eigen::Index>(0, a - 2); b <= std::min(m - 1, a + 2); ++b) {
      const auto jb = static_cast<std::size_t>(b);
      double value = 0.0;
      if (a == b) value += (h[ja] + h[ja + 1]) / 3.0;
      if (b == a + 1) value += h[ja + 1] / 6.0;
      if (a == b + 1) value += h[jb + 1] / 6.0;
      // (QᵀW⁻¹Q)_ab = Σ_rows Q_row,a Q_row,b / w_row over the rows both columns touch.
      for (int oa = 0; oa < 3; ++oa) {
        const std::size_t row = ja + static_cast<std::size_t>(oa);
        const long ob = static_cast<long>(row) - static_cast<long>(jb);
        if (ob < 0 || ob > 2) continue;
        value += lambda * q(ja, oa) * q(jb, static_cast<int>(ob)) * inverse_weight[row];
      }
      entries.emplace_back(a, b, value);
    }
  }
  Eigen::SparseMatrix<double> matrix(m, m);
  matrix.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(matrix);
  if (solver.info() != Eigen::Success) {
    throw NumericalError("SmoothPoints: factorisation of the smoothing system failed");
  }

  for (std::vector<double>* values : {&y, &z}) {
    std::vector<double>& x = *values;
    Eigen::VectorXd rhs(m);
    for (Eigen::Index a = 0; a < m; ++a) {
      const auto j = static_cast<std::size_t>(a);
      rhs[a] = q(j, 0) * x[j] + q(j, 1) * x[j + 1] + q(j, 2) * x[j + 2];
    }
    const Eigen::VectorXd gamma = solver.solve(rhs);
    std::vector<double> q_gamma(n, 0.0);
    for (Eigen::Index a = 0; a < m; ++a) {
      const auto j = static_cast<std::size_t>(a);
      for (int offset = 0; offset < 3; ++offset) {
        q_gamma[j + static_cast<std::size_t>(offset)] += q(j, offset) * gamma[a];
      }
    }
    for (std::size_t i = 0; i < n; ++i) x[i] -= lambda * inverse_weight[i] * q_gamma[i];
  }
}

void SmoothPointsBetweenKinks(std::vector<double>& y, std::vector<double>& z, double wavelength,
                              const std::vector<std::size_t>& kinks) {
  if (kinks.empty()) {
    SmoothPoints(y, z, wavelength);
    return;
  }
  std::vector<std::size_t> bounds{0};
  bounds.insert(bounds.end(), kinks.begin(), kinks.end());
  bounds.push_back(y.size() - 1);
  for (std::size_t part = 0; part + 1 < bounds.size(); ++part) {
    const auto first = static_cast<std::ptrdiff_t>(bounds[part]);
    const auto last = static_cast<std::ptrdiff_t>(bounds[part + 1]);
    if (last - first < 2) continue;  // Two points: a straight piece, nothing to smooth.
    std::vector<double> part_y(y.begin() + first, y.begin() + last + 1);
    std::vector<double> part_z(z.begin() + first, z.begin() + last + 1);
    SmoothPoints(part_y, part_z, wavelength, part > 0, part + 2 < bounds.size());
    std::copy(part_y.begin(), part_y.end(), y.begin() + first);
    std::copy(part_z.begin(), part_z.end(), z.begin() + first);
  }
}

}  // namespace wrc::profile_detail
