#include "sphark/schemes/spmhd/spmhd_setup.hpp"

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

PeriodicBox<2> unit_periodic_box() {
  PeriodicBox<2> box;
  box.periodic = {true, true};
  return box;
}

void disc_initial_field(const SpmhdScheme<2>& s, const ParticleSet2D& p, Real* y) {
  const StateLayout& L = s.layout();
  const Real b0 = 1.0 / std::sqrt(4 * kPi), r0 = 1.0 / std::sqrt(8.0);
  auto B = vector_field<3>(y, L, Field::MagneticField);
  for (std::size_t a = 0; a < p.size(); ++a) {
    const Real q = std::hypot(p.x[2 * a], p.x[2 * a + 1]) / r0;
    const Real q4 = q * q * q * q;
    B(0, a) = q < 1 ? b0 * (q4 * q4 - 2 * q4 + 1) : 0.0;  // seed 000, eq. (40)
    B(1, a) = 0;
    B(2, a) = b0;
  }
  if (L.has(Field::Psi)) scalar_field(y, L, Field::Psi).setZero();
}

void orszag_tang_initial_state(const SpmhdScheme<2>& s, const ParticleSet2D& p, Real* y) {
  const StateLayout& L = s.layout();
  const Real b0 = 1.0 / std::sqrt(4 * kPi), two_pi = 2 * kPi;
  const Real u0 = kOrszagTangPressure / ((s.options().gamma - 1) * kOrszagTangRho);
  auto x = vector_field<2>(y, L, Field::Position);
  auto v = vector_field<2>(y, L, Field::Velocity);
  auto u = scalar_field(y, L, Field::InternalEnergy);
  for (std::size_t a = 0; a < p.size(); ++a) {
    const Real px = p.x[2 * a], py = p.x[2 * a + 1];
    x(0, a) = px;
    x(1, a) = py;
    v(0, a) = -std::sin(two_pi * py);
    v(1, a) = std::sin(two_pi * px);
    u(a) = u0;
  }
  if (L.has(Field::MagneticField)) {
    auto B = vector_field<3>(y, L, Field::MagneticField);
    for (std::size_t a = 0; a < p.size(); ++a) {
      B(0, a) = -b0 * std::sin(two_pi * p.x[2 * a + 1]);
      B(1, a) = b0 * std::sin(2 * two_pi * p.x[2 * a]);
      B(2, a) = 0;
    }
  }
  if (L.has(Field::EulerAlpha)) {
    auto alpha = scalar_field(y, L, Field::EulerAlpha);
    for (std::size_t a = 0; a < p.size(); ++a)
      alpha(a) = b0 * (std::cos(2 * two_pi * p.x[2 * a]) / (2 * two_pi) + std::cos(two_pi * p.x[2 * a + 1]) / two_pi);
  }
  if (L.has(Field::Psi)) scalar_field(y, L, Field::Psi).setZero();
}

}  // namespace sphark
