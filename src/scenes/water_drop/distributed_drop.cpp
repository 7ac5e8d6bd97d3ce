#include "sphark/scenes/water_drop/distributed_drop.hpp"

#include <stdexcept>
#include <string>

#include "sphark/parallel/global_state.hpp"

namespace sphark {

DistributedDrop::DistributedDrop(const WaterDropConfig& config, Communicator comm)
    : drop_(make_water_drop(config)),
      parts_(std::move(comm), drop_.y0.data() + drop_.model->layout().offset(Field::Position), drop_.particles()) {
  y_ = share_of(drop_.model->layout(), drop_.y0, ids());
  drop_.model->distribute(communicator(), ids());
}

const std::vector<std::int64_t>& DistributedDrop::take_share(const std::vector<Real>& y_all) {
  const StateLayout all = drop_.model->layout().with_count(Species::Gas, global_particles());
  if (y_all.size() != all.size())  // (before the positions are read)
    throw std::invalid_argument("DistributedDrop::take_share: a state of " + std::to_string(y_all.size()) +
                                " values for " + std::to_string(global_particles()) + " particles");
  parts_.take_share(y_all.data() + all.offset(Field::Position));
  y_ = share_of(all, y_all, ids());
  drop_.model->set_particles(ids());
  return ids();
}

std::size_t DistributedDrop::migrate(std::vector<Real>& y, std::vector<Real>* carried, bool repartition) {
  const WaterDropConfig& c = drop_.config;
  std::vector<Real> mass(ids().size(), c.rho0 * c.spacing * c.spacing);
  DistributedParticles<2>::Payload p;
  p.y = &y;
  p.components = field_components(drop_.model->layout());
  p.masses = &mass;
  if (carried) p.aligned_states = {carried};
  const std::size_t sent = parts_.migrate(p, repartition);
  drop_.model->set_particles(ids());
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
