#pragma once
// Tait equation of state for a weakly compressible liquid.
#include <cmath>

#include "sphark/core/types.hpp"

namespace sphark {

// seed 000, eq. (26):  P = c_s^2 rho_0 / 7 * ((rho / rho_0)^7 - 1)
inline Real tait_pressure(Real rho, Real rho0, Real sound_speed) {
  const Real s = rho / rho0;
  const Real s2 = s * s, s3 = s2 * s, s7 = s3 * s3 * s;
  return sound_speed * sound_speed * rho0 / 7.0 * (s7 - 1.0);
}

// Inverse of eq. (26): the density at which the Tait EOS gives pressure P.
inline Real tait_density(Real pressure, Real rho0, Real sound_speed) {
  return rho0 * std::pow(1.0 + 7.0 * pressure / (sound_speed * sound_speed * rho0), 1.0 / 7.0);
}

// Local sound speed of the Tait EOS, c = sqrt(dP/drho) = c_s (rho/rho_0)^3.
inline Real tait_sound_speed(Real rho, Real rho0, Real sound_speed) {
  const Real s = rho / rho0;
  return sound_speed * s * s * s;
}

}  // namespace sphark
