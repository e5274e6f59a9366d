// Interpolation accuracy, derivatives and flags, through the C++ API (wrc::Table).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "tests/runtime/table_writer.h"
#include "wrc/runtime.hpp"

namespace {

using wrc::Interpolation;
using wrc::Table;
using wrc::test::Linspace;
using wrc::test::ScratchFile;
using wrc::test::TableContent;

// Non-uniform axes: the spacing varies by up to ±20 % (fixed seed), so nothing relies on a
// uniform grid.
std::vector<double> Jittered(double first, double last, int n, unsigned seed) {
  std::vector<double> values = Linspace(first, last, n);
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  const double h = (last - first) / (n - 1);
  for (int i = 1; i + 1 < n; ++i) values[static_cast<std::size_t>(i)] += jitter(random) * h;
  return values;
}

std::vector<double> RandomPoint(const Table& table, std::mt19937& random) {
  std::vector<double> point(static_cast<std::size_t>(table.num_axes()));
  for (int a = 0; a < table.num_axes(); ++a) {
    const std::vector<double> values = table.axis_values(a);
    point[static_cast<std::size_t>(a)] =
        std::uniform_real_distribution<double>(values.front(), values.back())(random);
  }
  return point;
}

// ---------------------------------------------------------------------------------------------
// Exactness

TEST(RuntimeInterpolation, ReproducesNodeValuesExactly) {
  ScratchFile scratch("nodes");
  TableContent content;
  content.axes = {{"y", Jittered(-10, 10, 9, 1)},
                  {"yaw", Jittered(-0.01, 0.01, 5, 2)},
                  {"spin", Jittered(-0.01, 0.01, 6, 3)}};
  content.outputs = {"fx", "fy"};
  content.function = [](int k, const std::vector<double>& x) {  // Rough data: limiter active.
    return std::sin(3.0 * x[0] + 700.0 * x[1] * (k + 1)) + std::cos(900.0 * x[2]);
  };
  wrc::test::WriteTable(scratch.path(), content);
  for (Interpolation mode : {Interpolation::kLinear, Interpolation::kCubic}) {
    Table table(scratch.path());
    table.set_interpolation(mode);
    const auto& ys = content.axes[0].values;
    const auto& yaws = content.axes[1].values;
    const auto& spins = content.axes[2].values;
    for (double y : ys) {
      for (double yaw : yaws) {
        for (double spin : spins) {
          const std::vector<double> point = {y, yaw, spin};
          int flags = -1;
          const std::vector<double> out = table.eval(point, &flags);
          EXPECT_EQ(flags, 0);
          // Exact: at a node t is exactly 0 or 1, so every other weight is exactly 0.
          EXPECT_EQ(out[0], content.function(0, point));
          EXPECT_EQ(out[1], content.function(1, point));
        }
      }
    }
  }
}

TEST(RuntimeInterpolation, MultilinearReproducesMultilinearFunctions) {
  ScratchFile scratch("multilinear");
  TableContent content;
  content.axes = {{"y", Jittered(-10, 10, 7, 4)},
                  {"roll", {-0.002, 0.0, 0.002}},
                  {"yaw", Jittered(-0.01, 0.01, 4, 5)},
                  {"spin", Jittered(-0.01, 0.01, 5, 6)}};
  content.outputs = {"f"};
  auto f = [](const std::vector<double>& x) {
    const double y = x[0] / 10.0, roll = x[1] / 0.002, yaw = x[2] / 0.01, spin = x[3] / 0.01;
    return 3.0 + 2.0 * y - roll + 0.5 * yaw * spin + 4.0 * y * roll * yaw -
           1.5 * y * roll * yaw * spin;
  };
  content.function = [&](int, const std::vector<double>& x) { return f(x); };
  wrc::test::WriteTable(scratch.path(), content);
  Table table(scratch.path());
  std::mt19937 random(11);
  double worst = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const std::vector<double> point = RandomPoint(table, random);
    worst = std::max(worst, std::abs(table.eval(point)[0] - f(point)));
  }
  // |f| <= 12.5; 16 corner terms rounded at 1.1e-16 relative each: 1e-13 leaves room.
  EXPECT_LT(worst, 1e-13);
}

// p, q, r: cubics that are monotone and resolved by the grids below, so the limiter leaves the
// slope estimates (exact for cubics) unchanged everywhere.
double P(double y) { return y * y * y / 3.0 + y + 5.0; }  // p' = y² + 1 in [1, 5] on [-2, 2]
double Pd(double y) { return y * y + 1.0; }
double Q(double roll) { return 3.0 + roll + 0.2 * roll * roll * roll; }  // q > 0, q' in [1, 1.6]
double Qd(double roll) { return 1.0 + 0.6 * roll * roll; }
double R(double yaw) { return 0.5 * yaw * yaw * yaw + 2.0 * yaw; }  // r' = 1.5 yaw² + 2
double Rd(double yaw) { return 1.5 * yaw * yaw + 2.0; }

