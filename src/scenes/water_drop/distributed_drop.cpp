#include "sphark/scenes/water_drop/distributed_drop.hpp"

#include <stdexcept>
#include <string>

#include "sphark/parallel/global_state.hpp"
#include "sphark/parallel/migration.hpp"

namespace sphark {

DistributedDrop::DistributedDrop(const WaterDropConfig& config, Communicator comm)
    : drop_(make_water_drop(config)), comm_(std::move(comm)), global_(drop_.particles()) {
  const StateLayout all = drop_.model->layout();
  own_domain_of(drop_.y0.data() + all.offset(Field::Position));
  y_ = share_of(all, drop_.y0, ids_);
  drop_.model->distribute(comm_, ids_);
}

// Every rank passes the positions of every particle to partition_rcb: the cuts are those of one
// copy (each bin's weight P times over); this rank keeps the particles of its domain.
void DistributedDrop::own_domain_of(const Real* x) {
  domains_ = partition_rcb<2>(comm_, x, nullptr, global_, std::nullopt);
  std::vector<int> owner(global_);
  domains_.owners(x, global_, owner.data());
  ids_.clear();
  for (std::size_t a = 0; a < global_; ++a)
    if (owner[a] == comm_.rank()) ids_.push_back(static_cast<std::int64_t>(a));
}

const std::vector<std::int64_t>& DistributedDrop::take_share(const std::vector<Real>& y_all) {
  const StateLayout all = drop_.model->layout().with_count(Species::Gas, global_);
  if (y_all.size() != all.size())  // (before the positions are read)
    throw std::invalid_argument("DistributedDrop::take_share: a state of " + std::to_string(y_all.size()) +
                                " values for " + std::to_string(global_) + " particles");
  own_domain_of(y_all.data() + all.offset(Field::Position));
  y_ = share_of(all, y_all, ids_);
  drop_.model->set_particles(ids_);
  return ids_;
}

std::size_t DistributedDrop::migrate(std::vector<Real>& y, std::vector<Real>* carried, bool repartition) {
  const StateLayout& L = drop_.model->layout();
  const std::size_t n = ids_.size();
  const Real* x = y.data() + L.offset(Field::Position);
  if (repartition) domains_ = partition_rcb<2>(comm_, x, nullptr, n, std::nullopt);
  std::vector<int> owner(n);
  domains_.owners(x, n, owner.data());
  const WaterDropConfig& c = drop_.config;
  std::vector<Real> mass(n, c.rho0 * c.spacing * c.spacing);
  ParticleData data;
  data.ids = &ids_;
  data.arrays = {{&mass, 1}};
  data.states = {{&y, field_components(L)}};
  if (carried) data.states.push_back({carried, field_components(L)});
  data.mass.array = 0;
  data.velocity.state = 0;
  data.velocity.field = 1;
  data.dim = 2;
  const std::size_t sent = sphark::migrate(comm_, owner, data).sent;
  drop_.model->set_particles(ids_);
  return sent;
}

std::size_t DistributedDrop::migrate(Stepper& stepper, bool repartition, Real atol) {
  std::vector<Real> carried = stepper.carried_data();
  const std::size_t sent = migrate(y_, carried.empty() ? nullptr : &carried, repartition);
  const std::vector<Real> tolerances = atol > 0 ? water_drop_absolute_tolerances(drop_, atol) : std::vector<Real>();
  stepper.resize({y_.data(), tolerances.empty() ? nullptr : tolerances.data(), carried.empty() ? nullptr : carried.data()});
  return sent;
}

// Sums of sums, the mean |div v| from each rank's sum, the largest density error.
WcsphDiagnostics<2> reduce_diagnostics(const Communicator& comm, const WcsphDiagnostics<2>& local, std::size_t n) {
  Real sums[8] = {local.kinetic_energy, local.internal_energy, local.potential_energy, local.psi_energy,
                  local.momentum.x(), local.momentum.y(), n > 0 ? local.mean_abs_div_v * static_cast<Real>(n) : 0,
                  static_cast<Real>(n)};
  comm.allreduce(sums, 8, ReduceOp::Sum);
  WcsphDiagnostics<2> d;
  d.kinetic_energy = sums[0];
  d.internal_energy = sums[1];
  d.potential_energy = sums[2];
  d.psi_energy = sums[3];
  d.momentum = Vec<2>(sums[4], sums[5]);
  d.mean_abs_div_v = sums[6] / sums[7];
  d.max_rel_density_error = comm.allreduce(local.max_rel_density_error, ReduceOp::Max);
  d.total_energy = d.kinetic_energy + d.internal_energy + d.potential_energy + d.psi_energy;
  return d;
}

}  // namespace sphark
