#pragma once
// Parameters of weakly compressible SPH with constrained velocity cleaning (seed 000, §III).
#include <functional>
#include <string>

#include "sphark/core/types.hpp"

namespace sphark {

template <int D>
struct WcsphParams {
  Real rho0 = 1000;           // reference density, eq. (26)
  Real sound_speed = 1400;    // c_s, eq. (26)
  Real mass = 0;              // particle mass (all equal)
  Real h = 0;                 // smoothing length, constant (eq. (5) at t = 0)
  Real alpha = 0.0;           // Monaghan artificial viscosity coefficient
  Real delta = 0.1;           // density diffusion (delta-SPH) coefficient; 0 switches it off
  bool diffusion_correction = true;  // Antuono et al. (2010) correction; false: Molteni & Colagrossi
  bool cleaning = false;      // constrained velocity cleaning, eqs. (29)-(30) with (36), (39)
  Real clean_speed = 0;       // c_h; 0 means c_h = c_s
  Real clean_sigma = 0.5;     // damping strength sigma, tau = h / (sigma c_h); 0: purely hyperbolic
  bool cleaning_subsystem_only = false;  // particles fixed; evolve only v and psi by (29)-(30)
  Real cfl = 0.25;            // CFL number of max_stable_dt: dt <= cfl h / (c + |v|max)
  Real skin_fraction = 0.1;   // Verlet skin as a fraction of the support radius
  // External body force per unit mass, a = g(x); empty for none.
  std::function<Vec<D>(const Vec<D>&)> body_force;
  // Potential per unit mass of the body force, for the total-energy diagnostic (optional).
  std::function<Real(const Vec<D>&)> body_potential;

  Real cleaning_speed() const { return clean_speed > 0 ? clean_speed : sound_speed; }
  // seed 000, text after eq. (3): tau^-1 = sigma c_h / h
  Real cleaning_rate() const { return clean_sigma * cleaning_speed() / h; }
};

}  // namespace sphark
