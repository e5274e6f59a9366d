#include "wrc/core/material.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wrc {
namespace {

void ValidateBody(const ElasticMaterial& m, const char* which) {
  if (!(std::isfinite(m.shear_modulus) && m.shear_modulus > 0.0)) {
    throw std::invalid_argument(std::string(which) + " shear_modulus = " +
                                std::to_string(m.shear_modulus) + ": must be positive");
  }
  // ν = 0.5 (incompressible) is allowed; beyond it the half-space kernels change sign.
  if (!(std::isfinite(m.poisson) && m.poisson >= 0.0 && m.poisson <= 0.5)) {
    throw std::invalid_argument(std::string(which) + " poisson = " + std::to_string(m.poisson) +
                                ": must lie in [0, 0.5]");
  }
}

}  // namespace

CombinedElasticity CombinedElasticity::FromBodies(const ElasticMaterial& body1,
                                                  const ElasticMaterial& body2) {
  ValidateBody(body1, "body 1");
  ValidateBody(body2, "body 2");
  CombinedElasticity c;
  c.shear_modulus = 2.0 / (1.0 / body1.shear_modulus + 1.0 / body2.shear_modulus);
  c.poisson = c.shear_modulus * 0.5 *
              (body1.poisson / body1.shear_modulus + body2.poisson / body2.shear_modulus);
  c.kappa = 0.25 * c.shear_modulus *
            ((1.0 - 2.0 * body1.poisson) / body1.shear_modulus -
             (1.0 - 2.0 * body2.poisson) / body2.shear_modulus);
  return c;
}

}  // namespace wrc
