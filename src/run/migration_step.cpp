#include "sphark/run/migration_step.hpp"

namespace sphark {

std::optional<TimeLoopHooks::Resize> migration_step(MigrationSchedule& schedule, const Communicator& world,
                                                    const StateLayout& layout, const Real* y,
                                                    const TimeLoopHooks::CarriedData& carried,
                                                    const MigrateParticles& migrate,
                                                    const std::function<std::vector<Real>()>& atol) {
  const long steps = ++schedule.steps;
  if (steps % schedule.every != 0) return std::nullopt;
  std::vector<Real> state(y, y + layout.size()), kick = carried();
  const bool with_kick = world.allreduce(std::int64_t(kick.empty() ? 0 : 1), ReduceOp::Max) == 1;
  const StateLayout after = migrate(state, with_kick ? &kick : nullptr, steps % schedule.repartition_every == 0);
  TimeLoopHooks::Resize r{after, std::move(state), atol ? atol() : std::vector<Real>(), {}, std::nullopt};
  if (with_kick) r.carried = std::move(kick);
  return r;
}

}  // namespace sphark
