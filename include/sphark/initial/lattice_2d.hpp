#pragma once
// Particle placements in 2D shared by the scenes: a square lattice cut to a disc (the cleaning
// disc of seed 000 §IV-A and the water drop of §IV-D) and a hexagonal lattice filling the
// periodic unit square (Orszag-Tang, §IV-B).
#include <cstddef>
#include <vector>

#include "sphark/core/types.hpp"

namespace sphark {

struct ParticleSet2D {
  std::vector<Real> x;  // 2 x N, column-major
  std::vector<Real> m;  // N
  Real spacing = 0;
  std::size_t size() const { return m.size(); }
};

// Square lattice points ((i + 1/2) dx, (j + 1/2) dx) strictly inside the disc r < R (rows j
// outer, columns i inner, both ascending), mass rho dx^2. R = 1, dx = 0.04 gives the seed's 1976
// particles (§IV-A, §IV-D).
ParticleSet2D disc_square_lattice(Real radius, Real dx, Real rho);

// Hexagonal (close-packed) lattice filling the periodic box [0,1]^2: nx particles per row,
// ny rows (ny even so that the lattice is periodic), odd rows shifted by dx/2. The seed's
// 512 x 590 is nx = 512, ny = 590 (590/512 ~ 2/sqrt(3)). Mass rho / (nx ny).
ParticleSet2D hexagonal_lattice_unit_box(int nx, int ny, Real rho);

// Rows of a hexagonal lattice for a given nx: the even number nearest nx * 2 / sqrt(3).
int hexagonal_rows(int nx);

}  // namespace sphark
