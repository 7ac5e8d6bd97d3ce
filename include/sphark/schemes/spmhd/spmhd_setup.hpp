#pragma once
// Initial conditions of the SPMHD reproductions (seed 000, §IV-A and §IV-B), shared by the
// examples and the tests.
#include <optional>
#include <vector>

#include "sphark/neighbours/periodic_box.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"

namespace sphark {

struct ParticleSet2D {
  std::vector<Real> x;  // 2 x N, column-major
  std::vector<Real> m;  // N
  Real spacing = 0;
  std::size_t size() const { return m.size(); }
};

// Square lattice points ((i + 1/2) dx, (j + 1/2) dx) inside the disc r < R, mass rho dx^2.
// R = 1, dx = 0.04 gives the seed's 1976 particles (§IV-A).
ParticleSet2D disc_square_lattice(Real radius, Real dx, Real rho);

// Hexagonal (close-packed) lattice filling the periodic box [0,1]^2: nx particles per row,
// ny rows (ny even so that the lattice is periodic), odd rows shifted by dx/2. The seed's
// 512 x 590 is nx = 512, ny = 590 (590/512 ~ 2/sqrt(3)). Mass rho / (nx ny).
ParticleSet2D hexagonal_lattice_unit_box(int nx, int ny, Real rho);
PeriodicBox<2> unit_periodic_box();

// Rows of a hexagonal lattice for a given nx: the even number nearest nx * 2 / sqrt(3).
int hexagonal_rows(int nx);

// The disc's magnetic field (seed 000, eq. (40)): B_z = 1/sqrt(4 pi),
// B_x = [(r/r0)^8 - 2 (r/r0)^4 + 1] / sqrt(4 pi) for r < r0 = 1/sqrt(8), else 0. psi = 0.
void disc_initial_field(const SpmhdScheme<2>& scheme, const ParticleSet2D& p, Real* y);

// Orszag-Tang (seed 000, §IV-B): rho = 25/(36 pi) (through the masses), P = 5/(12 pi),
// gamma = 5/3, v = (-sin 2 pi y, sin 2 pi x), B = B0 (-sin 2 pi y, sin 4 pi x, 0) with
// B0 = 1/sqrt(4 pi) (mu0 = 1: beta0 = 2 P / B0^2 = 10/3). With Euler potentials the state holds
// alpha = A_z = B0 (cos(4 pi x)/(4 pi) + cos(2 pi y)/(2 pi)), B = (d_y A_z, -d_x A_z).
inline constexpr Real kOrszagTangRho = 25.0 / (36.0 * kPi);
inline constexpr Real kOrszagTangPressure = 5.0 / (12.0 * kPi);
void orszag_tang_initial_state(const SpmhdScheme<2>& scheme, const ParticleSet2D& p, Real* y);

}  // namespace sphark
