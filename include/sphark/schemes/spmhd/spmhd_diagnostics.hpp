#pragma once
// Global diagnostics of an SPMHD state (seed 000, §IV; DESIGN.md "Known difficulties"):
// the divergence error h|div B|/|B| with the difference div B of eq. (20) (particle mean and
// max), the energies (mu0 = 1) and the total momentum. Sums are serial, in particle order.
#include <array>

#include "sphark/schemes/spmhd/spmhd_scheme.hpp"

namespace sphark {

struct SpmhdDiagnostics {
  Real mean_h_divb_over_b = 0;
  Real max_h_divb_over_b = 0;
  Real max_h_divb = 0;        // max h|div B| (not normalised; grows with the field)
  Real kinetic_energy = 0;    // sum m v^2 / 2
  Real magnetic_energy = 0;   // sum m B^2 / (2 rho)
  Real thermal_energy = 0;    // sum m u
  Real psi_energy = 0;        // sum m psi^2 / (2 rho c_h^2), seed 000 eq. (17)
  Real total_energy = 0;      // the sum of the four above
  std::array<Real, 3> momentum{0, 0, 0};
  Real cleaning_speed = 0;
};

// Refreshes the scheme's per-particle quantities at y (scheme.evaluate) and sums them.
// Particles with |B| = 0 are left out of the mean and max of h|div B|/|B|.
template <int D, class K>
SpmhdDiagnostics spmhd_diagnostics(SpmhdScheme<D, K>& scheme, Real t, const Real* y);

}  // namespace sphark
