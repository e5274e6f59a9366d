#include "wrc/influence.h"

#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <tuple>

namespace wrc {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Antiderivatives F(X, Y) with ∂²F/∂X∂Y = kernel(X, Y). Terms that depend on X alone or on Y
// alone cancel in the corner sum of RectangleIntegral, so they are left out; this also removes
// the log singularities (X ln|X|) that would otherwise need special cases.

// ∫∫ 1/r: X·asinh(Y/|X|) + Y·asinh(X/|Y|)  (= X ln(Y + r) + Y ln(X + r) up to such terms).
double AntiInverseR(double X, double Y) {
  double f = 0.0;
  if (X != 0.0) f += X * std::asinh(Y / std::fabs(X));
  if (Y != 0.0) f += Y * std::asinh(X / std::fabs(Y));
  return f;
}
// ∫∫ X²/r³: Y·asinh(X/|Y|), since ∂/∂X [Y ln(X + r)] = Y/r and ∂/∂Y [Y/r] = X²/r³.
double AntiXXOverR3(double X, double Y) {
  return Y != 0.0 ? Y * std::asinh(X / std::fabs(Y)) : 0.0;
}
// ∫∫ Y²/r³: X·asinh(Y/|X|) by symmetry.
double AntiYYOverR3(double X, double Y) { return AntiXXOverR3(Y, X); }
// ∫∫ XY/r³: −r.
double AntiXYOverR3(double X, double Y) { return -std::hypot(X, Y); }
// ∫∫ X/r²: ½·Y·ln(X² + Y²) + X·atan(Y/X)  (the −Y term cancels).
double AntiXOverR2(double X, double Y) {
  double f = 0.0;
  const double r2 = X * X + Y * Y;
  if (Y != 0.0 && r2 > 0.0) f += 0.5 * Y * std::log(r2);
  if (X != 0.0) f += X * std::atan(Y / X);
  return f;
}

// Integral of kernel(X − ξ, Y − η) over ξ ∈ [−hx, hx], η ∈ [−hy, hy].
template <typename Anti>
double RectangleIntegral(Anti anti, double X, double Y, double hx, double hy) {
  return anti(X + hx, Y + hy) - anti(X - hx, Y + hy) - anti(X + hx, Y - hy) + anti(X - hx, Y - hy);
}

}  // namespace

double PointLoadKernel(InfluenceComponent c, const CombinedElasticity& m, double X, double Y) {
  const double r = std::hypot(X, Y);
  const double scale = 1.0 / (kPi * m.shear_modulus);
  const double nu = m.poisson;
  switch (c) {
    case InfluenceComponent::kNN:
      return scale * (1.0 - nu) / r;
    case InfluenceComponent::kXX:
      return scale * ((1.0 - nu) / r + nu * X * X / (r * r * r));
    case InfluenceComponent::kYY:
      return scale * ((1.0 - nu) / r + nu * Y * Y / (r * r * r));
    case InfluenceComponent::kXY:
      return scale * nu * X * Y / (r * r * r);
    case InfluenceComponent::kXN:
      return -scale * m.kappa * X / (r * r);
    case InfluenceComponent::kNX:
      return scale * m.kappa * X / (r * r);
  }
  throw std::invalid_argument("unknown influence component");
}

double RectangleInfluence(InfluenceComponent c, const CombinedElasticity& m, double X, double Y,
                          double hx, double hy) {
  const double scale = 1.0 / (kPi * m.shear_modulus);
  const double nu = m.poisson;
  switch (c) {
    case InfluenceComponent::kNN:
      return scale * (1.0 - nu) * RectangleIntegral(AntiInverseR, X, Y, hx, hy);
    case InfluenceComponent::kXX:
      return scale * ((1.0 - nu) * RectangleIntegral(AntiInverseR, X, Y, hx, hy) +
                      nu * RectangleIntegral(AntiXXOverR3, X, Y, hx, hy));
    case InfluenceComponent::kYY:
      return scale * ((1.0 - nu) * RectangleIntegral(AntiInverseR, X, Y, hx, hy) +
                      nu * RectangleIntegral(AntiYYOverR3, X, Y, hx, hy));
    case InfluenceComponent::kXY:
      return scale * nu * RectangleIntegral(AntiXYOverR3, X, Y, hx, hy);
    case InfluenceComponent::kXN:
      return -scale * m.kappa * RectangleIntegral(AntiXOverR2, X, Y, hx, hy);
    case InfluenceComponent::kNX:
      return scale * m.kappa * RectangleIntegral(AntiXOverR2, X, Y, hx, hy);
  }
  throw std::invalid_argument("unknown influence component");
}

// Coefficients depend only on the component, the material, the element size and the offset, so
// one table per (component, material, dx, dy), grown on demand, serves every grid of a solve
// (every patch, every vertical force iteration, every point of a table). Values are computed
// by the same closed form, so cached and fresh coefficients are bit-identical.
struct CoefficientTable {
  int half_x = 0, half_y = 0;  // offsets −half…half
  std::vector<double> values;  // (2·half_x + 1) × (2·half_y + 1), x fastest
  double at(int di, int dj) const {
    return values[static_cast<std::size_t>(di + half_x) +
                  static_cast<std::size_t>(2 * half_x + 1) * static_cast<std::size_t>(dj + half_y)];
  }
};

