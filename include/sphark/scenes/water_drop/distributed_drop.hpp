#pragma once
// The water drop on the ranks of a communicator (docs/scaling.md): every rank builds the whole
// drop, keeps the particles of its RCB domain, and its WcsphSystem exchanges the halo inside
// every RHS (WcsphSystem::distribute). Between advance() calls, migrate() moves every particle
// to the owner of its position, with its state (and the leapfrog's carried kick), and hands the
// stepper the new state (Stepper::resize).
#include <cstdint>
#include <vector>

#include "sphark/integrate/stepper.hpp"
#include "sphark/diagnostics/wcsph_diagnostics.hpp"
#include "sphark/parallel/distributed_particles.hpp"
#include "sphark/scenes/water_drop/water_drop.hpp"

namespace sphark {

class DistributedDrop {
 public:
  // Collective. The drop of `config`, this rank's share by RCB of the initial positions.
  DistributedDrop(const WaterDropConfig& config, Communicator comm);

  // drop().model holds this rank's particles; drop().y0 is the whole drop's initial state.
  WaterDrop& drop() { return drop_; }
  WcsphModel& model() { return *drop_.model; }
  const std::vector<std::int64_t>& ids() const { return parts_.ids(); }
  std::vector<Real>& state() { return y_; }  // this rank's particles' (field-major, model().layout())
  std::size_t global_particles() const { return parts_.global_particles(); }
  const Communicator& communicator() const { return parts_.communicator(); }

  // Collective. Every particle to the owner of its position in y (this rank's state; the domains
  // recomputed first when `repartition`), with y and `carried` (if not null: entries aligned
  // with y, e.g. the leapfrog's carried kick); migrate() checks count, ids, mass and momentum.
  // The model then holds this rank's new particles. Returns the particles this rank sent.
  std::size_t migrate(std::vector<Real>& y, std::vector<Real>* carried, bool repartition);
  // Collective. A restart: the whole drop's field-major state (every particle, by global id, as
  // a checkpoint holds it) partitioned anew; this rank keeps the particles of its domain (state()
  // their values, the model holds them). Returns their ids.
  const std::vector<std::int64_t>& take_share(const std::vector<Real>& y_all);
  // The same for state(), and the stepper continues from this rank's new state; atol > 0: a run
  // with per-entry tolerances (water_drop_absolute_tolerances of atol).
  std::size_t migrate(Stepper& stepper, bool repartition, Real atol = 0);

 private:
  WaterDrop drop_;
  DistributedParticles<2> parts_;  // RCB domains, the ids, migration
  std::vector<Real> y_;
};

// Collective: the diagnostics of the whole drop from each rank's of its n particles.
WcsphDiagnostics<2> reduce_diagnostics(const Communicator& comm, const WcsphDiagnostics<2>& local, std::size_t n);

}  // namespace sphark
