#include "core/gsl/fit.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_fit.h>

#include <cmath>

#include "core/gsl/error.h"

namespace wrc::gsl {

Line FitLine(const std::vector<double>& x, const std::vector<double>& y) {
  DisableAbortOnError();
  if (x.size() != y.size() || x.size() < 2) throw GslError("FitLine", GSL_EBADLEN);
  Line line;
  double cov00 = 0.0, cov01 = 0.0, cov11 = 0.0, sumsq = 0.0;
  CheckStatus(gsl_fit_linear(x.data(), 1, y.data(), 1, x.size(), &line.intercept, &line.slope,
                             &cov00, &cov01, &cov11, &sumsq),
              "gsl_fit_linear");
  // Equal x make GSL divide by a zero spread; it reports no error, the slope is not finite.
  if (!std::isfinite(line.slope)) throw GslError("gsl_fit_linear", GSL_EZERODIV);
  return line;
}

}  // namespace wrc::gsl
