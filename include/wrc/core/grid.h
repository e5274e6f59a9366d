#pragma once
/// @file grid.h
/// Rectangular grid of piecewise-constant traction elements (the potential contact area).

#include <cstddef>
#include <stdexcept>

namespace wrc {

/// nx × ny elements of size dx × dy; element (i, j) has its centre at
/// (x0 + i·dx, y0 + j·dy). Arrays on the grid are stored with i fastest: index = i + nx·j
/// (the paper's I = i + mx·(j − 1), §2.7).
struct Grid {
  /// Most elements along one direction: 2^16. The FFT influence operator works on twice that
  /// (2^17 points per direction); finer grids are input mistakes, not contact problems.
  static constexpr int kMaxElementsAlong = 1 << 16;
  /// Most elements in all: 2^22 (4 M). The solvers keep about 30 doubles per element and the
  /// FFT four times the grid, so this is already several GiB; more ends in std::bad_alloc.
  static constexpr double kMaxElements = 4194304.0;

  int nx = 0;
  int ny = 0;
  double dx = 0.0;
  double dy = 0.0;
  double x0 = 0.0;  ///< Centre of the first element in x, mm.
  double y0 = 0.0;  ///< Centre of the first element in y, mm.

  std::size_t size() const { return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny); }
  double x(int i) const { return x0 + i * dx; }
  double y(int j) const { return y0 + j * dy; }
  double element_area() const { return dx * dy; }
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * static_cast<std::size_t>(j);
  }
  /// Throws std::invalid_argument unless nx, ny >= 1 and dx, dy are positive and finite.
  void Validate() const;

  /// The grid of cells dx × dy covering [xmin, xmax] × [ymin, ymax], cell centres at
  /// xmin + (i + ½)dx (docs/reference/case-files.md, half-space cases). The cell count is rounded
  /// to the nearest integer.
  static Grid Covering(double xmin, double xmax, double ymin, double ymax, double dx, double dy);
};

}  // namespace wrc
