// The interpolation sums exist in a baseline build and, on x86-64, an AVX2+FMA build chosen at
// load time (runtime/kernels.h). Every test in this binary runs the build this CPU selects; this
// one forces the baseline build with WRC_RUNTIME_ISA=baseline and checks that both agree, for
// 1 to 8 axes (every lower/upper split) and output counts that take each code path (one
// compile-time chunk, or several chunks of 8 with a partial last one).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "tests/runtime/table_writer.h"
#include "wrc/runtime.hpp"

namespace {

using wrc::Interpolation;
using wrc::Table;

// Opens path with the baseline kernels forced (the variable is read when a table is loaded).
Table OpenBaseline(const std::string& path) {
  ::setenv("WRC_RUNTIME_ISA", "baseline", 1);
  Table table(path);
  ::unsetenv("WRC_RUNTIME_ISA");
  return table;
}

TEST(RuntimeKernels, BaselineAndSelectedKernelsAgree) {
  for (int n_axes = 1; n_axes <= WRC_MAX_AXES; ++n_axes) {
    for (int n_outputs : {1, 6, 11}) {
      wrc::test::ScratchFile scratch("kernels");
      wrc::test::TableContent content;
      // 3 nodes per axis up to 5 axes, then 2 (cubic data grow as 2^D per node).
      const int nodes = n_axes <= 5 ? 3 : 2;
      for (int a = 0; a < n_axes; ++a) {
        content.axes.push_back({"x" + std::to_string(a), wrc::test::Linspace(-1.0, 1.0, nodes)});
      }
      for (int k = 0; k < n_outputs; ++k) content.outputs.push_back("f" + std::to_string(k));
      std::mt19937 values(static_cast<unsigned>(100 * n_axes + n_outputs));
      std::uniform_real_distribution<double> unit(-1.0, 1.0);
      content.function = [&](int, const std::vector<double>&) { return unit(values); };
      wrc::test::WriteTable(scratch.path(), content);
      for (Interpolation mode : {Interpolation::kLinear, Interpolation::kCubic}) {
        Table selected(scratch.path());
        Table baseline = OpenBaseline(scratch.path());
        selected.set_interpolation(mode);
        baseline.set_interpolation(mode);
        std::mt19937 random(7);
        std::uniform_real_distribution<double> coordinate(-1.1, 1.1);  // Some points clamped.
        double worst = 0.0;
        for (int i = 0; i < 50; ++i) {
          std::vector<double> point(static_cast<std::size_t>(n_axes));
          for (double& x : point) x = coordinate(random);
          std::vector<double> out_a(static_cast<std::size_t>(n_outputs));
          std::vector<double> out_b(out_a.size());
          std::vector<double> d_a(out_a.size() * static_cast<std::size_t>(n_axes));
          std::vector<double> d_b(d_a.size());
          ASSERT_EQ(selected.eval(point.data(), out_a.data(), d_a.data()),
                    baseline.eval(point.data(), out_b.data(), d_b.data()));
          for (std::size_t k = 0; k < out_a.size(); ++k) {
            worst = std::max(worst, std::abs(out_a[k] - out_b[k]));
          }
          for (std::size_t k = 0; k < d_a.size(); ++k) {
            worst = std::max(worst, std::abs(d_a[k] - d_b[k]) / (1.0 + std::abs(d_a[k])));
          }
        }
        // Data in [-1, 1]: the builds differ only in rounding (fused multiply-adds, summation
        // order within a vector), ~1e-16 per term over at most 4^8 terms.
        EXPECT_LT(worst, 1e-10) << n_axes << " axes, " << n_outputs << " outputs, mode "
                                << static_cast<int>(mode);
      }
    }
  }
}

}  // namespace
