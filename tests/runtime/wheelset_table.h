#pragma once
// A synthetic right-wheel table for the wheelset API's tests and benchmark: the four axes of
// WheelsetAxes(), the outputs the wheelset result reads, each affine in the axes (so that
// multilinear interpolation reproduces it exactly), and a scene made at 20 m/s.

#include <string>
#include <vector>

#include "tests/runtime/table_writer.h"

namespace wrc::test {

inline const std::vector<std::string>& WheelsetOutputs() {
  static const std::vector<std::string> names = {
      "fx", "fy", "fz", "mx", "my", "mz", "contact_y", "contact_angle", "t_gamma"};
  return names;
}

/// Output k at (y, roll, yaw, spin): a different affine function per output.
inline double WheelsetFunction(int k, const std::vector<double>& x) {
  return 100.0 * (k + 1) + (10.0 + k) * x[0] + 2000.0 * (k - 3) * x[1] +
         5000.0 * (2 * k - 5) * x[2] + 30000.0 * (k % 3 - 1) * x[3];
}

inline const char* kWheelsetScene =
    "# a right wheel at 20 m/s\n"
    "[wheelset]\nside = \"right\" # the default\nnominal_radius = 460.0\n"
    "[state]\nfz = 10_000.0\nvelocity = 20000.0 # mm/s\n"
    "[table]\naxes = [\"y\", \"roll\", \"yaw\", \"spin\"]\n";

inline void WriteWheelsetTable(const std::string& path, int y_nodes = 41) {
  TableContent content;
  content.axes = WheelsetAxes(y_nodes);
  content.outputs = WheelsetOutputs();
  content.function = WheelsetFunction;
  content.scene = kWheelsetScene;
  WriteTable(path, content);
}

}  // namespace wrc::test
