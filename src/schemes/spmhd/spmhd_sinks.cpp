// Sink particles in the SPMHD state (3D): the species Species::Sink (position, velocity, mass,
// spin) after the gas fields. Their gravity on the gas and the gas's on them, and between sinks
// (Bate, Bonnell & Price 1995; gravity/point_mass_gravity.hpp: equal and opposite pair forces,
// momentum conserved); dx/dt = v, dv/dt = a, the mass and spin change only between steps
// (sinks/sink_events.hpp: creation, accretion). The potential energy gains the sink-gas and
// sink-sink pair energies, and each gas particle's potential the sinks' (the creation checks
// read it).
#include <algorithm>
#include <stdexcept>

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
}

#define SPHARK_SPMHD_SINKS(D, K)                                   \
  template void SpmhdScheme<D, K>::sink_pass(const Real*, Real*); \
  template void SpmhdScheme<D, K>::change_particles(const std::vector<std::size_t>&, std::size_t);
#define SPHARK_SPMHD_SINKS_2D_3D(K) SPHARK_SPMHD_SINKS(2, K<2>) SPHARK_SPMHD_SINKS(3, K<3>)
SPHARK_KERNELS(SPHARK_SPMHD_SINKS_2D_3D)
#undef SPHARK_SPMHD_SINKS_2D_3D
#undef SPHARK_SPMHD_SINKS

}  // namespace sphark
