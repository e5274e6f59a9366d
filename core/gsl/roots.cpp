#include "core/gsl/roots.h"

#include <cmath>
#include <exception>
#include <limits>
#include <memory>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include "core/gsl/error.h"

namespace wrc::gsl {
namespace {

struct SolverDeleter {
  void operator()(gsl_root_fsolver* s) const { gsl_root_fsolver_free(s); }
};
using Solver = std::unique_ptr<gsl_root_fsolver, SolverDeleter>;

using Objective = GuardedCallback;  // exceptions must not unwind through GSL

}  // namespace

RootResult FindRootBrent(const std::function<double(double)>& f, double lo, double hi,
                         const RootOptions& options) {
  DisableAbortOnError();
  // GSL's Brent accepts an end point where f is exactly zero but then iterates on; returning it
  // directly is both cheaper and exact.
  const double f_lo = f(lo);
  if (f_lo == 0.0) return RootResult{lo, 0, true};
  const double f_hi = f(hi);
  if (f_hi == 0.0) return RootResult{hi, 0, true};
  // GSL's sign test is false for NaN and would accept such a bracket.
  if (!std::isfinite(f_lo) || !std::isfinite(f_hi)) throw GslError("FindRootBrent", GSL_EBADFUNC);

  Solver solver(gsl_root_fsolver_alloc(gsl_root_fsolver_brent));
  if (!solver) throw GslError("gsl_root_fsolver_alloc", GSL_ENOMEM);
  Objective objective{&f, nullptr};
  gsl_function function{&Objective::Call, &objective};
  // Fails with GSL_EINVAL ("endpoints do not straddle y=0") for a bracket without sign change.
  const int set_status = gsl_root_fsolver_set(solver.get(), &function, lo, hi);
  objective.RethrowIfFailed();
  CheckStatus(set_status, "gsl_root_fsolver_set");

  RootResult result;
  while (result.iterations < options.max_iterations) {
    ++result.iterations;
    const int step_status = gsl_root_fsolver_iterate(solver.get());
    objective.RethrowIfFailed();
    CheckStatus(step_status, "gsl_root_fsolver_iterate");
    result.root = gsl_root_fsolver_root(solver.get());
    const int test = gsl_root_test_interval(gsl_root_fsolver_x_lower(solver.get()),
                                            gsl_root_fsolver_x_upper(solver.get()),
                                            options.abs_tolerance, options.rel_tolerance);
    if (test == GSL_SUCCESS) {
      result.converged = true;
      break;
    }
    if (test != GSL_CONTINUE) CheckStatus(test, "gsl_root_test_interval");
  }
  return result;
}

}  // namespace wrc::gsl
