#pragma once
// The static cleaning test with a free boundary (seed 000, §IV-A, Fig. 1): a disc of fixed
// particles on a square lattice, only the cleaning subsystem (dB/dt = -grad psi, dpsi/dt =
// -c_h^2 div B - psi/tau), with c_h frozen at t = 0 (no gas pressure in this test: the Alfven
// speed max |B|/sqrt(rho)), so that the cleaning energy is a constant of the sigma = 0 runs.
// One constructor for the example, the stepper study and the tests.
#include <string>
#include <vector>

#include "sphark/initial/lattice_2d.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"

namespace sphark {

// The disc's magnetic field (seed 000, eq. (40)): B_z = 1/sqrt(4 pi),
// B_x = [(r/r0)^8 - 2 (r/r0)^4 + 1] / sqrt(4 pi) for r < r0 = 1/sqrt(8), else 0. psi = 0.
void disc_initial_field(const SpmhdScheme<2>& scheme, const ParticleSet2D& p, Real* y);

// The four runs of Fig. 1: {constrained, non-conservative} x {sigma = 0, sigma > 0}.
struct CleaningDiscVariant {
  std::string name;
  Cleaning form;
  bool damped;
  bool vtk;  // writes a VTK series
};
const std::vector<CleaningDiscVariant>& cleaning_disc_variants();

// The unit disc (spacing 0.04: the seed's 1976 particles) with the given cleaning form and
// damping sigma (0: none); courant: dt = C h / c_h of max_stable_dt.
struct CleaningDisc {
  CleaningDisc(Cleaning form, Real sigma, Real spacing, Real courant = SpmhdOptions{}.courant);
  ParticleSet2D particles;
  SpmhdScheme<2> scheme;
  std::vector<Real> y0;
};

}  // namespace sphark
