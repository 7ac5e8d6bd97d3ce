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

// Specific internal energy of eq. (26) plus a constant background pressure P_b, measured from
// rho_0: u(rho) = int_{rho_0}^{rho} P(r) / r^2 dr
//              = c_s^2 rho_0 / 7 [(rho^6 - rho_0^6) / (6 rho_0^7) + 1/rho - 1/rho_0] + P_b (1/rho_0 - 1/rho).
inline Real tait_specific_energy(Real rho, Real rho0, Real sound_speed, Real background_pressure = 0) {
  const Real s = rho / rho0, s2 = s * s, s6 = s2 * s2 * s2;
  const Real B = sound_speed * sound_speed * rho0 / 7.0;
  return B * ((s6 - 1.0) / (6.0 * rho0) + 1.0 / rho - 1.0 / rho0) + background_pressure * (1.0 / rho0 - 1.0 / rho);
}

// Local sound speed of the Tait EOS, c = sqrt(dP/drho) = c_s (rho/rho_0)^3.
inline Real tait_sound_speed(Real rho, Real rho0, Real sound_speed) {
  const Real s = rho / rho0;
  return sound_speed * s * s * s;
}

}  // namespace sphark
