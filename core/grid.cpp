#include "wrc/core/grid.h"

#include <cmath>
#include <string>

namespace wrc {

void Grid::Validate() const {
  if (nx < 1 || ny < 1) {
    throw std::invalid_argument("grid has " + std::to_string(nx) + " x " + std::to_string(ny) +
                                " elements: need at least 1 x 1");
  }
  if (!(std::isfinite(dx) && dx > 0.0) || !(std::isfinite(dy) && dy > 0.0)) {
    throw std::invalid_argument("grid element size " + std::to_string(dx) + " x " +
                                std::to_string(dy) + ": must be positive and finite");
  }
  if (!std::isfinite(x0) || !std::isfinite(y0)) {
    throw std::invalid_argument("grid origin is not finite");
  }
}

namespace {

// Elements along one direction, counted in floating point so that an absurd range cannot wrap
// an integer: refused above kMaxElementsAlong.
int ElementCount(double min, double max, double step, const char* direction) {
  const double count = std::round((max - min) / step);
  if (!(count <= Grid::kMaxElementsAlong)) {
    throw std::invalid_argument("grid range along " + std::string(direction) + " holds " +
                                std::to_string(count) + " elements of " + std::to_string(step) +
                                " mm: more than " + std::to_string(Grid::kMaxElementsAlong));
  }
  return static_cast<int>(count);
}

}  // namespace

Grid Grid::Covering(double xmin, double xmax, double ymin, double ymax, double dx, double dy) {
  Grid g;
  g.dx = dx;
  g.dy = dy;
  if (!(xmax > xmin) || !(ymax > ymin)) {
    throw std::invalid_argument("grid range is empty: need xmin < xmax and ymin < ymax");
  }
  if (!(dx > 0.0) || !(dy > 0.0)) {
    throw std::invalid_argument("grid element size must be positive");
  }
  // Rounding, not truncation: the range is meant to be a whole number of cells, and
  // (xmax - xmin)/dx lands a few ulps below that integer for values like 8.96/0.28.
  g.nx = ElementCount(xmin, xmax, dx, "x");
  g.ny = ElementCount(ymin, ymax, dy, "y");
  if (static_cast<double>(g.nx) * g.ny > Grid::kMaxElements) {
    throw std::invalid_argument("grid of " + std::to_string(g.nx) + " x " + std::to_string(g.ny) +
                                " elements: more than " +
                                std::to_string(static_cast<long>(Grid::kMaxElements)) + " in all");
  }
  g.x0 = xmin + 0.5 * dx;
  g.y0 = ymin + 0.5 * dy;
  g.Validate();
  return g;
}

}  // namespace wrc
