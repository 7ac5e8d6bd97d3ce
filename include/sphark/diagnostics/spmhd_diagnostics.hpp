#pragma once
// Global diagnostics of an SPMHD state (seed 000, §IV; DESIGN.md "Known difficulties"):
// the divergence error h|div B|/|B| with the difference div B of eq. (20) (particle mean and
// max), the energies (mu0 = 1) and the total momentum. Sums are serial, in particle order.
#include <array>

#include "sphark/io/particle_frame.hpp"
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
  Real potential_energy = 0;  // self-gravity: (1/2) sum m Phi (0 without gravity)
  Real total_energy = 0;      // the sum of the five above
  std::array<Real, 3> momentum{0, 0, 0};
  Real cleaning_speed = 0;
};

// Refreshes the scheme's per-particle quantities at y (scheme.evaluate) and sums them.
// Particles with |B| = 0 are left out of the mean and max of h|div B|/|B|.
template <int D, class K>
SpmhdDiagnostics spmhd_diagnostics(SpmhdScheme<D, K>& scheme, Real t, const Real* y);

// The VTK frame of an SPMHD state (refreshes the scheme at y, scheme.evaluate): density,
// magnetic pressure B^2/2, div B (eq. (20)), h|div B|/|B|, then as the state has them pressure,
// B, velocity, psi, and h. Positions are wrapped into `box` when one is given. Owns the copies
// its arrays point into (valid until the next build()).
class SpmhdFrame {
 public:
  template <int D, class K>
  ParticleFrame build(SpmhdScheme<D, K>& scheme, Real t, const Real* y, const PeriodicBox<D>* box = nullptr);

 private:
  std::vector<Real> positions_, density_, magnetic_pressure_, div_b_, error_, pressure_, field_, velocity_, psi_, h_;
};

}  // namespace sphark
