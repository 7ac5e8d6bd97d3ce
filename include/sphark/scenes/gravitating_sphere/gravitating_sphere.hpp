#pragma once
// A self-gravitating gas sphere in 3D (issue #15), units G = M = R = 1: the hydrodynamics of the
// SPMHD scheme without a field (adiabatic gas, artificial viscosity), kernel-softened self-gravity
// (gravity/), isolated. Two profiles:
//   uniform   rho = 3 M / (4 pi R^3): with a small u0 a nearly pressureless free fall, whose every
//             mass shell has the exact solution of analytic/free_fall.hpp until t_ff
//   evrard    rho = M / (2 pi R^2 r), u = 0.05 (Evrard 1988): collapse, bounce, virialisation
// Particles on a cut close-packed lattice (the Evrard sphere stretched radially), or at random.
// Optional sink particles (sinks/): created from the densest gas above rho_sink when every check
// of sinks/sink_creation.hpp passes, accreting within r_acc; their gravity on the gas (and the
// gas's on them) is kernel-softened with h = r_acc / 2 (Newtonian beyond r_acc).
#include <string>
#include <vector>

#include "sphark/initial/spheres.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"
#include "sphark/sinks/sink.hpp"

namespace sphark {

// The default accretion radius, 0.03 R: the creation check 2 h < r_acc (sinks/sink_creation.hpp)
// passes at the default 30,000 particles once the gas reaches about rho_sink = 100 x the mean
// density (h = 1.2 (m / rho)^(1/3) = 0.0134 there, 2 h = 0.027), and the sink's softening length
// r_acc / 2 = 0.015 R stays below the 10 % Lagrangian radius until 0.99 t_ff of the free fall.
inline constexpr Real kDefaultSphereAccretionRadius = 0.03;

struct GravitatingSphereParams {
  std::string profile = "uniform";  // "uniform" | "evrard"
  std::size_t particles = 30000;    // requested (a lattice gives the nearest count it allows)
  bool random = false;              // random placement instead of the lattice
  Real u0 = 0;                      // initial specific internal energy (0: the profile's, 1e-4 / 0.05)
  Real gamma = 5.0 / 3.0;
  Real theta = kDefaultFixedTheta;  // tree opening angle (the root's with the mass-dependent opening)
  GravityOpening opening = GravityOpening::Fixed;
  GravitySolver gravity = GravitySolver::Tree;
  Real alpha_visc = 1;              // artificial viscosity (Monaghan 1997 signal velocity)
  Real alpha_u = 0;                 // artificial conductivity (off: the literature's Evrard runs have none)
  // 0.6: the cheapest Courant number measured with time errors <= 1/10 of the spatial ones and the
  // total energy kept to 1e-3 (docs/time_integration.md, "The self-gravitating spheres' default")
  Real courant = 0.6;
  Real force_courant = 0.25;
  bool sinks = false;                             // sink particles (off: the scheme has no sink species)
  Real rho_sink = 100 * 3 / (4 * kPi);            // creation threshold: 100 x the mean density 3 M / (4 pi R^3)
  Real accretion_radius = kDefaultSphereAccretionRadius;  // r_acc (R = 1)
};

// The profile's default u0: 1e-4 (uniform: thermal / gravitational energy 1.7e-4, nearly cold),
// 0.05 (Evrard).
Real default_u0(const std::string& profile);
SpmhdOptions gravitating_sphere_options(const GravitatingSphereParams& p);
// The sinks' parameters (isolated: no box; the kernel-softened pair potential of the gravity).
SinkParams gravitating_sphere_sink_params(const GravitatingSphereParams& p);

struct GravitatingSphere {
  explicit GravitatingSphere(const GravitatingSphereParams& p);
  ParticlePlacement placement;
  SpmhdScheme<3> scheme;
  std::vector<Real> y0;  // at rest
};

// Radii about the centre of mass enclosing the mass fractions `fractions` of equal-mass particles
// (positions 3 x n): the ceil(f n)-th smallest distance.
std::vector<Real> lagrangian_radii(const Real* x, std::size_t n, const std::vector<Real>& fractions);
// The same for n point masses m (positions 3 x n; gas and sinks alike): about their centre of
// mass, the smallest distance within which the mass (sorted by distance, summed) reaches f x the
// total (to a relative 1e-12, so that equal masses give the ceil(f n)-th distance as above).
std::vector<Real> lagrangian_radii(const Real* x, const Real* m, std::size_t n, const std::vector<Real>& fractions);

}  // namespace sphark