TEST(RuntimeInterpolation, CubicReproducesFunctionsCubicAlongEachAxis) {
  // f = p(y)·q(roll) + r(yaw) is cubic along each axis, with non-zero mixed derivative in
  // (y, roll). Each grid line is monotone with slopes within 3× the adjacent secants, so no
  // limiter acts and the tensor Hermite interpolant equals f, derivatives included, in every
  // cell including the boundary cells (the five-point slope windows are exact for cubics there
  // as well). See CubicLimiterTradesExactnessAtExtrema for what happens where the data are not
  // monotone.
  ScratchFile scratch("cubic");
  TableContent content;
  content.axes = {{"y", Jittered(-2, 2, 9, 7)},
                  {"roll", Jittered(-1, 1, 6, 8)},
                  {"yaw", Jittered(-1, 1, 7, 9)}};
  content.outputs = {"f", "g"};
  content.function = [](int k, const std::vector<double>& x) {
    return k == 0 ? P(x[0]) * Q(x[1]) + R(x[2]) : R(x[2]) - 2.0 * Q(x[1]);
  };
  wrc::test::WriteTable(scratch.path(), content);
  Table table(scratch.path());
  table.set_interpolation(Interpolation::kCubic);
  std::mt19937 random(12);
  double worst_value = 0.0;
  double worst_derivative = 0.0;
  for (int i = 0; i < 3000; ++i) {
    const std::vector<double> x = RandomPoint(table, random);
    double out[2];
    double d_out[2 * 3];
    ASSERT_EQ(table.eval(x.data(), out, d_out), 0);
    worst_value = std::max(worst_value, std::abs(out[0] - (P(x[0]) * Q(x[1]) + R(x[2]))));
    worst_value = std::max(worst_value, std::abs(out[1] - (R(x[2]) - 2.0 * Q(x[1]))));
    const double exact[2][3] = {{Pd(x[0]) * Q(x[1]), P(x[0]) * Qd(x[1]), Rd(x[2])},
                                {0.0, -2.0 * Qd(x[1]), Rd(x[2])}};
    for (int k = 0; k < 2; ++k) {
      for (int a = 0; a < 3; ++a) {
        worst_derivative = std::max(worst_derivative, std::abs(d_out[k * 3 + a] - exact[k][a]));
      }
    }
  }
  // |f| <= 40 and |f'| <= 35: rounding of the slope estimates (differences of nearby values
  // divided by h ~ 0.5, ~1e-15 each) and of 64 Hermite terms stays below 1e-11; a single
  // limited slope would cause errors of order h·|f'|·4/27 ~ 1e-1.
  EXPECT_LT(worst_value, 1e-11);
  EXPECT_LT(worst_derivative, 1e-10);
}

TEST(RuntimeInterpolation, CubicLimiterTradesExactnessAtExtrema) {
  // f = x³ - x on nodes -2, -1.5, ..., 2 (h = 0.5). The data have extrema at x = ±0.5 (secants
  // 0.75 and -0.75 meet there), where the limiter sets the slope to 0 instead of f'(±0.5) =
  // -0.25. In the four cells touching those nodes the interpolant therefore differs from f by
  // exactly h·h11(t)·0.25 (or h·h10(t)·0.25), at most 0.5·0.25·4/27 = 0.00926 at t = 1/3 or 2/3.
  // Everywhere else the slope estimates are monotone-consistent (e.g. at x = -1: f' = 2 <=
  // 3·min(3.75, 0.75) = 2.25) and f is reproduced exactly. Along the axis the interpolant never
  // leaves the range of its cell's node values.
  ScratchFile scratch("extrema");
  TableContent content;
  content.axes = {{"y", Linspace(-2.0, 2.0, 9)}};
  content.outputs = {"f"};
  auto f = [](double x) { return x * x * x - x; };
  content.function = [&](int, const std::vector<double>& x) { return f(x[0]); };
  wrc::test::WriteTable(scratch.path(), content);
  Table table(scratch.path());
  table.set_interpolation(Interpolation::kCubic);
  const double bound = 0.5 * 0.25 * 4.0 / 27.0;
  double worst_exact_cells = 0.0;
  double worst_limited_cells = 0.0;
  for (int i = 0; i <= 4000; ++i) {
    const double x = -2.0 + 4.0 * i / 4000.0;
    const double value = table.eval(std::vector<double>{x})[0];
    const double error = std::abs(value - f(x));
    const double cell_start = -2.0 + 0.5 * std::floor((x + 2.0) / 0.5);
    if (std::abs(x) < 1.0) {
      worst_limited_cells = std::max(worst_limited_cells, error);
    } else {
      worst_exact_cells = std::max(worst_exact_cells, error);
    }
    if (x < 2.0) {  // No overshoot: within the cell's node values (1e-12: rounding).
      const double a = f(cell_start);
      const double b = f(cell_start + 0.5);
      EXPECT_GE(value, std::min(a, b) - 1e-12) << "x = " << x;
      EXPECT_LE(value, std::max(a, b) + 1e-12) << "x = " << x;
    }
  }
  EXPECT_LT(worst_exact_cells, 1e-12);  // |f| <= 6: rounding only.
  EXPECT_LE(worst_limited_cells, bound + 1e-12);
  EXPECT_GT(worst_limited_cells, 0.99 * bound);  // The samples hit t = 1/3 within 1 %.
}

