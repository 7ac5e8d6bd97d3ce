#pragma once
// Exact properties of one SPMHD right-hand side, for any dimension and kernel: the total momentum
// rate and the total energy rate (with their scales, for "zero to round-off" checks), and a
// disordered periodic cubic lattice in D dimensions with random fields (the 3D tests).
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "sphark/schemes/spmhd/spmhd_scheme.hpp"

namespace sphark::test {

// Every term that conserves energy on (viscosity, conductivity, resistivity, constrained cleaning
// without damping), and not the (9) term (which does not conserve momentum).
inline SpmhdOptions conserving_options() {
  SpmhdOptions o;
  o.alpha_b = 1.0;
  o.cleaning = Cleaning::Constrained;
  o.sigma = 0;
  o.subtract_monopole_force = false;
  return o;
}

// sum_a m_a dv_a/dt and its scale sum_a m_a |dv_a/dt|.
template <int D, class K>
std::pair<Vec<D>, Real> momentum_rate(const SpmhdScheme<D, K>& s, const std::vector<Real>& ydot) {
  const auto dv = vector_field<D>(ydot.data(), s.layout(), Field::Velocity);
  Vec<D> total = Vec<D>::Zero();
  Real scale = 0;
  for (std::size_t a = 0; a < s.particles(); ++a) {
    total += s.masses()[a] * dv.col(a);
    scale += s.masses()[a] * dv.col(a).norm();
  }
  return {total, scale};
}

struct EnergyRate {
  Real rate = 0;   // dE/dt
  Real scale = 0;  // sum of the magnitudes of its terms
};

// d/dt sum_a m_a (v^2/2 + u + B^2/(2 rho) + psi^2/(2 rho c_h^2)) after s.rhs(y) -> ydot, with the
// time derivative of the summation density (4) at variable h: drho_a/dt = -rho_a div v_a (the
// continuity form of eq. (25)).
template <int D, class K>
EnergyRate energy_rate(const SpmhdScheme<D, K>& s, const std::vector<Real>& y, const std::vector<Real>& ydot) {
  const StateLayout& L = s.layout();
  auto v = vector_field<D>(y.data(), L, Field::Velocity);
  auto dv = vector_field<D>(ydot.data(), L, Field::Velocity);
  auto du = scalar_field(ydot.data(), L, Field::InternalEnergy);
  auto B = vector_field<3>(y.data(), L, Field::MagneticField);
  auto dB = vector_field<3>(ydot.data(), L, Field::MagneticField);
  const bool psi_field = L.has(Field::Psi);
  const Real ch2 = s.cleaning_speed() * s.cleaning_speed();
  EnergyRate e;
  for (std::size_t a = 0; a < s.particles(); ++a) {
    const Real m = s.masses()[a], rho = s.rho()[a], drho = -rho * s.div_v()[a];
    std::vector<Real> terms = {m * v.col(a).dot(dv.col(a)), m * du(a), m * B.col(a).dot(dB.col(a)) / rho,
                               -m * B.col(a).squaredNorm() / (2 * rho * rho) * drho};
    if (psi_field) {
      const Real psi = y[L.offset(Field::Psi) + a], dpsi = ydot[L.offset(Field::Psi) + a];
      terms.push_back(m * psi * dpsi / (rho * ch2));
      terms.push_back(-m * psi * psi / (2 * rho * rho * ch2) * drho);
    }
    for (Real t : terms) {
      e.rate += t;
      e.scale += std::abs(t);
    }
  }
  return e;
}

// A periodic unit box in D dimensions (all directions periodic).
template <int D>
PeriodicBox<D> unit_box() {
  PeriodicBox<D> box;
  for (int k = 0; k < D; ++k) box.periodic[k] = true;
  return box;
}

// nx^D particles of mass dx^D (rho ~ 1) on a cubic lattice in the periodic unit box, displaced by
// up to `disorder` dx (so that h varies), with random velocities, thermal energies (pressure
// jumps), a smooth field plus noise, and random psi where the layout has it; uniform_b: B the same
// everywhere instead.
struct LatticeCase {
  int nx = 8;
  Real disorder = 0.2;
  bool uniform_b = false;
  unsigned seed = 5;
};

template <int D>
std::vector<Real> lattice_masses(const LatticeCase& c) {
  const Real dx = 1.0 / c.nx;
  return std::vector<Real>(static_cast<std::size_t>(std::pow(c.nx, D)), std::pow(dx, D));
}

template <int D, class K>
std::vector<Real> lattice_state(const SpmhdScheme<D, K>& s, const LatticeCase& c) {
  const StateLayout& L = s.layout();
  std::vector<Real> y(L.size(), 0);
  auto x = vector_field<D>(y.data(), L, Field::Position);
  auto v = vector_field<D>(y.data(), L, Field::Velocity);
  auto u = scalar_field(y.data(), L, Field::InternalEnergy);
  auto B = vector_field<3>(y.data(), L, Field::MagneticField);
  std::mt19937_64 rng(c.seed);
  std::uniform_real_distribution<Real> U(-1, 1);
  const Real dx = 1.0 / c.nx;
  for (std::size_t a = 0; a < s.particles(); ++a) {
    std::size_t rest = a;
    for (int k = 0; k < D; ++k) {
      x(k, a) = (static_cast<Real>(rest % c.nx) + 0.5 + c.disorder * U(rng)) * dx;
      rest /= c.nx;
      v(k, a) = U(rng);
    }
    u(a) = 1.5 * (1 + 0.3 * U(rng));
    const Real s1 = std::sin(2 * kPi * x(0, a)), s2 = std::sin(2 * kPi * x(1, a));
    B.col(a) = c.uniform_b ? Eigen::Vector3d(0.3, -0.2, 0.1)
                           : Eigen::Vector3d(-0.3 * s2 + 0.05 * U(rng), 0.3 * s1, 0.1 + 0.05 * U(rng));
  }
  if (L.has(Field::Psi)) {
    auto psi = scalar_field(y.data(), L, Field::Psi);
    for (std::size_t a = 0; a < s.particles(); ++a) psi(a) = 0.05 * U(rng);
  }
  return y;
}

}  // namespace sphark::test
