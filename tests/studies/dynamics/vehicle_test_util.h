#pragma once
// What the bogie and curving tests share: the shipped Manchester vehicle and a linear contact
// of its size.

#include <string>

#include "studies/dynamics/bogie.h"
#include "studies/dynamics/forces.h"

namespace wrc::dynamics::test {

inline BogieParameters Vehicle() {
  return LoadBogieParameters(std::string(WRC_SOURCE_DIR) + "/tables/manchester_vehicle.toml");
}

/// Linear creep at the vehicle's wheel load (Kalker-size coefficients of a 54.5 kN contact),
/// conicity of a new S1002 profile, and a gravitational stiffness (N/mm).
inline LinearContact VehicleCreep(double gravity_stiffness = 0.0) {
  LinearContact c;
  c.f11 = 8.0e6;
  c.f22 = 7.2e6;
  c.conicity = 0.2;
  c.semi_spacing = 750.0;
  c.nominal_radius = 460.0;
  c.gravity_stiffness = gravity_stiffness;
  return c;
}

}  // namespace wrc::dynamics::test
