#pragma once
/// @file error.h
/// Error handling shared by the GSL wrappers in core/gsl/: GSL's default handler aborts the
/// process, so the wrappers switch it off once and turn every non-zero status into an exception.

#include <exception>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "wrc/core/errors.h"

namespace wrc {

/// A GSL routine reported a failure. what() reads "<function>: <gsl_strerror text>".
class GslError : public NumericalError {
 public:
  /// @param function The GSL routine (or wrapper) that failed, for the message.
  /// @param status   The GSL status code (GSL_EDOM, GSL_EINVAL, ...).
  GslError(const std::string& function, int status);

  /// The GSL status code, e.g. GSL_EDOM.
  int status() const noexcept { return status_; }

 private:
  int status_;
};

namespace gsl {

/// Replaces GSL's abort-on-error handler by "return the status" for the whole process. Safe to
/// call from any thread any number of times; only the first call has an effect. Every wrapper
/// calls it before its first GSL call, so callers need not.
void DisableAbortOnError();

/// Throws GslError(function, status) unless status is GSL_SUCCESS.
void CheckStatus(int status, const char* function);

/// Passes a C++ callable to a GSL routine as its C callback. An exception must not unwind
/// through GSL's C frames (they have no unwind tables), so it is parked here, the callback
/// returns NaN until GSL gives up, and the caller rethrows it once GSL has returned.
struct GuardedCallback {
  const std::function<double(double)>* f;
  std::exception_ptr error;

  static double Call(double x, void* params) {
    auto* self = static_cast<GuardedCallback*>(params);
    if (self->error) return std::numeric_limits<double>::quiet_NaN();
    try {
      return (*self->f)(x);
    } catch (...) {
      self->error = std::current_exception();
      return std::numeric_limits<double>::quiet_NaN();
    }
  }
  void RethrowIfFailed() const {
    if (error) std::rethrow_exception(error);
  }
};

}  // namespace gsl
}  // namespace wrc
