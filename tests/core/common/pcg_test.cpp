// The conjugate-gradient kernel against Eigen's dense Cholesky solve.
#include "core/common/pcg.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

namespace wrc::linear {
namespace {

// A = Bᵀ·B + n·I (symmetric positive definite, condition ~ 10) from a fixed pseudo-random B,
// with a Jacobi preconditioner; counts the steps it is told about.
class DenseOperator {
 public:
  explicit DenseOperator(int n) : a_(n, n) {
    Eigen::MatrixXd b(n, n);
    unsigned state = 12345;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        state = state * 1103515245u + 12345u;
        b(i, j) = static_cast<double>((state >> 16) % 1000) / 1000.0 - 0.5;
      }
    }
    a_ = b.transpose() * b + n * Eigen::MatrixXd::Identity(n, n);
  }
  const Eigen::MatrixXd& matrix() const { return a_; }
  void Apply(const std::vector<double>& d, std::vector<double>& w) {
    Eigen::Map<Eigen::VectorXd>(w.data(), a_.rows()) =
        a_ * Eigen::Map<const Eigen::VectorXd>(d.data(), a_.rows());
  }
  void Precondition(const std::vector<double>& r, std::vector<double>& z) {
    for (std::size_t i = 0; i < r.size(); ++i) z[i] = r[i] / a_(i, i);
  }
  void Stepped(double) { ++steps; }
  int steps = 0;

 private:
  Eigen::MatrixXd a_;
};

TEST(Pcg, SolvesASymmetricPositiveDefiniteSystem) {
  const int n = 40;
  DenseOperator op(n);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b(i) = 1.0 + std::sin(0.3 * i);
  const Eigen::VectorXd expected = op.matrix().llt().solve(b);
  PcgScratch s;
  s.Resize(n);
  std::fill(s.x.begin(), s.x.end(), 0.0);
  for (int i = 0; i < n; ++i) s.r[i] = b(i);  // r = b − A·0
  const PcgOutcome outcome = SolvePcg(op, 1e-12, 200, s);
  ASSERT_TRUE(outcome.converged);
  // CG is exact after n steps in exact arithmetic; a well-conditioned system needs far fewer.
  EXPECT_LT(outcome.iterations, n);
  EXPECT_EQ(op.steps, outcome.iterations);
  for (int i = 0; i < n; ++i)
    EXPECT_NEAR(s.x[i], expected(i), 1e-10 * expected.cwiseAbs().maxCoeff());
  // r is b − A·x to round-off.
  const Eigen::VectorXd r = b - op.matrix() * Eigen::Map<const Eigen::VectorXd>(s.x.data(), n);
  for (int i = 0; i < n; ++i) EXPECT_NEAR(s.r[i], r(i), 1e-9 * b.norm());
}

// x = 0 and r = b = (1, …, 1).
PcgScratch StartAtZero(int n) {
  PcgScratch s;
  s.Resize(n);
  std::fill(s.x.begin(), s.x.end(), 0.0);
  std::fill(s.r.begin(), s.r.end(), 1.0);
  return s;
}

TEST(Pcg, StopsAtTheIterationBudget) {
  const int n = 40;
  DenseOperator op(n);
  PcgScratch s = StartAtZero(n);
  const PcgOutcome outcome = SolvePcg(op, 1e-30, 3, s);
  EXPECT_FALSE(outcome.converged);
  EXPECT_EQ(outcome.iterations, 3);
  EXPECT_GT(outcome.residual, 0.0);
}

TEST(Pcg, NoBudgetMakesNoProduct) {
  DenseOperator op(5);
  PcgScratch s = StartAtZero(5);
  const PcgOutcome outcome = SolvePcg(op, 1e-8, 0, s);
  EXPECT_FALSE(outcome.converged);
  EXPECT_EQ(outcome.iterations, 0);
  EXPECT_EQ(op.steps, 0);
}

}  // namespace
}  // namespace wrc::linear
