#pragma once
/// @file solver_status.h
/// Outcome of an iterative solve: non-convergence is a status, not an exception.

namespace wrc {

enum class SolverStatus {
  kConverged,     ///< Met the tolerance.
  kNoContact,     ///< The bodies do not touch: zero tractions are the solution.
  kNotConverged,  ///< Hit the iteration limit; the last iterate is returned.
};

/// "ok", "no_contact" or "not_converged", as in docs/reference/json.md.
const char* ToString(SolverStatus status);

}  // namespace wrc
