// Concurrent evaluation of one handle from several threads gives exactly the serial results, and
// error messages stay per thread.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "tests/runtime/table_writer.h"
#include "wrc/runtime.h"

namespace {

constexpr int kThreads = 8;
constexpr int kOutputs = 6;
constexpr int kAxes = 4;

TEST(RuntimeThreads, ConcurrentEvaluationMatchesSerial) {
  wrc::test::ScratchFile scratch("threads");
  wrc::test::TableContent content;
  content.axes = {{"y", wrc::test::Linspace(-10, 10, 21)},
                  {"roll", {-0.002, 0.0, 0.002}},
                  {"yaw", wrc::test::Linspace(-0.01, 0.01, 5)},
                  {"spin", wrc::test::Linspace(-0.01, 0.01, 9)}};
  content.outputs = {"fx", "fy", "fz", "mx", "my", "mz"};
  content.function = [](int k, const std::vector<double>& x) {
    return std::sin(0.4 * x[0] + k) * (1.0 + 200.0 * x[1]) + std::tanh(400.0 * x[3]) * (k + 1) +
           50.0 * x[2];
  };
  wrc::test::WriteTable(scratch.path(), content);

  std::mt19937 random(41);
  std::uniform_real_distribution<double> unit(-1.1, 1.1);  // ~10 % of the points clamped.
  constexpr int kPoints = 3000;
  std::vector<double> points;
  for (int i = 0; i < kPoints; ++i) {
    points.push_back(10.0 * unit(random));
    points.push_back(0.002 * unit(random));
    points.push_back(0.01 * unit(random));
    points.push_back(0.01 * unit(random));
  }

  for (int mode : {WRC_INTERP_LINEAR, WRC_INTERP_CUBIC}) {
    wrc_table* table = nullptr;
    ASSERT_EQ(wrc_table_open(scratch.path().c_str(), &table), 0) << wrc_last_error();
    ASSERT_EQ(wrc_table_set_interpolation(table, mode), 0);
    std::vector<double> serial_out(kPoints * kOutputs);
    std::vector<double> serial_d_out(kPoints * kOutputs * kAxes);
    std::vector<int> serial_flags(kPoints);
    for (int i = 0; i < kPoints; ++i) {
      serial_flags[i] = wrc_table_eval_deriv(table, &points[i * kAxes], &serial_out[i * kOutputs],
                                             &serial_d_out[i * kOutputs * kAxes]);
      ASSERT_GE(serial_flags[i], 0);
    }

    // Every thread walks all points, starting at a different place, several times, and also
    // provokes its own NaN error on "its" axis to check that messages do not mix.
    std::vector<long> mismatches(kThreads, 0);
    std::vector<std::string> own_errors(kThreads);
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
      threads.emplace_back([&, t] {
        double out[kOutputs];
        double d_out[kOutputs * kAxes];
        double nan_point[kAxes] = {0.0, 0.0, 0.0, 0.0};
        nan_point[t % kAxes] = std::nan("");
        for (int round = 0; round < 4; ++round) {
          for (int n = 0; n < kPoints; ++n) {
            const int i = (n + t * kPoints / kThreads) % kPoints;
            const int flags = wrc_table_eval_deriv(table, &points[i * kAxes], out, d_out);
            const bool same =
                flags == serial_flags[i] &&
                std::memcmp(out, &serial_out[i * kOutputs], sizeof out) == 0 &&
                std::memcmp(d_out, &serial_d_out[i * kOutputs * kAxes], sizeof d_out) == 0;
            mismatches[t] += !same;
            if (n % 500 == 0) {
              wrc_table_eval(table, nan_point, out);
              own_errors[t] = wrc_last_error();
            }
          }
        }
      });
    }
    for (std::thread& thread : threads) thread.join();
    for (int t = 0; t < kThreads; ++t) {
      EXPECT_EQ(mismatches[t], 0) << "thread " << t << ", mode " << mode;
      const std::string expected =
          "point[" + std::to_string(t % kAxes) + "] (axis '" + content.axes[t % kAxes].name + "')";
      EXPECT_NE(own_errors[t].find(expected), std::string::npos) << own_errors[t];
    }
    wrc_table_close(table);
  }
}

}  // namespace