TEST(RuntimeInterpolation, CubicDoesNotOvershootAtAContactJump) {
  // A flange-contact-like jump in y: the force is 0 before contact, then jumps to a level that
  // grows with y and spin. Multilinear and cubic must both stay within the data range, and the
  // no-contact plateau must stay exactly 0 (an overshooting spline would ring there).
  ScratchFile scratch("jump");
  TableContent content;
  content.axes = {{"y", Linspace(-10.0, 10.0, 21)}, {"spin", Linspace(-0.01, 0.01, 9)}};
  content.outputs = {"fy"};
  content.function = [](int, const std::vector<double>& x) {
    return x[0] < 3.2 ? 0.0 : 20000.0 + 500.0 * x[0] + 1e5 * x[1];
  };
  wrc::test::WriteTable(scratch.path(), content);
  Table table(scratch.path());
  table.set_interpolation(Interpolation::kCubic);
  std::mt19937 random(13);
  for (int i = 0; i < 5000; ++i) {
    const std::vector<double> x = RandomPoint(table, random);
    const double value = table.eval(x)[0];
    if (x[0] <= 3.0) {
      EXPECT_EQ(value, 0.0) << "y = " << x[0];  // Plateau: all node data there are exactly 0.
    }
    EXPECT_GE(value, 0.0);
    EXPECT_LE(value, 20000.0 + 500.0 * 10.0 + 1e5 * 0.01);
    // Between y = 3 and 4 the value rises monotonically from 0 to the level at y = 4.
    if (x[0] > 3.0 && x[0] < 4.0) {
      EXPECT_LE(value, 20000.0 + 500.0 * 4.0 + 1e5 * x[1] + 1e-9) << "y = " << x[0];
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Derivatives and smoothness

TableContent SmoothTable() {
  TableContent content;
  content.axes = {{"y", Jittered(-10, 10, 11, 21)},
                  {"yaw", Jittered(-0.01, 0.01, 6, 22)},
                  {"spin", Jittered(-0.01, 0.01, 7, 23)}};
  content.outputs = {"fx", "fy", "fz"};
  content.function = [](int k, const std::vector<double>& x) {
    return std::sin(0.3 * x[0] + k) * std::cos(150.0 * x[1]) + 50.0 * x[2] * (k + 1) +
           std::sin(200.0 * x[2] - k);
  };
  return content;
}

TEST(RuntimeInterpolation, DerivativesMatchFiniteDifferences) {
  ScratchFile scratch("derivatives");
  const TableContent content = SmoothTable();
  wrc::test::WriteTable(scratch.path(), content);
  for (Interpolation mode : {Interpolation::kLinear, Interpolation::kCubic}) {
    Table table(scratch.path());
    table.set_interpolation(mode);
    std::mt19937 random(14);
    double worst = 0.0;
    for (int i = 0; i < 500; ++i) {
      std::vector<double> x = RandomPoint(table, random);
      double out[3];
      double d_out[3 * 3];
      ASSERT_GE(table.eval(x.data(), out, d_out), 0);
      for (int a = 0; a < 3; ++a) {
        const std::vector<double> axis = table.axis_values(a);
        // Central difference with a step of 1e-7 of the axis range: truncation ~ (step)²·f'''
        // and rounding ~ 1e-16·|f|/step, both far below the 1e-5 relative tolerance. Skip
        // points whose stencil crosses a node (multilinear derivatives jump there).
        const double step = 1e-7 * (axis.back() - axis.front());
        const auto next = std::upper_bound(axis.begin(), axis.end(), x[a] - step);
        if (next == axis.end() || *next <= x[a] + step) continue;
        std::vector<double> plus = x;
        std::vector<double> minus = x;
        plus[a] += step;
        minus[a] -= step;
        const std::vector<double> f_plus = table.eval(plus);
        const std::vector<double> f_minus = table.eval(minus);
        for (int k = 0; k < 3; ++k) {
          const double difference = (f_plus[k] - f_minus[k]) / (2.0 * step);
          const double scale = 1.0 + std::abs(difference);
          worst = std::max(worst, std::abs(d_out[k * 3 + a] - difference) / scale);
        }
      }
    }
    EXPECT_LT(worst, 1e-5) << "mode " << static_cast<int>(mode);
  }
}

TEST(RuntimeInterpolation, CubicIsContinuouslyDifferentiableAcrossCells) {
  // Rough data (limiter active at many nodes): the derivative just below and just above every
  // interior node agrees in cubic mode; multilinear derivatives jump there (which shows the test
  // can see a jump).
  ScratchFile scratch("c1");
  const TableContent content = SmoothTable();
  wrc::test::WriteTable(scratch.path(), content);
  Table cubic(scratch.path());
  cubic.set_interpolation(Interpolation::kCubic);
  Table linear(scratch.path());
  std::mt19937 random(15);
  double worst_cubic = 0.0;
  double largest_linear = 0.0;
  for (int i = 0; i < 200; ++i) {
    std::vector<double> x = RandomPoint(cubic, random);
    for (int a = 0; a < 3; ++a) {
      const std::vector<double> axis = cubic.axis_values(a);
      for (std::size_t node = 1; node + 1 < axis.size(); ++node) {
        // 1e-9 of the local step: the derivative changes by ~1e-9·h·f'' across the gap, i.e.
        // ~1e-9 relative, well under the 1e-6 tolerance; a C¹ failure would show as O(1).
        const double gap = 1e-9 * (axis[node + 1] - axis[node - 1]);
        std::vector<double> below = x;
        std::vector<double> above = x;
        below[a] = axis[node] - gap;
        above[a] = axis[node] + gap;
        for (Table* table : {&cubic, &linear}) {
          double out[3];
          double d_below[9];
          double d_above[9];
          table->eval(below.data(), out, d_below);
          table->eval(above.data(), out, d_above);
          for (int k = 0; k < 3; ++k) {
            const double scale = 1.0 + std::abs(d_below[k * 3 + a]);
            const double jump = std::abs(d_above[k * 3 + a] - d_below[k * 3 + a]) / scale;
            if (table == &cubic) {
              worst_cubic = std::max(worst_cubic, jump);
            } else {
              largest_linear = std::max(largest_linear, jump);
            }
          }
        }
      }
    }
  }
  EXPECT_LT(worst_cubic, 1e-6);
  EXPECT_GT(largest_linear, 1e-2);
}

TEST(RuntimeInterpolation, ValuesDoNotDependOnAskingForDerivatives) {
  // eval and eval with derivatives sum the values in the same order: bitwise the same results
  // (an integrator may mix both kinds of call).
  ScratchFile scratch_3d("same-3d");
  wrc::test::WriteTable(scratch_3d.path(), SmoothTable());
  ScratchFile scratch_4d("same-4d");
  TableContent content;
  content.axes = {{"y", Jittered(-10, 10, 9, 31)},
                  {"roll", Linspace(-0.002, 0.002, 5)},
                  {"yaw", Jittered(-0.01, 0.01, 5, 32)},
                  {"spin", Linspace(-0.01, 0.01, 7)}};
  content.outputs = {"fx", "fy", "fz", "mx", "my", "mz"};
  content.function = [](int k, const std::vector<double>& x) {
    return std::sin(0.3 * x[0] + k) * (1.0 + 300.0 * x[1]) + std::tanh(300.0 * x[3]) * x[2];
  };
  wrc::test::WriteTable(scratch_4d.path(), content);
  for (const std::string& path : {scratch_3d.path(), scratch_4d.path()}) {
    for (Interpolation mode : {Interpolation::kLinear, Interpolation::kCubic}) {
      Table table(path);
      table.set_interpolation(mode);
      std::mt19937 random(16);
      const std::size_t n_out = static_cast<std::size_t>(table.num_outputs());
      std::vector<double> values(n_out);
      std::vector<double> with_derivatives(n_out);
      std::vector<double> d_out(n_out * static_cast<std::size_t>(table.num_axes()));
      int mismatches = 0;
      for (int i = 0; i < 300; ++i) {
        const std::vector<double> x = RandomPoint(table, random);
        table.eval(x.data(), values.data());
        table.eval(x.data(), with_derivatives.data(), d_out.data());
        mismatches += values != with_derivatives;
      }
      EXPECT_EQ(mismatches, 0) << path << ", mode " << static_cast<int>(mode);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Flags and errors

TEST(RuntimeInterpolation, OutOfRangePointsAreClampedAndFlagged) {
  ScratchFile scratch("clamp");
  TableContent content;
  content.axes = {{"y", Linspace(-10, 10, 5)}, {"spin", Linspace(-0.01, 0.01, 3)}};
  content.outputs = {"f"};
  content.function = [](int, const std::vector<double>& x) { return x[0] + 1000.0 * x[1]; };
  wrc::test::WriteTable(scratch.path(), content);
  for (Interpolation mode : {Interpolation::kLinear, Interpolation::kCubic}) {
    Table table(scratch.path());
    table.set_interpolation(mode);
    double out[1];
    double d_out[2];
    const double outside[2] = {12.0, 0.005};
    EXPECT_EQ(table.eval(outside, out, d_out), WRC_FLAG_CLAMPED);
    EXPECT_NEAR(out[0], 10.0 + 5.0, 1e-12);  // Value at y = 10 (|f| <= 20: rounding only).
    EXPECT_EQ(d_out[0], 0.0);                // f(clamp(y)) is flat in y out there.
    EXPECT_NEAR(d_out[1], 1000.0, 1e-9);     // Still the slope in spin.
    const double far_below[2] = {-std::numeric_limits<double>::infinity(), -1.0};
    EXPECT_EQ(table.eval(far_below, out, d_out), WRC_FLAG_CLAMPED);
    EXPECT_NEAR(out[0], -10.0 - 10.0, 1e-12);
    const double on_edge[2] = {10.0, 0.01};  // On the boundary is inside.
    EXPECT_EQ(table.eval(on_edge, out), 0);
    EXPECT_NEAR(out[0], 20.0, 1e-12);
  }
}

TEST(RuntimeInterpolation, NanInputIsAnErrorNeverANanOutput) {
  ScratchFile scratch("nan-input");
  TableContent content;
  content.axes = {{"y", Linspace(-10, 10, 5)}, {"spin", Linspace(-0.01, 0.01, 3)}};
  content.outputs = {"f"};
  content.function = [](int, const std::vector<double>& x) { return x[0]; };
  wrc::test::WriteTable(scratch.path(), content);
  Table table(scratch.path());
  double out[1] = {123.0};
  const double point[2] = {0.0, std::nan("")};
  EXPECT_EQ(table.try_eval(point, out), WRC_ERR_NAN_INPUT);
  const std::string message = wrc_last_error();
  EXPECT_NE(message.find("point[1] (axis 'spin') is NaN"), std::string::npos) << message;
  EXPECT_NE(message.find(scratch.path()), std::string::npos) << message;
  try {
    table.eval(point, out);
    ADD_FAILURE() << "no exception";
  } catch (const wrc::TableError& error) {
    EXPECT_EQ(error.code(), WRC_ERR_NAN_INPUT);
  }
}

TEST(RuntimeInterpolation, PointsNextToFailedNodesAreFlagged) {
  // One node (y = 0, spin = 0) did not converge (status 2) but holds a finite value. The flag
  // covers exactly the cells whose result uses it: the 4 cells around it for multilinear; for
  // cubic, cell i along an axis uses nodes i-2 .. i+3 (the five-node slope windows of its two
  // corners), so 6 cells per axis.
  ScratchFile scratch("status");
  TableContent content;
  content.axes = {{"y", Linspace(-10, 10, 21)}, {"spin", Linspace(-0.01, 0.01, 21)}};
  content.outputs = {"f"};
  content.function = [](int, const std::vector<double>& x) { return x[0] * x[1]; };
  content.status = [](const std::vector<double>& x) -> std::int8_t {
    return x[0] == 0.0 && x[1] == 0.0 ? 2 : 0;
  };
  wrc::test::WriteTable(scratch.path(), content);
  Table linear(scratch.path());
  Table cubic(scratch.path());
  cubic.set_interpolation(Interpolation::kCubic);
  double out[1];
  auto flags = [&](const Table& table, double y_cell, double spin_cell) {
    // Centre of the cell whose lower corner is (y_cell, spin_cell) in node units.
    const double point[2] = {y_cell + 0.5, (spin_cell + 0.5) * 0.001};
    return table.eval(point, out);
  };
  EXPECT_EQ(flags(linear, 0, 0), WRC_FLAG_STATUS);
  EXPECT_EQ(flags(linear, -1, -1), WRC_FLAG_STATUS);
  EXPECT_EQ(flags(linear, -1, 0), WRC_FLAG_STATUS);
  EXPECT_EQ(flags(linear, 1, 0), 0);
  EXPECT_EQ(flags(linear, -2, -1), 0);
  EXPECT_EQ(flags(cubic, 0, 0), WRC_FLAG_STATUS);
  EXPECT_EQ(flags(cubic, 2, 0), WRC_FLAG_STATUS);   // Lower corner's window reaches 2 back.
  EXPECT_EQ(flags(cubic, -3, 0), WRC_FLAG_STATUS);  // Upper corner's window reaches 2 ahead.
  EXPECT_EQ(flags(cubic, 2, -3), WRC_FLAG_STATUS);
  EXPECT_EQ(flags(cubic, 3, 0), 0);
  EXPECT_EQ(flags(cubic, -4, 0), 0);
  EXPECT_EQ(flags(cubic, 0, 3), 0);
}

// A failed node (status 3) stored as NaN in a table of linear data. In the cells around it the
// valid corners decide (their multilinear weights renormalised), in both modes, flagged; one
// cell further away both modes interpolate as usual.
TEST(RuntimeInterpolation, NextToAFailedNodeTheValidCornersDecide) {
  ScratchFile scratch("nan-node");
  TableContent content;
  content.axes = {{"y", Linspace(-10, 10, 21)}, {"spin", Linspace(-0.01, 0.01, 11)}};
  content.outputs = {"fx", "fz"};
  auto failed = [](const std::vector<double>& x) { return x[0] == 4.0 && x[1] == 0.0; };
  auto f = [](int k, double y, double spin) { return y * (k + 1) + 100.0 * spin; };
  content.function = [&](int k, const std::vector<double>& x) {
    return failed(x) ? std::numeric_limits<double>::quiet_NaN() : f(k, x[0], x[1]);
  };
  content.status = [&](const std::vector<double>& x) -> std::int8_t { return failed(x) ? 3 : 0; };
  wrc::test::WriteTable(scratch.path(), content);
  for (Interpolation mode : {Interpolation::kLinear, Interpolation::kCubic}) {
    Table table(scratch.path());
    table.set_interpolation(mode);
    double out[2];
    double d_out[4];
    // The middle of the cell y in [3, 4], spin in [0, 0.002]: the three valid corners weigh
    // 1/4 each, renormalised to 1/3.
    const double touching[2] = {3.5, 0.001};
    EXPECT_EQ(table.try_eval(touching, out, d_out), WRC_FLAG_STATUS);
    for (int k = 0; k < 2; ++k) {
      const double mean = (f(k, 3.0, 0.0) + f(k, 3.0, 0.002) + f(k, 4.0, 0.002)) / 3.0;
      EXPECT_NEAR(out[k], mean, 1e-12) << "output " << k;
    }
    // Derivatives: those of the function returned, against central differences.
    constexpr double kStep = 1e-7;  // well inside the cell; the error is O(step²) ~ 1e-14
    double plus[2], minus[2];
    for (int a = 0; a < 2; ++a) {
      const double h = kStep * (a == 0 ? 1.0 : 0.002);
      double p[2] = {touching[0], touching[1]}, m[2] = {touching[0], touching[1]};
      p[a] += h;
      m[a] -= h;
      table.try_eval(p, plus);
      table.try_eval(m, minus);
      for (int k = 0; k < 2; ++k) {
        EXPECT_NEAR(d_out[k * 2 + a], (plus[k] - minus[k]) / (2.0 * h),
                    1e-6 * std::fabs(d_out[k * 2 + a]) + 1e-6)
            << "output " << k << " axis " << a;
      }
    }
    // A valid node next to the failed one keeps its value exactly.
    const double valid_node[2] = {3.0, 0.0};
    EXPECT_EQ(table.try_eval(valid_node, out), WRC_FLAG_STATUS);
    EXPECT_EQ(out[0], f(0, 3.0, 0.0));
    // At the failed node itself, where only the failed corner has weight, the nearest valid
    // corners decide: a finite value between theirs.
    const double at_failed[2] = {4.0, 0.0};
    EXPECT_EQ(table.try_eval(at_failed, out), WRC_FLAG_STATUS);
    EXPECT_GE(out[0], std::min(f(0, 5.0, 0.0), f(0, 4.0, 0.002)));
    EXPECT_LE(out[0], std::max(f(0, 5.0, 0.0), f(0, 4.0, 0.002)));
    const double next_cell[2] = {2.5, 0.001};
    EXPECT_EQ(table.try_eval(next_cell, out, d_out),
              WRC_FLAG_STATUS * (mode == Interpolation::kCubic));
    for (double d : d_out) EXPECT_TRUE(std::isfinite(d));
    // Linear data next to the gap: the cubic windows shrink but stay exact for linear data.
    EXPECT_NEAR(out[0], 2.5 + 0.1, 1e-12);
    EXPECT_NEAR(out[1], 5.0 + 0.1, 1e-12);
  }
}

// A cell whose every node failed has no data: WRC_ERR_NO_DATA, and wrc_last_error() says so,
// in both modes; the outputs are NaN there, not stale values.
TEST(RuntimeInterpolation, ACellWhoseNodesAllFailedIsNoData) {
  ScratchFile scratch("failed-cell");
  TableContent content;
  content.axes = {{"y", Linspace(0, 10, 11)}, {"spin", Linspace(-0.01, 0.01, 5)}};
  content.outputs = {"fx"};
  auto failed = [](const std::vector<double>& x) { return x[0] >= 7.0 && x[0] <= 8.0; };
  content.function = [&](int, const std::vector<double>& x) {
    return failed(x) ? std::numeric_limits<double>::quiet_NaN() : x[0];
  };
  content.status = [&](const std::vector<double>& x) -> std::int8_t { return failed(x) ? 3 : 0; };
  wrc::test::WriteTable(scratch.path(), content);
  for (Interpolation mode : {Interpolation::kLinear, Interpolation::kCubic}) {
    Table table(scratch.path());
    table.set_interpolation(mode);
    double out[1];
    const double inside[2] = {7.5, 0.003};
    EXPECT_EQ(table.try_eval(inside, out), WRC_ERR_NO_DATA);
    EXPECT_NE(std::string(wrc_last_error()).find("every node of the cell failed"),
              std::string::npos)
        << wrc_last_error();
    EXPECT_NE(std::string(wrc_last_error()).find("'fx'"), std::string::npos);
    EXPECT_TRUE(std::isnan(out[0]));
    // The cells either side have valid nodes on their far face: those decide.
    const double below[2] = {6.5, 0.003};
    EXPECT_EQ(table.try_eval(below, out), WRC_FLAG_STATUS);
    EXPECT_DOUBLE_EQ(out[0], 6.0);
    const double above[2] = {8.25, 0.003};
    EXPECT_EQ(table.try_eval(above, out), WRC_FLAG_STATUS);
    EXPECT_DOUBLE_EQ(out[0], 9.0);
  }
}

// Nodes failed at random (fixed seed, 15 %) in a 3-axis table: no finite point inside the table
// gives NaN. Where a cell has a valid corner the result is finite, flagged, and (linear
// fallback: a convex combination) between the smallest and largest valid corner value; in
// cubic mode such cells give the same fallback. Only cells without any valid corner are
// WRC_ERR_NO_DATA.
TEST(RuntimeInterpolation, RandomlyFailedNodesNeverGiveNan) {
  ScratchFile scratch("random-holes");
  TableContent content;
  const std::vector<double> ys = Linspace(8, 16, 9), rolls = Linspace(-0.002, 0.002, 3),
                            yaws = Linspace(-0.005, 0.005, 5);
  content.axes = {{"y", ys}, {"roll", rolls}, {"yaw", yaws}};
  content.outputs = {"fy", "fz"};
  std::mt19937 random(2026);
  std::bernoulli_distribution fails(0.15);
  std::vector<bool> failed_node(ys.size() * rolls.size() * yaws.size());
  for (std::size_t n = 0; n < failed_node.size(); ++n) failed_node[n] = fails(random);
  auto index = [&](std::size_t i, std::size_t j, std::size_t k) {
    return (i * rolls.size() + j) * yaws.size() + k;
  };
  auto node_of = [&](const std::vector<double>& x) {
    auto at = [](const std::vector<double>& v, double c) {
      return static_cast<std::size_t>(std::find(v.begin(), v.end(), c) - v.begin());
    };
    return index(at(ys, x[0]), at(rolls, x[1]), at(yaws, x[2]));
  };
  auto f = [](int k, const std::vector<double>& x) {
    return (k + 1) * 1e4 * std::sin(x[0]) + 1e6 * x[1] - 3e5 * x[2];
  };
  content.function = [&](int k, const std::vector<double>& x) {
    return failed_node[node_of(x)] ? std::numeric_limits<double>::quiet_NaN() : f(k, x);
  };
  content.status = [&](const std::vector<double>& x) -> std::int8_t {
    return failed_node[node_of(x)] ? 3 : 0;
  };
  wrc::test::WriteTable(scratch.path(), content);
  Table linear(scratch.path());
  Table cubic(scratch.path());
  cubic.set_interpolation(Interpolation::kCubic);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int fallbacks = 0, no_data = 0;
  for (int n = 0; n < 20000; ++n) {
    const double point[3] = {8.0 + 8.0 * unit(random), -0.002 + 0.004 * unit(random),
                             -0.005 + 0.01 * unit(random)};
    // The cell's corners, found independently of the runtime.
    const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(point[0] - 8.0), 7);
    const std::size_t j = point[1] < 0.0 ? 0 : 1;
    const std::size_t k =
        std::min<std::size_t>(static_cast<std::size_t>((point[2] + 0.005) / 0.0025), 3);
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    int valid = 0;
    for (int c = 0; c < 8; ++c) {
      const std::size_t ci = i + (c & 1), cj = j + (c >> 1 & 1), ck = k + (c >> 2 & 1);
      if (failed_node[index(ci, cj, ck)]) continue;
      ++valid;
      for (int o = 0; o < 2; ++o) {
        const double v = f(o, {ys[ci], rolls[cj], yaws[ck]});
        lo[o] = std::min(lo[o], v);
        hi[o] = std::max(hi[o], v);
      }
    }
    double out[2], out_cubic[2], d_out[6];
    const int code = linear.try_eval(point, out, d_out);
    const int code_cubic = cubic.try_eval(point, out_cubic);
    if (valid == 0) {
      ++no_data;
      EXPECT_EQ(code, WRC_ERR_NO_DATA);
      EXPECT_EQ(code_cubic, WRC_ERR_NO_DATA);
      continue;
    }
    ASSERT_GE(code, 0) << wrc_last_error();
    ASSERT_GE(code_cubic, 0) << wrc_last_error();
    for (int o = 0; o < 2; ++o) {
      ASSERT_TRUE(std::isfinite(out[o]) && std::isfinite(out_cubic[o]));
      for (int a = 0; a < 3; ++a) ASSERT_TRUE(std::isfinite(d_out[o * 3 + a]));
    }
    if (valid == 8) continue;
    ++fallbacks;
    EXPECT_EQ(code & WRC_FLAG_STATUS, WRC_FLAG_STATUS);
    for (int o = 0; o < 2; ++o) {
      // Round-off of the weighted mean: 1e-12 of the values' size (1e4).
      EXPECT_GE(out[o], lo[o] - 1e-8);
      EXPECT_LE(out[o], hi[o] + 1e-8);
      EXPECT_EQ(out_cubic[o], out[o]);
    }
  }
  EXPECT_GT(fallbacks, 1000);  // the test exercised the fallback
}

TEST(RuntimeInterpolation, SingleNodeAxesAreConstantDirections) {
  ScratchFile scratch("single");
  TableContent content;
  content.axes = {{"y", Linspace(-10, 10, 5)}, {"roll", {0.0}}, {"spin", Linspace(-0.01, 0.01, 5)}};
  content.outputs = {"f"};
  content.function = [](int, const std::vector<double>& x) { return x[0] + 100.0 * x[2]; };
  wrc::test::WriteTable(scratch.path(), content);
  for (Interpolation mode : {Interpolation::kLinear, Interpolation::kCubic}) {
    Table table(scratch.path());
    table.set_interpolation(mode);
    double out[1];
    double d_out[3];
    const double on_node[3] = {2.5, 0.0, 0.005};
    EXPECT_EQ(table.eval(on_node, out, d_out), 0);
    EXPECT_NEAR(out[0], 3.0, 1e-12);
    EXPECT_EQ(d_out[1], 0.0);
    EXPECT_NEAR(d_out[0], 1.0, 1e-12);
    EXPECT_NEAR(d_out[2], 100.0, 1e-9);
    const double off_node[3] = {2.5, 0.001, 0.005};
    EXPECT_EQ(table.eval(off_node, out), WRC_FLAG_CLAMPED);
    EXPECT_NEAR(out[0], 3.0, 1e-12);
  }
}

TEST(RuntimeInterpolation, ManyOutputsAreInterpolatedInChunks) {
  // 19 outputs: kernels handle up to 8 at once, so this takes chunks of 8, 8 and 3. Output k is
  // affine with k-dependent coefficients (reproduced exactly by both modes), so a mix-up between
  // outputs, chunks or derivative slots shows as an error of order 1.
  ScratchFile scratch("many");
  TableContent content;
  content.axes = {{"y", Jittered(-10, 10, 6, 31)},
                  {"yaw", Jittered(-0.01, 0.01, 5, 32)},
                  {"spin", Jittered(-0.01, 0.01, 4, 33)}};
  constexpr int kOutputs = 19;
  for (int k = 0; k < kOutputs; ++k) content.outputs.push_back("out" + std::to_string(k));
  auto f = [](int k, const std::vector<double>& x) {
    return k + (k + 1) * x[0] - 100.0 * k * x[1] + 1000.0 * (k % 3) * x[2];
  };
  content.function = f;
  wrc::test::WriteTable(scratch.path(), content);
  for (Interpolation mode : {Interpolation::kLinear, Interpolation::kCubic}) {
    Table table(scratch.path());
    table.set_interpolation(mode);
    std::mt19937 random(34);
    for (int i = 0; i < 200; ++i) {
      const std::vector<double> x = RandomPoint(table, random);
      double out[kOutputs];
      double d_out[kOutputs * 3];
      ASSERT_EQ(table.eval(x.data(), out, d_out), 0);
      for (int k = 0; k < kOutputs; ++k) {
        // |f| <= 240 and |f'| <= 2000: rounding only.
        EXPECT_NEAR(out[k], f(k, x), 1e-10) << "output " << k;
        EXPECT_NEAR(d_out[k * 3 + 0], k + 1.0, 1e-9) << "output " << k;
        EXPECT_NEAR(d_out[k * 3 + 1], -100.0 * k, 1e-8) << "output " << k;
        EXPECT_NEAR(d_out[k * 3 + 2], 1000.0 * (k % 3), 1e-8) << "output " << k;
      }
    }
  }
}

TEST(RuntimeInterpolation, CppApiReportsErrorsAsExceptions) {
  ScratchFile scratch("cpp");
  try {
    Table table(scratch.path());
    ADD_FAILURE() << "opened a missing file";
  } catch (const wrc::TableError& error) {
    EXPECT_EQ(error.code(), WRC_ERR_FILE);
    EXPECT_NE(std::string(error.what()).find(scratch.path()), std::string::npos);
  }
  TableContent content;
  content.axes = {{"y", Linspace(-1, 1, 3)}};
  content.outputs = {"a", "b"};
  content.function = [](int k, const std::vector<double>& x) { return k + x[0]; };
  wrc::test::WriteTable(scratch.path(), content);
  Table table(scratch.path());
  Table moved = std::move(table);
  EXPECT_EQ(table.get(), nullptr);
  EXPECT_EQ(moved.output_names(), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(moved.axis_names(), std::vector<std::string>{"y"});
  EXPECT_EQ(moved.output_index("b"), 1);
  EXPECT_THROW(moved.output_index("c"), wrc::TableError);
  EXPECT_THROW(moved.eval(std::vector<double>{1.0, 2.0}), wrc::TableError);
  EXPECT_EQ(moved.attribute("format"), "wrc-table");
  EXPECT_EQ(moved.interpolation(), Interpolation::kLinear);
  moved.set_interpolation(Interpolation::kCubic);
  EXPECT_EQ(moved.interpolation(), Interpolation::kCubic);
  EXPECT_NEAR(moved.eval(std::vector<double>{0.25})[1], 1.25, 1e-12);
}

}  // namespace
