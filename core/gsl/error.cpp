#include "core/gsl/error.h"

#include <mutex>

#include <gsl/gsl_errno.h>

namespace wrc {

GslError::GslError(const std::string& function, int status)
    : NumericalError(function + ": " + gsl_strerror(status)), status_(status) {}

namespace gsl {

void DisableAbortOnError() {
  // gsl_set_error_handler_off() writes a process-wide pointer; call_once keeps concurrent first
  // calls from racing on it.
  static std::once_flag once;
  std::call_once(once, [] { gsl_set_error_handler_off(); });
}

void CheckStatus(int status, const char* function) {
  if (status != GSL_SUCCESS) throw GslError(function, status);
}

}  // namespace gsl
}  // namespace wrc
