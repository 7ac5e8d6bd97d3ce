#include "sphark/initial/close_packed.hpp"

#include <cmath>
#include <stdexcept>

namespace sphark {

Real close_packed_spacing(Real number_density) {
  if (!(number_density > 0)) throw std::invalid_argument("close_packed_spacing: number density must be positive");
  return std::cbrt(1.4142135623730951 / number_density);
}

namespace {

// Calls site(x, y, z) for every lattice site with |x| < radius.
template <class Site>
void fcc_ball(Real d, Real radius, Site&& site) {
  const Real half = std::sqrt(2.0) * d / 2;  // a / 2
  const Real c = half / 2;                   // inversion centre (a/4, a/4, 0): mid-point of a pair
  const long K = static_cast<long>(std::ceil(radius / half)) + 2;
  const Real r2 = radius * radius;
  for (long k = -K; k <= K; ++k)
    for (long j = -K; j <= K; ++j)
      for (long i = -K; i <= K; ++i) {
        if ((i + j + k) % 2 != 0) continue;
        const Real x = half * i - c, y = half * j - c, z = half * k;
        if (x * x + y * y + z * z < r2) site(x, y, z);
      }
}

template <class Site>
void hcp_ball(Real d, Real radius, Site&& site) {
  const Real row = d * std::sqrt(3.0) / 2;       // distance between rows of a triangular net
  const Real layer = d * std::sqrt(2.0 / 3.0);   // distance between A and B layers
  const Real cx = d / 4, cy = d * std::sqrt(3.0) / 12, cz = layer / 2;  // inversion centre
  const long L = static_cast<long>(std::ceil(radius / layer)) + 2;
  const long J = static_cast<long>(std::ceil(radius / row)) + 2;
  const long I = static_cast<long>(std::ceil(radius / d)) + J + 2;
  const Real r2 = radius * radius;
  for (long l = -L; l <= L; ++l) {
    const bool b_layer = (l % 2 + 2) % 2 == 1;
    const Real sx = b_layer ? d / 2 : 0, sy = b_layer ? d * std::sqrt(3.0) / 6 : 0;
    const Real z = layer * l - cz;
    for (long j = -J; j <= J; ++j)
      for (long i = -I; i <= I; ++i) {
        const Real x = d * (i + 0.5 * j) + sx - cx, y = row * j + sy - cy;
        if (x * x + y * y + z * z < r2) site(x, y, z);
      }
  }
}

template <class Site>
void close_packed_sites(CloseLattice lattice, Real spacing, Real radius, Site&& site) {
  if (!(spacing > 0) || !(radius > 0)) throw std::invalid_argument("close_packed_ball: spacing and radius must be positive");
  if (lattice == CloseLattice::fcc)
    fcc_ball(spacing, radius, site);
  else
    hcp_ball(spacing, radius, site);
}

}  // namespace

std::vector<Real> close_packed_ball(CloseLattice lattice, Real spacing, Real radius) {
  std::vector<Real> x;
  x.reserve(3 * close_packed_ball_count(lattice, spacing, radius));
  close_packed_sites(lattice, spacing, radius, [&](Real a, Real b, Real c) { x.insert(x.end(), {a, b, c}); });
  return x;
}

std::size_t close_packed_ball_count(CloseLattice lattice, Real spacing, Real radius) {
  std::size_t n = 0;
  close_packed_sites(lattice, spacing, radius, [&](Real, Real, Real) { ++n; });
  return n;
}

std::vector<Real> fcc_periodic_cube(Real side, std::size_t cells, Real exclude_radius) {
  if (!(side > 0) || cells == 0) throw std::invalid_argument("fcc_periodic_cube: need side > 0 and cells >= 1");
  const Real a = side / static_cast<Real>(cells), lo = -side / 2;
  // basis of the cubic cell, offset by a/4 along x and y: no site on the x and y faces
  static const Real basis[4][3] = {{0.25, 0.25, 0}, {0.75, 0.75, 0}, {0.75, 0.25, 0.5}, {0.25, 0.75, 0.5}};
  const Real r2 = exclude_radius * exclude_radius;
  std::vector<Real> x;
  x.reserve(12 * cells * cells * cells);
  for (std::size_t k = 0; k < cells; ++k)
    for (std::size_t j = 0; j < cells; ++j)
      for (std::size_t i = 0; i < cells; ++i)
        for (const auto& b : basis) {
          const Real px = lo + a * (i + b[0]), py = lo + a * (j + b[1]), pz = lo + a * (k + b[2]);
          if (px * px + py * py + pz * pz >= r2) x.insert(x.end(), {px, py, pz});
        }
  return x;
}

}  // namespace sphark
