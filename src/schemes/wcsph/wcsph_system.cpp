#include "sphark/schemes/wcsph/wcsph_system.hpp"

#include <algorithm>
#include <exception>
#include <sstream>

#include "sphark/core/profile.hpp"
#include "sphark/kernels/kernel_list.hpp"
#include "sphark/operators/artificial_viscosity.hpp"
#include "sphark/operators/conjugate_cleaning.hpp"
#include "sphark/operators/density_diffusion.hpp"
#include "sphark/operators/pair_geometry.hpp"
#include "sphark/operators/pressure_force.hpp"
#include "sphark/operators/renormalised_gradient.hpp"
#include "sphark/operators/tait_eos.hpp"

namespace sphark {

namespace {
template <int D>
StateLayout wcsph_layout(std::size_t n, bool cleaning) {
  StateLayout L(n);
  L.add(Field::Position, D).add(Field::Velocity, D).add(Field::Density, 1);
  if (cleaning) L.add(Field::Psi, 1);
  return L;
}
}  // namespace

template <int D, class Kernel>
WcsphSystem<D, Kernel>::WcsphSystem(std::size_t particles, WcsphParams<D> params, std::optional<PeriodicBox<D>> box)
    : p_(std::move(params)), layout_(wcsph_layout<D>(particles, p_.cleaning)), search_(std::move(box)) {
  if (!(p_.h > 0) || !(p_.mass > 0) || !(p_.rho0 > 0) || !(p_.sound_speed > 0))
    throw std::invalid_argument("WcsphSystem: h, mass, rho0 and sound_speed must be positive");
  pressure_.assign(particles, 0);
  p_over_rho2_.assign(particles, 0);
  q_psi_.assign(particles, 0);
  div_v_.assign(particles, 0);
  grad_rho_.assign(particles, Vec<D>::Zero());
}

template <int D, class Kernel>
void WcsphSystem<D, Kernel>::update_neighbours(const Real* x) {
  const Real support = Kernel::support * p_.h;
  const Real skin = p_.skin_fraction * support;
  ScopedPhase timer(Phase::Neighbours);
  if (built_ && search_.max_displacement_since_build(x) < 0.5 * skin) return;
  search_.build(x, layout_.particles(), support + skin);
  built_ = true;
  ++builds_;
}

// <grad rho>^L of Antuono et al. (2010), eq. (12), for the corrected density diffusion.
template <int D, class Kernel>
void WcsphSystem<D, Kernel>::renormalised_density_gradients(const Real* x, const Real* rho) {
  const NeighbourList& nl = search_.list();
  const Real h = p_.h, support2 = Kernel::support * h * Kernel::support * h;
  const std::size_t n = layout_.particles();
  ScopedPhase timer(Phase::DensityH);
#pragma omp parallel for schedule(static)
  for (std::size_t a = 0; a < n; ++a) {
    RenormalisedGradient<D> g;
    for (std::size_t k = nl.begin(a); k < nl.end(a); ++k) {
      const std::size_t b = nl.indices[k];
      const Vec<D> x_ab = search_.separation(x, a, b);
      if (x_ab.squaredNorm() >= support2) continue;
      g.add(p_.mass / rho[b], rho[a], rho[b], x_ab, Kernel::f_over_r(x_ab.norm(), h) * x_ab);
    }
    grad_rho_[a] = g.finish();
  }
}

// The state is finite with rho > 0 (the stepper's guard checks it before every call).
template <int D, class Kernel>
int WcsphSystem<D, Kernel>::rhs(Real /*t*/, const Real* y, Real* ydot) {
  ScopedPhase rhs_timer(Phase::Rhs);
  ++rhs_calls_;
  evaluated_y_.clear();  // set again once every derived array is y's
  const auto x = vector_field<D>(y, layout_, Field::Position);
  const auto v = vector_field<D>(y, layout_, Field::Velocity);
  const auto rho = scalar_field(y, layout_, Field::Density);
  auto dx = vector_field<D>(ydot, layout_, Field::Position);
  auto dv = vector_field<D>(ydot, layout_, Field::Velocity);
  auto drho = scalar_field(ydot, layout_, Field::Density);
  const bool clean = p_.cleaning;
  const Real* psi = clean ? y + layout_.offset(Field::Psi) : nullptr;
  Real* dpsi = clean ? ydot + layout_.offset(Field::Psi) : nullptr;
  const bool subsystem = p_.cleaning_subsystem_only;

  update_neighbours(x.data());
  const std::size_t n = layout_.particles();
  const Real m = p_.mass, h = p_.h, c_h = p_.cleaning_speed();
  const Real dh_c = p_.delta * h * p_.sound_speed;
#pragma omp parallel for schedule(static)
  for (std::size_t a = 0; a < n; ++a) {
    pressure_[a] = tait_pressure(rho[a], p_.rho0, p_.sound_speed);
    p_over_rho2_[a] = pressure_[a] / (rho[a] * rho[a]);
    if (clean) q_psi_[a] = psi[a] / (rho[a] * rho[a]);  // Omega = 1 for constant h
  }

  const bool corrected_diffusion = dh_c > 0 && p_.diffusion_correction && !subsystem;
  if (corrected_diffusion) renormalised_density_gradients(x.data(), rho.data());
  const Vec<D> zero = Vec<D>::Zero();
  const NeighbourList& nl = search_.list();
  const Real support2 = Kernel::support * h * Kernel::support * h;
  Real max_acc2 = 0;
  ScopedPhase forces_timer(Phase::Forces);
#pragma omp parallel for schedule(static) reduction(max : max_acc2)
  for (std::size_t a = 0; a < n; ++a) {
    Vec<D> acc = Vec<D>::Zero();
    Real cont = 0, diffusion = 0, div_sum = 0;
    const Vec<D> va = v.col(a);
    for (std::size_t k = nl.begin(a); k < nl.end(a); ++k) {
      const std::size_t b = nl.indices[k];
      const Vec<D> x_ab = search_.separation(x.data(), a, b);
      if (x_ab.squaredNorm() >= support2) continue;
      const auto g = pair_geometry<Kernel, D>(x_ab, h);
      const Vec<D> v_ab = va - v.col(b);
      // seed 000, eq. (36): summand of the difference divergence of v (also the continuity sum)
      const Real div_term = difference_divergence_term(m, va, Vec<D>(v.col(b)), g.grad_w);
      div_sum += div_term;
      if (clean) acc += -symmetric_gradient_term(m, q_psi_[a], g.grad_w, q_psi_[b], g.grad_w);  // eq. (39)
      if (subsystem) continue;
      acc += pressure_acceleration_term<D>(m, p_over_rho2_[a], p_over_rho2_[b], g.grad_w);  // eq. (27)
      if (p_.alpha > 0) {
        const Real c_ab = 0.5 * (tait_sound_speed(rho[a], p_.rho0, p_.sound_speed) +
                                 tait_sound_speed(rho[b], p_.rho0, p_.sound_speed));
        acc += monaghan_viscosity_term<D>(m, p_.alpha, c_ab, 0.5 * (rho[a] + rho[b]), h, x_ab, v_ab, g.grad_w);
      }
      cont += continuity_term<D>(m, v_ab, g.grad_w);  // eq. (28), sign of eq. (36)
      if (dh_c > 0)
        diffusion += density_diffusion_term<D>(m / rho[b], rho[a], rho[b], corrected_diffusion ? grad_rho_[a] : zero,
                                               corrected_diffusion ? grad_rho_[b] : zero, x_ab, g.grad_w);
    }
    div_v_[a] = -div_sum / rho[a];  // eq. (36)
    if (!subsystem && p_.body_force) acc += p_.body_force(Vec<D>(x.col(a)));
    dv.col(a) = acc;
    dx.col(a) = subsystem ? Vec<D>::Zero() : va;
    drho[a] = subsystem ? 0.0 : cont + dh_c * diffusion;
    if (clean) dpsi[a] = -c_h * c_h * rho[a] * div_v_[a] - p_.cleaning_rate() * psi[a];  // eq. (30)
    max_acc2 = std::max(max_acc2, acc.squaredNorm());
  }
  max_accel_ = std::sqrt(max_acc2);
  evaluated_y_.assign(y, y + layout_.size());
  return 0;
}

template <int D, class Kernel>
int WcsphSystem<D, Kernel>::stiff_diagonal(Real /*t*/, const Real* /*y*/, Real* c) {
  std::fill(c, c + layout_.size(), 0.0);
  if (!p_.cleaning) return 0;
  const std::size_t o = layout_.offset(Field::Psi);
  std::fill(c + o, c + o + layout_.particles(), p_.cleaning_rate());  // psi / tau of eq. (30)
  return 0;
}

template <int D, class Kernel>
void WcsphSystem<D, Kernel>::evaluate(Real t, const Real* y) {
  if (evaluated_y_.size() == layout_.size() && std::equal(y, y + layout_.size(), evaluated_y_.begin())) return;
  scratch_.resize(layout_.size());
  if (rhs(t, y, scratch_.data()) != 0) throw std::runtime_error("WcsphSystem: " + error_);
}

// max_a |dv_a/dt| of a derivative: the force criterion's acceleration.
template <int D, class Kernel>
Real WcsphSystem<D, Kernel>::max_acceleration(const Real* ydot) const {
  const auto dv = vector_field<D>(ydot, layout_, Field::Velocity);
  Real max_acc2 = 0;
  for (Index a = 0; a < dv.cols(); ++a) max_acc2 = std::max(max_acc2, Vec<D>(dv.col(a)).squaredNorm());
  return std::sqrt(max_acc2);
}

template <int D, class Kernel>
Real WcsphSystem<D, Kernel>::max_stable_dt(Real t, const Real* y, const Real* ydot) {
  const auto v = vector_field<D>(y, layout_, Field::Velocity);
  const auto rho = scalar_field(y, layout_, Field::Density);
  Real vmax = 0, cmax = p_.cleaning ? p_.cleaning_speed() : 0;
  for (Index a = 0; a < v.cols(); ++a) {
    vmax = std::max(vmax, v.col(a).norm());
    cmax = std::max(cmax, tait_sound_speed(rho[a], p_.rho0, p_.sound_speed));
  }
  // Courant condition with the viscous signal speed (Monaghan 1992), and the force condition.
  Real dt = p_.cfl * p_.h / (cmax + vmax + 1.2 * p_.alpha * cmax);
  Real accel = 0;
  if (ydot) {
    accel = max_acceleration(ydot);
  } else {
    evaluate(t, y);
    accel = max_accel_;
  }
  if (accel > 0) dt = std::min(dt, p_.cfl * std::sqrt(p_.h / accel));
  return dt;
}

#define SPHARK_WCSPH_SYSTEM(K)          \
  template class WcsphSystem<2, K<2>>; \
  template class WcsphSystem<3, K<3>>;
SPHARK_KERNELS(SPHARK_WCSPH_SYSTEM)
#undef SPHARK_WCSPH_SYSTEM

}  // namespace sphark
