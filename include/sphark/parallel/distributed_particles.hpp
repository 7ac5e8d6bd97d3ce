#pragma once
// A scene's particles spread over the ranks of a communicator (docs/scaling.md): every rank
// built the whole scene (particle k = global id k); each keeps the particles of its RCB domain of
// the positions, and between steps migrate() moves every particle to the owner of its current
// position with all its data (the state, the masses, any per-particle arrays such as a scheme's
// resume data, the leapfrog's carried derivative), migrate()'s checks included (count, ids,
// mass, momentum). Scene-independent: the water drop and Orszag-Tang use it.
#include <cstdint>
#include <optional>
#include <vector>

#include "sphark/parallel/decomposition.hpp"
#include "sphark/parallel/migration.hpp"

namespace sphark {

template <int D>
class DistributedParticles {
 public:
  // Collective. x: the positions of every particle (D each, global id order); box: periodic
  // domains wrap.
  DistributedParticles(Communicator comm, const Real* x, std::size_t particles,
                       std::optional<PeriodicBox<D>> box = std::nullopt);

  const std::vector<std::int64_t>& ids() const { return ids_; }
  std::size_t global_particles() const { return global_; }
  const Communicator& communicator() const { return comm_; }

  // This rank's particles set by hand (tests: e.g. every particle on one rank); the next
  // migrate() moves them to the owners of the current domains.
  void assign(std::vector<std::int64_t> ids) { ids_ = std::move(ids); }
  // Collective: a restart's share, the positions x of every particle partitioned anew.
  const std::vector<std::int64_t>& take_share(const Real* x);

  // What moves with a particle besides its id: the field-major state y (its field components;
  // field `velocity_field` is the velocity, checked with the masses), the masses (one per
  // particle), more per-particle arrays, and more flat states aligned with y (e.g. carried data).
  struct Payload {
    std::vector<Real>* y = nullptr;
    std::vector<int> components;
    int position_field = 0, velocity_field = 1;
    std::vector<Real>* masses = nullptr;
    std::vector<ParticleData::Array> arrays;
    std::vector<std::vector<Real>*> aligned_states;
  };
  // Collective: every particle to the owner of its position in *p.y (the domains recomputed
  // first when `repartition`). ids() then holds this rank's new particles. Returns the
  // particles this rank sent.
  std::size_t migrate(Payload& p, bool repartition);
  // The same with a scheme's data (`data`: `per_particle` values per particle, particle-major,
  // then `tail` values alike on every rank), which then holds the new particles' (and the tail).
  std::size_t migrate(Payload& p, bool repartition, std::vector<Real>& data, int per_particle, std::size_t tail);

 private:
  void own_domain_of(const Real* x);  // every particle's positions: domains_ and ids_

  Communicator comm_;
  std::optional<PeriodicBox<D>> box_;
  Decomposition<D> domains_;
  std::vector<std::int64_t> ids_;
  std::size_t global_ = 0;
};

}  // namespace sphark
