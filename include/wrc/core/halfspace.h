#pragma once
/// @file halfspace.h
/// Half-space problems with quadratic undeformed distance h = a1·x² + b1·y² − approach
/// (docs/reference/case-files.md, half-space cases), solved with CONTACT's module-3 conventions:
/// forces on body 1, steady rolling in +x with the leading edge at x > 0, rigid slip w = [ξ − φ·y,
/// η + φ·(x + δq/6)] with δq = dx.

#include <string>
#include <vector>

#include "wrc/core/case.h"
#include "wrc/core/grid.h"
#include "wrc/core/normal_solver.h"
#include "wrc/core/tangential_solver.h"

namespace wrc {

/// Result of a half-space solve: totals (docs/reference/json.md `patches[0]`) and the fields.
struct HalfspaceResult {
  SolverStatus status = SolverStatus::kNotConverged;
  Grid grid;
  double fn = 0.0, fx = 0.0, fy = 0.0, mz = 0.0;  ///< N, N, N, N·mm.
  double pmax = 0.0, approach = 0.0, area = 0.0;  ///< N/mm², mm, mm².
  int n_contact = 0, n_slip = 0, n_adhesion = 0;
  NormalSummary normal_summary;
  TangentialSummary tangential_summary;
  bool tangential_solved = false;
  std::vector<double> pressure, px, py, sx, sy, h;
  std::vector<ElementState> state;
  /// Doubts about the result (contact cut off by the potential area, too few elements across
  /// the patch), one sentence each; a non-finite solution also sets status not converged.
  std::vector<std::string> warnings;
};

/// The potential contact grid of a half-space case: [grid].x/y when given, otherwise a box
/// of 1.25 times the Hertz semi-axes for the prescribed force (or approach).
Grid HalfspaceGrid(const Case& c);

/// Solves a `type = "halfspace"` case. Computes only what the case asks for: no tangential
/// solve when effects.tangential is false. Throws InputError for a case that is not a
/// half-space case or has inconsistent data.
HalfspaceResult SolveHalfspace(const Case& c, const NormalOptions& normal_options = {},
                               const TangentialOptions& tangential_options = {});

}  // namespace wrc
