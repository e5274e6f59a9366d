#pragma once
/// @file influence.h
/// Influence coefficients of an elastic half-space for piecewise-constant tractions on
/// rectangular elements (Boussinesq for normal, Cerruti for tangential loads), for two bodies
/// combined as in Kalker's theory (paper §2.7, Eq. 17).

#include <cstddef>
#include <memory>
#include <vector>

#include "wrc/core/grid.h"
#include "wrc/core/material.h"

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

/// Process-wide table of coefficients for one (component, material, dx, dy), influence.cpp.
struct CoefficientTable;

/// Coefficients for every offset between two elements of a grid: the response at element
/// (i + di, j + dj) to unit traction on element (i, j), for di in [−(nx−1), nx−1] and dj in
/// [−(ny−1), ny−1]. A view of the process-wide table (no copy: a table of a large flange patch
/// is ~0.5 MB per component).
class InfluenceCoefficients {
 public:
  InfluenceCoefficients(const Grid& grid, const CombinedElasticity& material,
                        InfluenceComponent component);

  const Grid& grid() const { return grid_; }
  InfluenceComponent component() const { return component_; }
  /// Coefficient for the offset (di, dj) in elements.
  double at(int di, int dj) const { return origin_[di + stride_ * dj]; }
  /// The coefficient of offset (0, 0); offset (di, dj) is at origin()[di + stride()·dj], so the
  /// coefficients of one dj are contiguous in di.
  const double* origin() const { return origin_; }
  std::ptrdiff_t stride() const { return stride_; }

 private:
  Grid grid_;
  InfluenceComponent component_;
  std::shared_ptr<const CoefficientTable> table_;
  const double* origin_ = nullptr;
  std::ptrdiff_t stride_ = 0;
};

}  // namespace wrc
