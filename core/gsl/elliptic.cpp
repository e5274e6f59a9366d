#include "core/gsl/elliptic.h"

#include <cmath>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_mode.h>
#include <gsl/gsl_sf_ellint.h>

#include "core/gsl/error.h"

namespace wrc::gsl {
namespace {

// GSL's own test (k² >= 1) lets NaN through to the Carlson routines, whose error for it is
// less clear; reject it here with the same status as any other argument out of the domain.
void RequireModulusInDomain(double modulus, const char* function) {
  if (!(std::fabs(modulus) < 1.0)) throw GslError(function, GSL_EDOM);
}

}  // namespace

double CompleteEllipticK(double modulus) {
  DisableAbortOnError();
  RequireModulusInDomain(modulus, "gsl_sf_ellint_Kcomp_e");
  gsl_sf_result result;
  CheckStatus(gsl_sf_ellint_Kcomp_e(modulus, GSL_PREC_DOUBLE, &result), "gsl_sf_ellint_Kcomp_e");
  return result.val;
}

double CompleteEllipticE(double modulus) {
  DisableAbortOnError();
  RequireModulusInDomain(modulus, "gsl_sf_ellint_Ecomp_e");
  gsl_sf_result result;
  CheckStatus(gsl_sf_ellint_Ecomp_e(modulus, GSL_PREC_DOUBLE, &result), "gsl_sf_ellint_Ecomp_e");
  return result.val;
}

double CarlsonRD(double x, double y, double z) {
  DisableAbortOnError();
  // GSL's domain test is false for NaN; it would then iterate to its limit (GSL_EMAXITER).
  if (std::isnan(x) || std::isnan(y) || std::isnan(z))
    throw GslError("gsl_sf_ellint_RD_e", GSL_EDOM);
  gsl_sf_result result;
  CheckStatus(gsl_sf_ellint_RD_e(x, y, z, GSL_PREC_DOUBLE, &result), "gsl_sf_ellint_RD_e");
  return result.val;
}

}  // namespace wrc::gsl
