// Float32 storage (wrc_table_set_storage): a lookup reads a float copy of the node data and sums
// in double, so it gives to the bit what float64 storage gives on a table whose values were
// rounded to float, in both modes' multilinear sums; the cubic data are rounded after they are
// built, within float rounding of the float64 lookups; switching back restores the float64
// lookups to the bit.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "tests/runtime/table_writer.h"
#include "wrc/runtime.h"
#include "wrc/runtime.hpp"

namespace {

using wrc::Interpolation;
using wrc::Storage;
using wrc::Table;

constexpr int kOutputs = 11;  // more than 8: the kernel's 12-lane pass

double Value(int k, const std::vector<double>& x) {
  return 1e4 * std::sin(0.3 * x[0] + k) + 3e6 * x[1] * x[2] - 2e5 * x[2] + 1e3 * k * x[0];
}

// y refined, yaw and spin uniform; `rounded`: the values as floats.
void Write(const std::string& path, bool rounded) {
  wrc::test::TableContent content;
  content.axes = {{"y", {-10.0, -4.0, -1.0, -0.5, 0.0, 0.25, 1.0, 3.0, 10.0}, "mm"},
                  {"yaw", wrc::test::Linspace(-0.01, 0.01, 5), "rad"},
                  {"spin", wrc::test::Linspace(-0.01, 0.01, 7), "-"}};
  for (int k = 0; k < kOutputs; ++k) content.outputs.push_back("out" + std::to_string(k));
  content.function = [rounded](int k, const std::vector<double>& x) {
    const double v = Value(k, x);
    return rounded ? static_cast<double>(static_cast<float>(v)) : v;
  };
  wrc::test::WriteTable(path, content);
}

// Points inside and a few outside (clamped).
std::vector<double> Points(int n) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1.05, 1.05);
  std::vector<double> points;
  for (int i = 0; i < n; ++i) {
    for (double scale : {10.0, 0.01, 0.01}) points.push_back(scale * unit(random));
  }
  return points;
}

class Storage32 : public ::testing::Test {
 protected:
  void SetUp() override {
    Write(exact_.path(), false);
    Write(rounded_.path(), true);
  }
  wrc::test::ScratchFile exact_{"storage-exact"};
  wrc::test::ScratchFile rounded_{"storage-rounded"};
};

TEST_F(Storage32, MultilinearLookupsAreThoseOfTheRoundedTable) {
  Table float32(exact_.path());
  float32.set_storage(Storage::kFloat32);
  EXPECT_EQ(float32.storage(), Storage::kFloat32);
  const Table rounded(rounded_.path());
  const std::vector<double> points = Points(20000);
  double a[kOutputs], b[kOutputs], da[kOutputs * 3], db[kOutputs * 3];
  for (std::size_t i = 0; i < points.size(); i += 3) {
    EXPECT_EQ(float32.eval(&points[i], a, da), rounded.eval(&points[i], b, db));
    for (int k = 0; k < kOutputs; ++k) ASSERT_EQ(a[k], b[k]) << i << ' ' << k;
    for (int k = 0; k < kOutputs * 3; ++k) ASSERT_EQ(da[k], db[k]) << i << ' ' << k;
  }
}

// The cubic data (values and mixed slopes) rounded to float: each lookup within float rounding
// of the float64 one, about 6e-8 of the largest |value| (1e4 here) times the few terms that
// matter; 1e-5 of it is 10 times that margin and far below the interpolation error.
TEST_F(Storage32, CubicLookupsStayWithinFloatRounding) {
  Table float64(exact_.path());
  Table float32(exact_.path());
  float64.set_interpolation(Interpolation::kCubic);
  float32.set_interpolation(Interpolation::kCubic);  // built in double, then switched
  float32.set_storage(Storage::kFloat32);
  Table float32_first(exact_.path());  // switched first, then built
  float32_first.set_storage(Storage::kFloat32);
  float32_first.set_interpolation(Interpolation::kCubic);
  const std::vector<double> points = Points(5000);
  double a[kOutputs], b[kOutputs], c[kOutputs];
  double worst = 0.0;
  for (std::size_t i = 0; i < points.size(); i += 3) {
    float64.eval(&points[i], a);
    float32.eval(&points[i], b);
    float32_first.eval(&points[i], c);
    for (int k = 0; k < kOutputs; ++k) {
      ASSERT_EQ(b[k], c[k]);
      worst = std::max(worst, std::fabs(a[k] - b[k]));
    }
  }
  EXPECT_LT(worst, 1e-5 * 1e4);
  EXPECT_GT(worst, 0.0);  // the copy is read
}

TEST_F(Storage32, SwitchingBackRestoresTheDoubleLookups) {
  const Table fresh(exact_.path());
  Table table(exact_.path());
  for (Interpolation mode : {Interpolation::kLinear, Interpolation::kCubic}) {
    Table reference(exact_.path());
    reference.set_interpolation(mode);
    table.set_interpolation(mode);
    table.set_storage(Storage::kFloat32);
    table.set_storage(Storage::kFloat64);
    const std::vector<double> points = Points(2000);
    double a[kOutputs], b[kOutputs];
    for (std::size_t i = 0; i < points.size(); i += 3) {
      reference.eval(&points[i], a);
      table.eval(&points[i], b);
      for (int k = 0; k < kOutputs; ++k) ASSERT_EQ(a[k], b[k]);
    }
  }
  EXPECT_EQ(fresh.storage(), Storage::kFloat64);  // the default
}

TEST_F(Storage32, RefusesAnUnknownStorageByName) {
  wrc_table* t = nullptr;
  ASSERT_EQ(wrc_table_open(exact_.path().c_str(), &t), 0);
  EXPECT_EQ(wrc_table_set_storage(t, 7), WRC_ERR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(wrc_last_error()).find("unknown storage 7"), std::string::npos);
  EXPECT_EQ(wrc_table_storage(t), WRC_STORAGE_FLOAT64);
  EXPECT_EQ(wrc_table_set_storage(nullptr, WRC_STORAGE_FLOAT32), WRC_ERR_NULL_POINTER);
  EXPECT_EQ(wrc_table_storage(nullptr), WRC_ERR_NULL_POINTER);
  wrc_table_close(t);
}

}  // namespace
