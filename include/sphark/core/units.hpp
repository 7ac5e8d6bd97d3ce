#pragma once
// Physical constants (cgs) and code units for self-gravitating scenes.
//
// Code units fix a length L and a mass M and set G = 1, so the time unit is
//   T = sqrt(L^3 / (G M))                        (G in cgs below),
// and every other unit follows: velocity L/T, density M/L^3, pressure M/(L T^2),
// specific energy (L/T)^2. The molecular-cloud collapse (issue #16; Phantom's sphere-in-box
// set-up) uses L = 1e16 cm, M = 1 M_sun: T = 8.68e10 s, density 1.99e-15 g/cm^3.
//
// A value in cgs becomes a code value by dividing by its unit: rho_code = rho_cgs / units.density().
#include <cmath>

#include "sphark/core/types.hpp"

namespace sphark::cgs {
inline constexpr Real gravitational_constant = 6.67430e-8;  // cm^3 g^-1 s^-2 (CODATA 2018)
// Solar mass: the IAU 2015 (Resolution B3) nominal GM_sun = 1.3271244e26 cm^3 s^-2 divided by
// the CODATA 2018 G (Phantom uses 1.9891e33 g; the two differ by 3e-4).
inline constexpr Real solar_mass = 1.988409870698051e33;     // g
inline constexpr Real astronomical_unit = 1.495978707e13;    // cm (IAU 2012, exact)
inline constexpr Real parsec = 3.0856775814913673e18;        // cm (IAU 2015, exact)
inline constexpr Real julian_year = 3.15576e7;               // s (365.25 d)
}  // namespace sphark::cgs

namespace sphark {

struct CodeUnits {
  Real length_cm = 1;  // L
  Real mass_g = 1;     // M

  Real time_s() const { return std::sqrt(length_cm * length_cm * length_cm / (cgs::gravitational_constant * mass_g)); }
  Real velocity_cm_s() const { return length_cm / time_s(); }
  Real density_g_cm3() const { return mass_g / (length_cm * length_cm * length_cm); }
  Real pressure_erg_cm3() const { return density_g_cm3() * velocity_cm_s() * velocity_cm_s(); }
  Real specific_energy_erg_g() const { return velocity_cm_s() * velocity_cm_s(); }

  // cgs -> code
  Real length(Real cm) const { return cm / length_cm; }
  Real mass(Real g) const { return g / mass_g; }
  Real time(Real s) const { return s / time_s(); }
  Real velocity(Real cm_s) const { return cm_s / velocity_cm_s(); }
  Real density(Real g_cm3) const { return g_cm3 / density_g_cm3(); }

  // The collapse's units (Phantom's setup_sphereinbox): 1e16 cm, 1 M_sun, G = 1.
  static CodeUnits collapse() { return CodeUnits{1e16, cgs::solar_mass}; }
};

}  // namespace sphark
