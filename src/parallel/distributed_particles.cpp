#include "sphark/parallel/distributed_particles.hpp"

#include <stdexcept>

namespace sphark {

template <int D>
DistributedParticles<D>::DistributedParticles(Communicator comm, const Real* x, std::size_t particles,
                                              std::optional<PeriodicBox<D>> box)
    : comm_(std::move(comm)), box_(std::move(box)), domains_(box_), global_(particles) {
  own_domain_of(x);
}

// Every rank passes the positions of every particle to partition_rcb: the cuts are those of one
// copy (each bin's weight P times over); this rank keeps the particles of its domain.
template <int D>
void DistributedParticles<D>::own_domain_of(const Real* x) {
  domains_ = partition_rcb<D>(comm_, x, nullptr, global_, box_);
  std::vector<int> owner(global_);
  domains_.owners(x, global_, owner.data());
  ids_.clear();
  for (std::size_t a = 0; a < global_; ++a)
    if (owner[a] == comm_.rank()) ids_.push_back(static_cast<std::int64_t>(a));
}

template <int D>
const std::vector<std::int64_t>& DistributedParticles<D>::take_share(const Real* x) {
  own_domain_of(x);
  return ids_;
}

template <int D>
std::size_t DistributedParticles<D>::migrate(Payload& p, bool repartition) {
  if (!p.y || !p.masses) throw std::invalid_argument("DistributedParticles::migrate: a state and masses are required");
  const std::size_t n = ids_.size();
  std::size_t offset = 0;  // of the positions in the field-major state
  for (int f = 0; f < p.position_field; ++f) offset += n * static_cast<std::size_t>(p.components[f]);
  const Real* x = p.y->data() + offset;
  if (repartition) domains_ = partition_rcb<D>(comm_, x, nullptr, n, box_);
  std::vector<int> owner(n);
  domains_.owners(x, n, owner.data());
  ParticleData data;
  data.ids = &ids_;
  data.arrays.push_back({p.masses, 1});
  for (const ParticleData::Array& a : p.arrays) data.arrays.push_back(a);
  data.states.push_back({p.y, p.components});
  for (std::vector<Real>* s : p.aligned_states) data.states.push_back({s, p.components});
  data.mass.array = 0;
  data.velocity.state = 0;
  data.velocity.field = p.velocity_field;
  data.dim = D;
  return sphark::migrate(comm_, owner, data).sent;
}

template <int D>
std::size_t DistributedParticles<D>::migrate(Payload& p, bool repartition, std::vector<Real>& data, int per_particle,
                                             std::size_t tail) {
  const std::size_t n = ids_.size();
  if (data.size() != per_particle * n + tail)
    throw std::invalid_argument("DistributedParticles::migrate: the scheme's data does not fit the particles");
  const std::vector<Real> tail_values(data.end() - static_cast<std::ptrdiff_t>(tail), data.end());
  data.resize(per_particle * n);
  p.arrays.push_back({&data, per_particle});
  const std::size_t sent = migrate(p, repartition);
  p.arrays.pop_back();
  data.insert(data.end(), tail_values.begin(), tail_values.end());
  return sent;
}

template class DistributedParticles<2>;
template class DistributedParticles<3>;

}  // namespace sphark
