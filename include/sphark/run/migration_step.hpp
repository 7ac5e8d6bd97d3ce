#pragma once
// The migration schedule of a distributed scene (docs/scaling.md): after every step the scene's
// after_step counts the steps, and every `every` of them moves each particle to the owner of
// its position (the domains recomputed every `repartition_every`), with the stepper's carried
// data (the leapfrog's derivative; every rank the same choice, also one left without particles).
#include <functional>
#include <optional>
#include <vector>

#include "sphark/parallel/communicator.hpp"
#include "sphark/run/time_loop.hpp"

namespace sphark {

struct MigrationSchedule {
  long every = 20, repartition_every = 100;
  long steps = 0;  // since t = 0 (a restart: the checkpoint's)
};

// migrate(state, carried or null, repartition) moves the particles of `state` (this rank's, the
// layout's before the move) and returns the layout after it; atol: the per-entry tolerances of
// the new state, when the run uses them (called after the move).
using MigrateParticles = std::function<StateLayout(std::vector<Real>& state, std::vector<Real>* carried, bool repartition)>;

// Collective. The resize that continues the loop after a migration, or nothing between them.
std::optional<TimeLoopHooks::Resize> migration_step(MigrationSchedule& schedule, const Communicator& world,
                                                    const StateLayout& layout, const Real* y,
                                                    const TimeLoopHooks::CarriedData& carried,
                                                    const MigrateParticles& migrate,
                                                    const std::function<std::vector<Real>()>& atol = {});

}  // namespace sphark
