#pragma once
// A self-gravitating gas sphere in 3D (issue #15), units G = M = R = 1: the hydrodynamics of the
// SPMHD scheme without a field (adiabatic gas, artificial viscosity), kernel-softened self-gravity
// (gravity/), isolated. Two profiles:
//   uniform   rho = 3 M / (4 pi R^3): with a small u0 a nearly pressureless free fall, whose every
//             mass shell has the exact solution of analytic/free_fall.hpp until t_ff
//   evrard    rho = M / (2 pi R^2 r), u = 0.05 (Evrard 1988): collapse, bounce, virialisation
// Particles on a cut close-packed lattice (the Evrard sphere stretched radially), or at random.
#include <string>
#include <vector>

#include "sphark/initial/spheres.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"

namespace sphark {

struct GravitatingSphereParams {
  std::string profile = "uniform";  // "uniform" | "evrard"
  std::size_t particles = 30000;    // requested (a lattice gives the nearest count it allows)
  bool random = false;              // random placement instead of the lattice
  Real u0 = 0;                      // initial specific internal energy (0: the profile's, 1e-4 / 0.05)
  Real gamma = 5.0 / 3.0;
  Real theta = 0.5;                 // tree opening angle
  GravitySolver gravity = GravitySolver::Tree;
  Real alpha_visc = 1;              // artificial viscosity (Monaghan 1997 signal velocity)
  Real alpha_u = 0;                 // artificial conductivity (off: the literature's Evrard runs have none)
  Real courant = 0.3;
  Real force_courant = 0.25;
};

// The profile's default u0: 1e-4 (uniform: thermal / gravitational energy 1.7e-4, nearly cold),
// 0.05 (Evrard).
Real default_u0(const std::string& profile);
SpmhdOptions gravitating_sphere_options(const GravitatingSphereParams& p);

struct GravitatingSphere {
  explicit GravitatingSphere(const GravitatingSphereParams& p);
  ParticlePlacement placement;
  SpmhdScheme<3> scheme;
  std::vector<Real> y0;  // at rest
};

// Radii about the centre of mass enclosing the mass fractions `fractions` of equal-mass particles
// (positions 3 x n): the ceil(f n)-th smallest distance.
std::vector<Real> lagrangian_radii(const Real* x, std::size_t n, const std::vector<Real>& fractions);

}  // namespace sphark
