#pragma once
/// @file error.h
/// Error handling shared by the GSL wrappers in core/gsl/: GSL's default handler aborts the
/// process, so the wrappers switch it off once and turn every non-zero status into an exception.

#include <stdexcept>
#include <string>

namespace wrc {

/// A GSL routine reported a failure. what() reads "<function>: <gsl_strerror text>".
class GslError : public std::runtime_error {
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

}  // namespace gsl
}  // namespace wrc