namespace {

using TableKey = std::tuple<int, double, double, double, double, double>;

std::shared_ptr<const CoefficientTable> Table(InfluenceComponent c, const CombinedElasticity& m,
                                              double dx, double dy, int half_x, int half_y) {
  static std::mutex mutex;
  static std::map<TableKey, std::shared_ptr<const CoefficientTable>> tables;
  const TableKey key{static_cast<int>(c), m.shear_modulus, m.poisson, m.kappa, dx, dy};
  {
    std::lock_guard<std::mutex> lock(mutex);
    auto it = tables.find(key);
    if (it != tables.end() && it->second->half_x >= half_x && it->second->half_y >= half_y) {
      return it->second;
    }
    if (it != tables.end()) {
      // Grow by half again so that slowly growing grids do not recompute every time.
      half_x = std::max(half_x, it->second->half_x + it->second->half_x / 2);
      half_y = std::max(half_y, it->second->half_y + it->second->half_y / 2);
    }
  }
  auto table = std::make_shared<CoefficientTable>();
  table->half_x = half_x;
  table->half_y = half_y;
  table->values.resize(static_cast<std::size_t>(2 * half_x + 1) *
                       static_cast<std::size_t>(2 * half_y + 1));
  // Each coefficient is the corner sum of an antiderivative F over its element (Eq. of
  // RectangleIntegral); neighbouring elements share corners, and F is odd or even in X and in Y,
  // so F is evaluated once per corner of one quadrant, (half_x + 1)(half_y + 1) times instead of
  // 4 per coefficient: 16x fewer logarithms (they were a tenth of a flange-contact solve).
  const double scale = 1.0 / (kPi * m.shear_modulus);
  const double nu = m.poisson;
  double (*anti_a)(double, double) = AntiInverseR;
  double (*anti_b)(double, double) = nullptr;
  double weight_a = scale * (1.0 - nu), weight_b = 0.0;
  bool odd_x = true, odd_y = true;
  switch (c) {
    case InfluenceComponent::kNN:
      break;
    case InfluenceComponent::kXX:
      anti_b = AntiXXOverR3;
      weight_b = scale * nu;
      break;
    case InfluenceComponent::kYY:
      anti_b = AntiYYOverR3;
      weight_b = scale * nu;
      break;
    case InfluenceComponent::kXY:
      anti_a = AntiXYOverR3;  // −r: even in X and Y
      weight_a = scale * nu;
      odd_x = odd_y = false;
      break;
    case InfluenceComponent::kXN:
    case InfluenceComponent::kNX:
      anti_a = AntiXOverR2;  // even in X, odd in Y
      weight_a = (c == InfluenceComponent::kXN ? -scale : scale) * m.kappa;
      odd_x = false;
      break;
  }
  const int cx = half_x + 1, cy = half_y + 1;
  std::vector<double> quadrant(static_cast<std::size_t>(cx) * cy);
  for (int b = 0; b < cy; ++b) {
    const double Y = (b + 0.5) * dy;
    for (int a = 0; a < cx; ++a) {
      const double X = (a + 0.5) * dx;
      double f = weight_a * anti_a(X, Y);
      if (anti_b) f += weight_b * anti_b(X, Y);
      quadrant[static_cast<std::size_t>(a) + static_cast<std::size_t>(cx) * b] = f;
    }
  }
  // F at the corner ((i + ½)·dx, (j + ½)·dy) for any integers i, j.
  auto corner = [&](int i, int j) {
    const int a = i >= 0 ? i : -i - 1, b = j >= 0 ? j : -j - 1;
    const double f = quadrant[static_cast<std::size_t>(a) + static_cast<std::size_t>(cx) * b];
    const bool negate = (odd_x && i < 0) != (odd_y && j < 0);
    return negate ? -f : f;
  };
  std::size_t k = 0;
  for (int dj = -half_y; dj <= half_y; ++dj) {
    for (int di = -half_x; di <= half_x; ++di) {
      table->values[k++] =
          corner(di, dj) - corner(di - 1, dj) - corner(di, dj - 1) + corner(di - 1, dj - 1);
    }
  }
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = tables[key];
  if (!slot || slot->half_x < table->half_x || slot->half_y < table->half_y) slot = table;
  return slot;
}

}  // namespace

InfluenceCoefficients::InfluenceCoefficients(const Grid& grid, const CombinedElasticity& material,
                                             InfluenceComponent component)
    : grid_(grid), component_(component) {
  grid_.Validate();
  table_ = Table(component, material, grid_.dx, grid_.dy, grid_.nx - 1, grid_.ny - 1);
  stride_ = 2 * table_->half_x + 1;
  origin_ = table_->values.data() + table_->half_x + stride_ * table_->half_y;
}

}  // namespace wrc
