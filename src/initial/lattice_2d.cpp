#include "sphark/initial/lattice_2d.hpp"

#include <cmath>
#include <stdexcept>

namespace sphark {

ParticleSet2D disc_square_lattice(Real radius, Real dx, Real rho) {
  ParticleSet2D p;
  p.spacing = dx;
  const int k = static_cast<int>(std::ceil(radius / dx)) + 1;
  for (int j = -k; j <= k; ++j)
    for (int i = -k; i <= k; ++i) {
      const Real x = (i + 0.5) * dx, y = (j + 0.5) * dx;
      if (x * x + y * y < radius * radius) {
        p.x.push_back(x);
        p.x.push_back(y);
        p.m.push_back(rho * dx * dx);
      }
    }
  return p;
}

int hexagonal_rows(int nx) {
  const int ny = static_cast<int>(std::lround(nx * 2.0 / std::sqrt(3.0) / 2.0)) * 2;
  return ny < 2 ? 2 : ny;
}

ParticleSet2D hexagonal_lattice_unit_box(int nx, int ny, Real rho) {
  if (nx < 4 || ny < 4 || ny % 2 != 0) throw std::invalid_argument("hexagonal lattice: need nx >= 4, even ny >= 4");
  ParticleSet2D p;
  const Real dx = 1.0 / nx, dy = 1.0 / ny;
  p.spacing = dx;
  const Real m = rho / (static_cast<Real>(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      p.x.push_back((i + 0.25 + 0.5 * (j % 2)) * dx);
      p.x.push_back((j + 0.5) * dy);
      p.m.push_back(m);
    }
  return p;
}

}  // namespace sphark
