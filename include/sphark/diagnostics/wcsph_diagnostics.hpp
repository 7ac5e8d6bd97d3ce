#pragma once
// What a run reports of a WCSPH state (seed 000, §III): energies, momentum, the mean |div v| of
// eq. (36) and the density error; and its VTK frame.
#include <vector>

#include "sphark/io/particle_frame.hpp"
#include "sphark/schemes/wcsph/wcsph_system.hpp"

namespace sphark {

template <int D>
struct WcsphDiagnostics {
  Real kinetic_energy = 0;
  Real internal_energy = 0;   // Tait EOS: integral of P / rho^2 d rho per unit mass
  Real potential_energy = 0;  // body-force potential
  Real psi_energy = 0;        // eq. (37): psi^2 / (2 c_h^2 rho^2) per unit mass
  Real total_energy = 0;
  Vec<D> momentum = Vec<D>::Zero();
  Real mean_abs_div_v = 0;    // particle mean of |div v|, eq. (36)
  Real max_rel_density_error = 0;  // max |rho - rho0| / rho0
};

// The diagnostics of state y (evaluates the system at y unless y is its last state evaluated).
template <int D, class Kernel>
WcsphDiagnostics<D> wcsph_diagnostics(WcsphSystem<D, Kernel>& system, Real t, const Real* y);

// The frame of a WCSPH state: positions, velocity, density, pressure, div v and, with cleaning,
// psi. Owns the copies its arrays point into (valid until the next build()).
class WcsphFrame {
 public:
  template <int D, class Kernel>
  ParticleFrame build(WcsphSystem<D, Kernel>& system, Real t, const Real* y);

 private:
  std::vector<Real> velocity_, density_, pressure_, div_v_, psi_;
};

}  // namespace sphark
