#include "sphark/scenes/water_drop/distributed_drop.hpp"

#include "sphark/parallel/migration.hpp"

namespace sphark {

namespace {
// The entries of the particles `ids` of a field-major state of every particle.
std::vector<Real> select(const std::vector<Real>& y, const StateLayout& all, const std::vector<std::int64_t>& ids) {
  std::vector<Real> out;
  for (const Field f : all.fields()) {
    const std::size_t c = static_cast<std::size_t>(all.components(f));
    for (const std::int64_t id : ids)
      for (std::size_t k = 0; k < c; ++k) out.push_back(y[all.offset(f) + c * static_cast<std::size_t>(id) + k]);
  }
  return out;
}

std::vector<int> field_components(const StateLayout& L) {
  std::vector<int> c;
  for (const Field f : L.fields()) c.push_back(L.components(f));
  return c;
}
}  // namespace

// Every rank passes the whole drop to partition_rcb: the cuts are those of one copy (each
// bin's weight P times over).
DistributedDrop::DistributedDrop(const WaterDropConfig& config, Communicator comm)
    : drop_(make_water_drop(config)), comm_(std::move(comm)), global_(drop_.particles()) {
  const StateLayout all = drop_.model->layout();
  const Real* x = drop_.y0.data() + all.offset(Field::Position);
  domains_ = partition_rcb<2>(comm_, x, nullptr, global_, std::nullopt);
  std::vector<int> owner(global_);
  domains_.owners(x, global_, owner.data());
  for (std::size_t a = 0; a < global_; ++a)
    if (owner[a] == comm_.rank()) ids_.push_back(static_cast<std::int64_t>(a));
  y_ = select(drop_.y0, all, ids_);
  drop_.model->distribute(comm_, ids_);
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
