#pragma once
// The Orszag-Tang vortex (seed 000, §IV-B): SPMHD on the periodic unit square, one constructor
// for the example, the stepper study, the benchmarks and the tests. Units mu0 = 1:
// rho = 25/(36 pi) (through the masses), P = 5/(12 pi), gamma = 5/3, v = (-sin 2 pi y, sin 2 pi x),
// B = B0 (-sin 2 pi y, sin 4 pi x, 0) with B0 = 1/sqrt(4 pi) (beta0 = 2 P / B0^2 = 10/3). With
// Euler potentials the state holds alpha = A_z = B0 (cos(4 pi x)/(4 pi) + cos(2 pi y)/(2 pi)),
// B = (d_y A_z, -d_x A_z).
//
// Five ways of controlling div B (the variants): none, artificial resistivity (eq. (10)), Euler
// potentials, constrained cleaning (eqs. (19)-(25)), cleaning plus resistivity.
#include <string>
#include <vector>

#include "sphark/initial/lattice_2d.hpp"
#include "sphark/neighbours/periodic_box.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"

namespace sphark {

inline constexpr Real kOrszagTangRho = 25.0 / (36.0 * kPi);
inline constexpr Real kOrszagTangPressure = 5.0 / (12.0 * kPi);

PeriodicBox<2> unit_periodic_box();

// The Orszag-Tang fields on particles p into the state y of `scheme` (its layout decides which).
void orszag_tang_initial_state(const SpmhdScheme<2>& scheme, const ParticleSet2D& p, Real* y);

// The scene's parameters (the example's options).
struct OrszagTangParams {
  int nx = 128;            // particles per row of the hexagonal lattice; rows: hexagonal_rows(nx)
  Real sigma = 0.3;        // cleaning damping, 1/tau = sigma c_h / h
  Real alpha_b = 1.0;      // artificial resistivity of the resistivity variants
  Real overclean = 8.0;    // cleaning variants: c_h = overclean x max fast speed (docs/spmhd.md)
  Real courant = 0.3;      // every variant: dt = C h / max(v_sig, c_h)
  Real cleaning_courant = 0.45;  // cleaning variants: the cleaning wave's own C_h (0 = C); measured stable to 0.6 (docs/spmhd.md)
  bool local_ch = false;   // per-particle c_h (Tricco, Price & Bate 2016)
  Real skin = SpmhdOptions{}.skin;  // Verlet skin in units of h (results do not depend on it)
  Real resort = 0.3;       // re-sort the state into cell order (cells 4 / nx) above this scrambled fraction
                           // (0: never; run/state_resort.hpp, docs/performance.md)
};

// "none", "resistivity", "euler", "cleaning", "cleaning+resistivity".
const std::vector<std::string>& orszag_tang_variants();
// The SPMHD options of a variant (std::invalid_argument for an unknown one), with h_initial
// from the lattice.
SpmhdOptions orszag_tang_options(const std::string& variant, const OrszagTangParams& params);

// The particles, the scheme and the initial state of one variant.
struct OrszagTang {
  OrszagTang(const std::string& variant, const OrszagTangParams& params);
  int nx, ny;
  ParticleSet2D particles;
  SpmhdScheme<2> scheme;
  std::vector<Real> y0;
};

}  // namespace sphark
