#include "wrc/core/solver_status.h"

namespace wrc {

const char* ToString(SolverStatus status) {
  switch (status) {
    case SolverStatus::kConverged:
      return "ok";
    case SolverStatus::kNoContact:
      return "no_contact";
    case SolverStatus::kNotConverged:
      return "not_converged";
  }
  return "error";
}

}  // namespace wrc
