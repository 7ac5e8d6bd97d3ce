#pragma once
// Shared set-ups of the cylinder-lattice tests.
#include <vector>

#include "sphark/scenes/cylinder_lattice/lattice_run.hpp"

namespace sphark::lattice_test {

// State (x, v) of system `sys` with positions x and every velocity = v.
inline std::vector<Real> state(const LatticeSystem& sys, const std::vector<Real>& x, const Vec<2>& v) {
  std::vector<Real> y(sys.size(), 0.0);
  for (std::size_t a = 0; a < sys.particles(); ++a) {
    y[sys.position_offset() + 2 * a] = x[2 * a];
    y[sys.position_offset() + 2 * a + 1] = x[2 * a + 1];
    y[sys.velocity_offset() + 2 * a] = v[0];
    y[sys.velocity_offset() + 2 * a + 1] = v[1];
  }
  return y;
}

inline LatticeParams undriven(GhostMap map) {
  LatticeParams p;
  p.map = map;
  p.tau = -1;   // no driving
  p.alpha = 0;  // no viscosity
  return p;
}

}  // namespace sphark::lattice_test
