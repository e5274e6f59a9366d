#include "wrc/core/influence.h"

#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <tuple>

#include "core/common/numbers.h"

namespace wrc {
namespace {

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
  // (2·half_x + 1) × (2·half_y + 1), x fastest. SumCorners writes every value, so they are not
  // zero-filled first (a std::vector would, at 1 % of a heavy-haul solve).
  std::unique_ptr<double[]> values;
  double at(int di, int dj) const {
    return values[static_cast<std::size_t>(di + half_x) +
                  static_cast<std::size_t>(2 * half_x + 1) * static_cast<std::size_t>(dj + half_y)];
  }
};

namespace {

using TableKey = std::tuple<int, double, double, double, double, double>;

// Fills table.values (half sizes set) from the antiderivative F at the corners of one
// quadrant. Each coefficient is the corner sum of F over its element (RectangleIntegral);
// neighbouring elements share corners, and F is odd or even in X and in Y, so F is needed once
// per corner of one quadrant, (half_x + 1)(half_y + 1) values instead of 4 per coefficient.
// The coefficients have the opposite parity of F's (even where F is odd), so one quadrant of
// them is summed and the other three are mirrored.
void SumCorners(const std::vector<double>& quadrant, bool odd_x, bool odd_y,
                CoefficientTable& table) {
  const int hx = table.half_x, hy = table.half_y, cx = hx + 1;
  const std::size_t width = static_cast<std::size_t>(2 * hx + 1);
  // F at the corner ((i + ½)·dx, (j + ½)·dy) for i, j >= −1.
  auto corner = [&](int i, int j) {
    const double f = quadrant[static_cast<std::size_t>(i < 0 ? 0 : i) +
                              static_cast<std::size_t>(cx) * (j < 0 ? 0 : j)];
    const bool negate = (odd_x && i < 0) != (odd_y && j < 0);
    return negate ? -f : f;
  };
  const double sign_x = odd_x ? 1.0 : -1.0, sign_y = odd_y ? 1.0 : -1.0;
  table.values.reset(new double[width * static_cast<std::size_t>(2 * hy + 1)]);
  for (int dj = 0; dj <= hy; ++dj) {
    double* row = table.values.get() + width * static_cast<std::size_t>(hy + dj) + hx;
    row[0] = corner(0, dj) - corner(-1, dj) - corner(0, dj - 1) + corner(-1, dj - 1);
    if (dj == 0) {
      for (int di = 1; di <= hx; ++di) {
        row[di] = corner(di, 0) - corner(di - 1, 0) - corner(di, -1) + corner(di - 1, -1);
      }
    } else {
      // Inside the quadrant no corner is mirrored: the same sum without the lookups' branches.
      const double* upper = quadrant.data() + static_cast<std::size_t>(cx) * dj;
      const double* lower = upper - cx;
      for (int di = 1; di <= hx; ++di) {
        row[di] = upper[di] - upper[di - 1] - lower[di] + lower[di - 1];
      }
    }
    for (int di = 1; di <= hx; ++di) row[-di] = sign_x * row[di];
    if (dj > 0) {
      double* mirror = table.values.get() + width * static_cast<std::size_t>(hy - dj);
      const double* source = row - hx;
      for (std::size_t k = 0; k < width; ++k) mirror[k] = sign_y * source[k];
    }
  }
}

// The tables of kNN, kXX, kYY and kXY, made together: in the positive quadrant the two terms
// of ∫∫1/r are A = X·asinh(Y/X) (which is ∫∫Y²/r³) and B = Y·asinh(X/Y) (∫∫X²/r³), and ∫∫XY/r³
// is −r, so one square root and two logarithms per corner serve all four components (instead
// of nine transcendental calls). asinh(Y/X) = ln((Y + r)/X) = log1p((Y + Y²/(r + X))/X), with
// r − X = Y²/(r + X) written so that nothing cancels.
std::array<std::shared_ptr<CoefficientTable>, 4> ElasticTables(const CombinedElasticity& m,
                                                               double dx, double dy, int half_x,
                                                               int half_y) {
  const int cx = half_x + 1, cy = half_y + 1;
  const std::size_t n = static_cast<std::size_t>(cx) * cy;
  std::vector<double> a_term(n), b_term(n), radius(n);
  for (int b = 0; b < cy; ++b) {
    const double Y = (b + 0.5) * dy;
    for (int a = 0; a < cx; ++a) {
      const double X = (a + 0.5) * dx;
      const double r = std::sqrt(X * X + Y * Y);
      const std::size_t k = static_cast<std::size_t>(a) + static_cast<std::size_t>(cx) * b;
      a_term[k] = X * std::log1p((Y + Y * Y / (r + X)) / X);
      b_term[k] = Y * std::log1p((X + X * X / (r + Y)) / Y);
      radius[k] = r;
    }
  }
  const double scale = 1.0 / (kPi * m.shear_modulus);
  const double nu = m.poisson;
  // Weights of A and B in NN, XX, YY: (1 − ν)(A + B), plus ν·B for XX and ν·A for YY.
  const double wa[3] = {scale * (1.0 - nu), scale * (1.0 - nu), scale};
  const double wb[3] = {scale * (1.0 - nu), scale, scale * (1.0 - nu)};
  std::array<std::shared_ptr<CoefficientTable>, 4> tables;
  std::vector<double> quadrant(n);
  for (int t = 0; t < 4; ++t) {
    tables[t] = std::make_shared<CoefficientTable>();
    tables[t]->half_x = half_x;
    tables[t]->half_y = half_y;
    if (t < 3) {
      for (std::size_t k = 0; k < n; ++k) quadrant[k] = wa[t] * a_term[k] + wb[t] * b_term[k];
      SumCorners(quadrant, true, true, *tables[t]);
    } else {
      for (std::size_t k = 0; k < n; ++k) quadrant[k] = -scale * nu * radius[k];
      SumCorners(quadrant, false, false, *tables[t]);  // −r: even in X and Y
    }
  }
  return tables;
}

std::shared_ptr<const CoefficientTable> Table(InfluenceComponent c, const CombinedElasticity& m,
                                              double dx, double dy, int half_x, int half_y) {
  static std::mutex mutex;
  static std::map<TableKey, std::shared_ptr<const CoefficientTable>> tables;
  auto key_of = [&](InfluenceComponent component) {
    return TableKey{static_cast<int>(component), m.shear_modulus, m.poisson, m.kappa, dx, dy};
  };
  const TableKey key = key_of(c);
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
    } else {
      // A first table covers a few more elements than asked: the steady-rolling operator of
      // the same patch has one more column, and the next steps of a force iteration slightly
      // larger boxes.
      half_x += 2 + half_x / 8;
      half_y += 2 + half_y / 8;
    }
  }
  using C = InfluenceComponent;
  if (c == C::kNN || c == C::kXX || c == C::kYY || c == C::kXY) {
    const auto made = ElasticTables(m, dx, dy, half_x, half_y);
    const C order[4] = {C::kNN, C::kXX, C::kYY, C::kXY};
    std::lock_guard<std::mutex> lock(mutex);
    for (int t = 0; t < 4; ++t) {
      auto& slot = tables[key_of(order[t])];
      if (!slot || slot->half_x < made[t]->half_x || slot->half_y < made[t]->half_y) {
        slot = made[t];
      }
    }
    return tables[key];
  }
  // kXN, kNX: F = ±K/(πG)·(½·Y·ln(X² + Y²) + X·atan(Y/X)), even in X and odd in Y.
  const double weight = (c == C::kXN ? -1.0 : 1.0) * m.kappa / (kPi * m.shear_modulus);
  const int cx = half_x + 1, cy = half_y + 1;
  std::vector<double> quadrant(static_cast<std::size_t>(cx) * cy);
  for (int b = 0; b < cy; ++b) {
    const double Y = (b + 0.5) * dy;
    for (int a = 0; a < cx; ++a) {
      const double X = (a + 0.5) * dx;
      quadrant[static_cast<std::size_t>(a) + static_cast<std::size_t>(cx) * b] =
          weight * AntiXOverR2(X, Y);
    }
  }
  auto table = std::make_shared<CoefficientTable>();
  table->half_x = half_x;
  table->half_y = half_y;
  SumCorners(quadrant, false, true, *table);
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
  origin_ = table_->values.get() + table_->half_x + stride_ * table_->half_y;
}

}  // namespace wrc
