#include "sphark/schemes/ghost_wcsph/ghost_migration.hpp"

#include <stdexcept>

#include "sphark/kernels/kernel_list.hpp"
#include "sphark/parallel/global_state.hpp"

namespace sphark {

template <class K>
std::size_t migrate_ghost_wcsph(DistributedParticles<2>& parts, GhostWcsph<K>& scheme, std::vector<Real>& y,
                                std::vector<Real>* carried, bool repartition) {
  if (parts.ids() != scheme.ids()) throw std::logic_error("migrate_ghost_wcsph: the scheme holds other particles");
  std::vector<Real> solve_state = scheme.migration_data();  // per particle, then one value alike on every rank
  std::vector<Real> masses(scheme.particles(), scheme.scheme_params().mass);  // (all equal)
  DistributedParticles<2>::Payload p;
  p.y = &y;
  p.components = field_components(scheme.layout());
  p.masses = &masses;
  if (carried) p.aligned_states = {carried};
  const std::size_t sent = parts.migrate(p, repartition, solve_state, GhostWcsph<K>::kMigrationValues, 1);
  scheme.set_particles(parts.ids());
  scheme.restore_migrated(solve_state);
  return sent;
}

#define SPHARK_GHOST_MIGRATION(K)                                                                       \
  template std::size_t migrate_ghost_wcsph(DistributedParticles<2>&, GhostWcsph<K<2>>&, std::vector<Real>&, \
                                           std::vector<Real>*, bool);
SPHARK_KERNELS(SPHARK_GHOST_MIGRATION)
#undef SPHARK_GHOST_MIGRATION

}  // namespace sphark
