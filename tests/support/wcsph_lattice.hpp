#pragma once
// A disturbed periodic square lattice of WCSPH particles for tests of WcsphSystem: positions
// moved by up to 0.2 dx, random velocities in [-1, 1]^2, a density with a gradient (1 % sine
// along x plus 0.2 % noise) and, when the layout has psi, psi in [-psi_scale, psi_scale].
#include <cmath>
#include <random>
#include <vector>

#include "sphark/schemes/wcsph/wcsph_params.hpp"
#include "sphark/state/state_layout.hpp"

namespace sphark::test {

struct WcsphLattice {
  int side = 40;  // particles per side
  Real dx = 0.05, rho0 = 1000, c0 = 20;
  unsigned seed = 5;
  Real psi_scale = 10;

  std::size_t particles() const { return static_cast<std::size_t>(side) * static_cast<std::size_t>(side); }
  PeriodicBox<2> box() const { return {Vec<2>::Zero(), Vec<2>::Constant(side * dx), {true, true}}; }
  // Tait fluid with Antuono's corrected density diffusion, no viscosity, no cleaning
  WcsphParams<2> params() const {
    WcsphParams<2> p;
    p.mass = rho0 * dx * dx;
    p.h = 1.3 * dx;
    p.rho0 = rho0;
    p.sound_speed = c0;
    p.alpha = 0;
    p.delta = 0.1;
    p.diffusion_correction = true;
    return p;
  }
  std::vector<Real> disturbed_state(const StateLayout& L) const {
    std::vector<Real> y(L.size());
    auto x = vector_field<2>(y.data(), L, Field::Position);
    auto v = vector_field<2>(y.data(), L, Field::Velocity);
    auto rho = scalar_field(y.data(), L, Field::Density);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<Real> u(-1, 1);
    const auto n = static_cast<std::size_t>(side);
    for (std::size_t a = 0; a < L.particles(); ++a) {
      x.col(a) = Vec<2>((a % n + 0.5) * dx, (a / n + 0.5) * dx) + 0.2 * dx * Vec<2>(u(rng), u(rng));
      v.col(a) = Vec<2>(u(rng), u(rng));
      rho[a] = rho0 * (1 + 0.01 * std::sin(2 * kPi * x(0, a) / (side * dx)) + 0.002 * u(rng));
      if (L.has(Field::Psi)) y[L.offset(Field::Psi) + a] = psi_scale * u(rng);
    }
    return y;
  }
};

}  // namespace sphark::test
