// Sink particles in the SPMHD state (3D): the species Species::Sink (position, velocity, mass,
// spin) after the gas fields. Their gravity on the gas and the gas's on them, and between sinks
// (Bate, Bonnell & Price 1995; gravity/point_mass_gravity.hpp: equal and opposite pair forces,
// momentum conserved); dx/dt = v, dv/dt = a, the mass and spin change only between steps
// (sinks/sink_events.hpp: creation, accretion). The potential energy gains the sink-gas and
// sink-sink pair energies, and each gas particle's potential the sinks' (the creation checks
// read it).
#include <algorithm>
#include <stdexcept>
#include <type_traits>

#include "sphark/kernels/kernel_list.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"

namespace sphark {

template <int D, class K>
void SpmhdScheme<D, K>::sink_pass(const Real* y, Real* ydot) {
  if constexpr (D == 3) {
    const std::size_t ns = layout_.particles(Species::Sink);
    if (ns == 0) return;
    const Real* xs = y + layout_.offset(Species::Sink, Field::Position);
    const Real* vs = y + layout_.offset(Species::Sink, Field::Velocity);
    const Real* ms = y + layout_.offset(Species::Sink, Field::Mass);
    sink_acc_.assign(3 * ns, 0);
    sink_potential_.assign(ns, 0);
    gas_from_sinks_.assign(3 * n_, 0);
    const PointMasses sinks{xs, ms, ns};
    const GravitySources gas = gravity_sources();  // particle order, as the self-gravity's (spmhd_gravity.cpp)
    Real energy = sink_gas_.add(opt_.G, sinks, gas, opt_.sink_softening, gas_from_sinks_.data(),
                                gravity_potential_.data(), sink_acc_.data(), sink_potential_.data());
    energy += add_sink_sink_gravity<K>(opt_.G, sinks, opt_.sink_softening, sink_acc_.data(), sink_potential_.data());
    potential_energy_ += energy;
    Real* dv_dt = ydot + layout_.offset(Field::Velocity);
#pragma omp parallel for schedule(static)
    for (std::size_t a = 0; a < n_; ++a)
      Eigen::Map<Vec<3>>(dv_dt + 3 * a) += Eigen::Map<const Vec<3>>(gas_from_sinks_.data() + 3 * a);
    std::copy(vs, vs + 3 * ns, ydot + layout_.offset(Species::Sink, Field::Position));
    std::copy(sink_acc_.begin(), sink_acc_.end(), ydot + layout_.offset(Species::Sink, Field::Velocity));
    std::fill_n(ydot + layout_.offset(Species::Sink, Field::Mass), ns, 0.0);
    std::fill_n(ydot + layout_.offset(Species::Sink, Field::Spin), 3 * ns, 0.0);
  }
}

template <int D, class K>
void SpmhdScheme<D, K>::change_particles(const std::vector<std::size_t>& kept, std::size_t sinks) {
  if (!opt_.evolve_particles) throw std::logic_error("SpmhdScheme::change_particles: fixed particles");
  if (sinks > 0 && !opt_.sink_particles) throw std::invalid_argument("SpmhdScheme::change_particles: no sink species");
  if (kept.empty()) throw std::invalid_argument("SpmhdScheme::change_particles: no gas left");
  const bool removal = std::is_sorted(kept.begin(), kept.end()) &&
                       std::adjacent_find(kept.begin(), kept.end()) == kept.end() && kept.back() < n_;
  if (removal && built_ && !halo_) return remove_particles(kept, sinks);
  // particle order: the last iterates of the h solves and div v (the next solve's start,
  // predict_smoothing_lengths) move with their particles
  const std::vector<Real> h_old = in_particle_order(h_eval_, 1, out_h_eval_), divv_old = div_v();
  std::vector<Real> th_old(n_, t_h_);  // and the times of those solves
  for (std::size_t s = 0; s < n_ && s < t_h_slot_.size(); ++s) th_old[perm_[s]] = t_h_slot_[s];
  std::vector<Real> h_new(kept.size()), m_new(kept.size()), divv_new(kept.size()), th_new(kept.size());
  for (std::size_t i = 0; i < kept.size(); ++i) {
    if (kept[i] >= n_) throw std::invalid_argument("SpmhdScheme::change_particles: particle out of range");
    h_new[i] = h_old[kept[i]];
    m_new[i] = m_[kept[i]];
    divv_new[i] = divv_old[kept[i]];
    th_new[i] = th_old[kept[i]];
  }
  const bool rate_known = h_rate_known_;
  n_ = kept.size();
  m_ = std::move(m_new);
  layout_ = layout_.with_count(Species::Gas, n_);
  if (opt_.sink_particles) layout_ = layout_.with_count(Species::Sink, sinks);
  h_ = std::move(h_new);  // slots = particles until the next list build sorts them
  x_.assign(D * n_, 0);
  allocate_per_particle();
  divv_ = std::move(divv_new);
  t_h_slot_ = std::move(th_new);
  h_rate_known_ = rate_known;
  built_ = false;
  ++version_;
  evaluated_version_ = -1;
  full_rhs_at_x_ = false;
}

// Particles removed (kept: ascending): the others keep their slots' order, their neighbour
// lists (less the removed; a removal brings no pair closer) and their last solves (h, rho,
// Omega, zeta, the solve times), so that a subset evaluation after an accretion need not build
// the lists or solve every density again. Their densities are due again (a neighbour may be gone).
template <int D, class K>
void SpmhdScheme<D, K>::remove_particles(const std::vector<std::size_t>& kept, std::size_t sinks) {
  interacting_rows_valid_ = false;
  constexpr std::uint32_t kGone = ~std::uint32_t{0};
  std::vector<std::uint32_t> number(n_, kGone);  // old particle -> new particle
  for (std::size_t i = 0; i < kept.size(); ++i) number[kept[i]] = static_cast<std::uint32_t>(i);
  std::vector<std::uint32_t> slots;  // the kept particles' slots, ascending
  for (std::size_t s = 0; s < n_; ++s)
    if (number[perm_[s]] != kGone) slots.push_back(static_cast<std::uint32_t>(s));
  ns_.keep(slots);
  const auto keep = [&](const auto& v, int comps) {
    std::remove_cvref_t<decltype(v)> out(comps * slots.size());
    if (v.size() == comps * n_)
      for (std::size_t i = 0; i < slots.size(); ++i)
        for (int k = 0; k < comps; ++k) out[comps * i + k] = v[comps * slots[i] + k];
    return out;
  };
  std::vector<Real> x = keep(x_, D), h = keep(h_, 1), h_eval = keep(h_eval_, 1), ms = keep(ms_, 1), rho = keep(rho_, 1),
                    omega = keep(omega_, 1), list_h = keep(list_h_, 1), radii = keep(radii_, 1), divv = keep(divv_, 1),
                    t_h = keep(t_h_slot_, 1), zeta = keep(zeta_over_omega_, 1);
  std::vector<std::uint32_t> perm = keep(perm_, 1);
  for (std::uint32_t& p : perm) p = number[p];
  std::vector<Real> m(kept.size());
  for (std::size_t i = 0; i < kept.size(); ++i) m[i] = m_[kept[i]];
  const bool rate_known = h_rate_known_, all_solved = every_slot_solved_;
  n_ = kept.size();
  m_ = std::move(m);
  layout_ = layout_.with_count(Species::Gas, n_);
  if (opt_.sink_particles) layout_ = layout_.with_count(Species::Sink, sinks);
  h_ = std::move(h);
  x_ = std::move(x);
  allocate_per_particle();
  h_eval_ = std::move(h_eval), ms_ = std::move(ms), rho_ = std::move(rho), omega_ = std::move(omega);
  list_h_ = std::move(list_h), radii_ = std::move(radii), divv_ = std::move(divv), t_h_slot_ = std::move(t_h);
  if (!zeta_over_omega_.empty()) zeta_over_omega_ = std::move(zeta);
  perm_ = std::move(perm);
  h_rate_known_ = rate_known;
  every_slot_solved_ = all_solved;
  ++version_;
  evaluated_version_ = -1;
  full_rhs_at_x_ = false;
}

#define SPHARK_SPMHD_SINKS(D, K)                                   \
  template void SpmhdScheme<D, K>::sink_pass(const Real*, Real*); \
  template void SpmhdScheme<D, K>::change_particles(const std::vector<std::size_t>&, std::size_t); \
  template void SpmhdScheme<D, K>::remove_particles(const std::vector<std::size_t>&, std::size_t);
#define SPHARK_SPMHD_SINKS_2D_3D(K) SPHARK_SPMHD_SINKS(2, K<2>) SPHARK_SPMHD_SINKS(3, K<3>)
SPHARK_KERNELS(SPHARK_SPMHD_SINKS_2D_3D)
#undef SPHARK_SPMHD_SINKS_2D_3D
#undef SPHARK_SPMHD_SINKS

}  // namespace sphark
