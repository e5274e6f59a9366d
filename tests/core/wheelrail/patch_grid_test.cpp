// What SolveOnGrid measures about the contact on its grid: the columns and rows the pressure
// spans, and whether it reaches the outermost elements of the potential contact area.

#include <gtest/gtest.h>

#include <vector>

#include "core/wheelrail/patch_common.h"
#include "wrc/core/case.h"

namespace wrc::wr {
namespace {

// A frictionless patch solved on `grid` with undeformed distance h (identical steel bodies).
PatchResult SolveFrictionless(const Grid& grid, const std::vector<double>& h) {
  static const Case c;
  static const WheelRailOptions options;
  PatchContext ctx;
  ctx.c = &c;
  ctx.options = &options;
  ctx.material = CombinedElasticity::FromBodies(c.rail_material, c.wheel_material);
  ctx.tangential = false;
  const std::vector<double> zero(grid.size(), 0.0), mu(1, 0.3);
  PatchResult result;
  SolveOnGrid(ctx, grid, h, zero, zero, mu, result);
  return result;
}

Grid Square(int n) {
  Grid g;
  g.nx = g.ny = n;
  g.dx = g.dy = 0.2;
  g.x0 = g.y0 = -0.2 * (n - 1) / 2.0;
  return g;
}

// A paraboloid interpenetration h = (x² + y²)/(2R) − δ with R = 100 mm, δ = 0.01 mm: contact
// (about 1 mm across, Hertz a = √(Rδ) = 1 mm for the radius of the contact) well inside a
// 21 × 21 grid of 0.2 mm, so the extent counts are those of the pressure and no border is hit.
std::vector<double> Paraboloid(const Grid& g, double cx, double cy) {
  std::vector<double> h(g.size());
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const double x = g.x(i) - cx, y = g.y(j) - cy;
      h[g.index(i, j)] = (x * x + y * y) / 200.0 - 0.01;
    }
  }
  return h;
}

TEST(PatchGrid, CountsTheColumnsAndRowsInContact) {
  const Grid g = Square(21);
  const PatchResult r = SolveFrictionless(g, Paraboloid(g, 0.0, 0.0));
  ASSERT_GT(r.n_contact, 0);
  int i_lo = g.nx, i_hi = -1, j_lo = g.ny, j_hi = -1;  // independent count from the fields
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      if (r.pn[g.index(i, j)] <= 0.0) continue;
      i_lo = std::min(i_lo, i), i_hi = std::max(i_hi, i);
      j_lo = std::min(j_lo, j), j_hi = std::max(j_hi, j);
    }
  }
  EXPECT_EQ(r.contact_columns, i_hi - i_lo + 1);
  EXPECT_EQ(r.contact_rows, j_hi - j_lo + 1);
  // Symmetric about the centre element: an odd count, about 2a/dx = 5 to 10 elements.
  EXPECT_EQ(r.contact_columns % 2, 1);
  EXPECT_GE(r.contact_columns, 5);
  EXPECT_LE(r.contact_columns, 11);
  EXPECT_EQ(r.contact_columns, r.contact_rows);
  EXPECT_FALSE(r.contact_at_border);
}

// The same interpenetration centred on a corner of the grid: the pressure reaches the first
// row and column, which is what the wheel–rail solve turns into a warning.
TEST(PatchGrid, FlagsPressureOnTheOutermostElements) {
  const Grid g = Square(21);
  const PatchResult corner = SolveFrictionless(g, Paraboloid(g, g.x(0), g.y(0)));
  ASSERT_GT(corner.n_contact, 0);
  EXPECT_TRUE(corner.contact_at_border);
  const PatchResult edge = SolveFrictionless(g, Paraboloid(g, 0.0, g.y(g.ny - 1)));
  EXPECT_TRUE(edge.contact_at_border);
  // No contact at all: nothing measured.
  std::vector<double> apart(g.size(), 0.1);
  const PatchResult none = SolveFrictionless(g, apart);
  EXPECT_EQ(none.n_contact, 0);
  EXPECT_EQ(none.contact_columns, 0);
  EXPECT_FALSE(none.contact_at_border);
}

}  // namespace
}  // namespace wrc::wr
