#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <random>
#include <vector>

#include "core/fft/fftw.h"

namespace wrc::fftw {
namespace {

using Complex = std::complex<double>;

// The 2-D DFT of an n0 × n1 field by its definition, O(n²): the reference for the row-column
// transform with its row pairing and padding shortcuts.
std::vector<Complex> NaiveForwardDft(const std::vector<double>& field, int n0, int n1) {
  const double pi = std::acos(-1.0);
  std::vector<Complex> out(static_cast<std::size_t>(n0) * n1);
  for (int k0 = 0; k0 < n0; ++k0) {
    for (int k1 = 0; k1 < n1; ++k1) {
      Complex sum = 0.0;
      for (int j = 0; j < n0; ++j) {
        for (int i = 0; i < n1; ++i) {
          const double phase = -2.0 * pi * (double(k0) * j / n0 + double(k1) * i / n1);
          sum += field[static_cast<std::size_t>(j) * n1 + i] * std::polar(1.0, phase);
        }
      }
      out[static_cast<std::size_t>(k0) * n1 + k1] = sum;
    }
  }
  return out;
}

struct Shape {
  int n0, n1, ny, nx;
};

// ny × nx values uniform in [−1, 1], reproducible from the seed.
std::vector<double> RandomField(const Shape& s, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> field(static_cast<std::size_t>(s.ny) * s.nx);
  for (double& v : field) v = u(rng);
  return field;
}

class PaddedPlanTest : public ::testing::TestWithParam<Shape> {};

// The field of RandomField, or with rows of zeros: a whole pair (rows 0 and 1), half of a pair
// (row 3) and the last row, which Forward skips instead of transforming. The staging buffer
// first serves a transform of all n0 rows, so that its padding rows hold values that this
// transform must clear.
void CheckForwardAgainstDefinition(const Shape& s, bool zero_rows) {
  PaddedPlan2d plan(s.n0, s.n1);
  std::vector<double> in = RandomField(s, 7);
  if (zero_rows) {
    for (int j : {0, 1, 3, s.ny - 1}) {
      if (j < s.ny) std::fill(in.begin() + j * s.nx, in.begin() + (j + 1) * s.nx, 0.0);
    }
  }
  std::vector<double> padded(static_cast<std::size_t>(s.n0) * s.n1, 0.0);
  for (int j = 0; j < s.ny; ++j) {
    for (int i = 0; i < s.nx; ++i)
      padded[static_cast<std::size_t>(j) * s.n1 + i] = in[j * s.nx + i];
  }
  ComplexBuffer spectrum(plan.complex_size()), rows(plan.row_buffer_size());
  PaddedPlan2d::Staging staging(plan);
  const std::vector<double> full = RandomField({s.n0, s.n1, s.n0, s.nx}, 3);
  plan.Forward(full.data(), s.n0, s.nx, spectrum.data(), rows.data(), staging);
  std::fill(spectrum.data(), spectrum.data() + spectrum.size(), Complex(7.0, -3.0));  // stale
  plan.Forward(in.data(), s.ny, s.nx, spectrum.data(), rows.data(), staging);
  const std::vector<Complex> expected = NaiveForwardDft(padded, s.n0, s.n1);
  const int nc = s.n1 / 2 + 1;
  for (int k0 = 0; k0 < s.n0; ++k0) {
    for (int k1 = 0; k1 < nc; ++k1) {
      // Round-off of an O(n log n) transform of O(1) values with sums of up to n0·n1 terms.
      EXPECT_NEAR(std::abs(spectrum[static_cast<std::size_t>(k0) * nc + k1] -
                           expected[static_cast<std::size_t>(k0) * s.n1 + k1]),
                  0.0, 1e-11)
          << "k0 " << k0 << " k1 " << k1 << (zero_rows ? " (zero rows)" : "");
    }
  }
}

TEST_P(PaddedPlanTest, ForwardMatchesTheDefinition) {
  CheckForwardAgainstDefinition(GetParam(), false);
}

TEST_P(PaddedPlanTest, ForwardOfZeroRowsMatchesTheDefinition) {
  CheckForwardAgainstDefinition(GetParam(), true);
}

TEST_P(PaddedPlanTest, BackwardOfForwardGivesTheFieldTimesTheSize) {
  const Shape s = GetParam();
  PaddedPlan2d plan(s.n0, s.n1);
  const std::vector<double> in = RandomField(s, 11);
  ComplexBuffer spectrum(plan.complex_size()), rows(plan.row_buffer_size());
  PaddedPlan2d::Staging staging(plan);
  plan.Forward(in.data(), s.ny, s.nx, spectrum.data(), rows.data(), staging);
  std::vector<double> out(in.size(), -99.0);
  plan.Backward(spectrum.data(), s.ny, s.nx, out.data(), rows.data());
  const double n = static_cast<double>(s.n0) * s.n1;
  for (std::size_t k = 0; k < in.size(); ++k) EXPECT_NEAR(out[k] / n, in[k], 1e-13) << k;
}

INSTANTIATE_TEST_SUITE_P(
    Shapes, PaddedPlanTest,
    ::testing::Values(Shape{2, 2, 1, 1}, Shape{6, 10, 3, 5}, Shape{8, 12, 4, 6}, Shape{10, 6, 5, 2},
                      Shape{12, 16, 7, 8}, Shape{16, 20, 16, 20}, Shape{20, 12, 9, 6},
                      // Lengths with factors 7, 11 and 13, which
                      // FastSizes picks (e.g. 70, 98, 154, 176).
                      Shape{14, 22, 7, 11}, Shape{26, 28, 13, 14}, Shape{22, 14, 11, 7}));

TEST(PaddedPlan, RejectsOddSizes) {
  EXPECT_THROW(PaddedPlan2d(5, 8), std::invalid_argument);
  EXPECT_THROW(PaddedPlan2d(8, 0), std::invalid_argument);
}

TEST(PaddedPlan, FastSizesAreEvenProductsOfTwoThreeOrFive) {
  EXPECT_EQ(PaddedPlan2d::FastSize(1), 2);
  EXPECT_EQ(PaddedPlan2d::FastSize(145), 160);
  EXPECT_EQ(PaddedPlan2d::FastSize(167), 192);
  EXPECT_EQ(PaddedPlan2d::FastSize(257), 320);
}

TEST(PaddedPlan, FastSizesCoverTheRequestWithEvenLengths) {
  // Every request from 1 to 600 values per direction (a linear convolution of up to 300
  // elements) gets even lengths of at least the request, from the table up to 1024 and
  // FastSize beyond; each at most twice the request (or FastSize's).
  for (int m0 = 1; m0 <= 600; m0 += 7) {
    for (int m1 = 1; m1 <= 600; m1 += 11) {
      const auto [n0, n1] = PaddedPlan2d::FastSizes(m0, m1);
      ASSERT_TRUE(n0 >= m0 && n1 >= m1) << m0 << " " << m1;
      ASSERT_TRUE(n0 % 2 == 0 && n1 % 2 == 0) << m0 << " " << m1;
      ASSERT_LE(n0, std::max(2 * m0, PaddedPlan2d::FastSize(m0))) << m0;
      ASSERT_LE(n1, std::max(2 * m1, PaddedPlan2d::FastSize(m1))) << m1;
    }
  }
  const auto [big0, big1] = PaddedPlan2d::FastSizes(1500, 2100);
  EXPECT_EQ(big0, PaddedPlan2d::FastSize(1500));
  EXPECT_EQ(big1, PaddedPlan2d::FastSize(2100));
}

}  // namespace
}  // namespace wrc::fftw
