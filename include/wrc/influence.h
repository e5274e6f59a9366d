#pragma once
/// @file influence.h
/// Influence coefficients of an elastic half-space for piecewise-constant tractions on
/// rectangular elements (Boussinesq for normal, Cerruti for tangential loads), for two bodies
/// combined as in Kalker's theory (paper §2.7, Eq. 17).

#include <vector>

#include "wrc/grid.h"
#include "wrc/material.h"

namespace wrc {

/// Which displacement responds to which traction. The first letter is the displacement
/// direction, the second the traction direction: kXN is the x-displacement due to pressure.
enum class InfluenceComponent { kNN, kXX, kYY, kXY, kXN, kNX };

/// Point-load kernels of the combined bodies: relative displacement u = u(1) − u(2) at offset
/// (X, Y) from a unit point force acting on body 1 (and its opposite on body 2), mm/N:
///   nn: (1−ν)/(πG)·1/r               xx: [(1−ν)/r + ν X²/r³]/(πG)
///   yy: [(1−ν)/r + ν Y²/r³]/(πG)      xy: ν XY/r³/(πG)
///   xn: −K/(πG)·X/r²                  nx: +K/(πG)·X/r²  (surface points move towards a
///   pressure load; the coupling vanishes for identical bodies, K = 0).
double PointLoadKernel(InfluenceComponent c, const CombinedElasticity& m, double X, double Y);

/// The same kernel integrated in closed form over the rectangle [−hx, hx] × [−hy, hy] of unit
/// traction, evaluated at (X, Y): the displacement at (X, Y) due to a uniform unit traction on
/// an element centred at the origin with half-sizes hx, hy. mm/(N/mm²).
double RectangleInfluence(InfluenceComponent c, const CombinedElasticity& m, double X, double Y,
                          double hx, double hy);

/// Coefficients for every offset between two elements of a grid: entry
/// (di + nx − 1) + (2nx − 1)·(dj + ny − 1) is the response at element (i + di, j + dj) to
/// unit traction on element (i, j), for di in [−(nx−1), nx−1] and dj in [−(ny−1), ny−1].
class InfluenceCoefficients {
 public:
  InfluenceCoefficients(const Grid& grid, const CombinedElasticity& material,
                        InfluenceComponent component);

  const Grid& grid() const { return grid_; }
  InfluenceComponent component() const { return component_; }
  /// Coefficient for the offset (di, dj) in elements.
  double at(int di, int dj) const {
    return values_[static_cast<std::size_t>(di + grid_.nx - 1) +
                   static_cast<std::size_t>(2 * grid_.nx - 1) *
                       static_cast<std::size_t>(dj + grid_.ny - 1)];
  }
  const std::vector<double>& values() const { return values_; }

 private:
  Grid grid_;
  InfluenceComponent component_;
  std::vector<double> values_;
};

}  // namespace wrc
