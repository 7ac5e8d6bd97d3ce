#include "sphark/schemes/spmhd/spmhd_migration.hpp"

#include <stdexcept>

#include "sphark/kernels/kernel_list.hpp"
#include "sphark/parallel/global_state.hpp"

namespace sphark {

template <int D, class K>
std::size_t migrate_spmhd(DistributedParticles<D>& parts, SpmhdScheme<D, K>& scheme, std::vector<Real>& y,
                          std::vector<Real>* carried, bool repartition) {
  if (parts.ids() != scheme.ids()) throw std::logic_error("migrate_spmhd: the scheme holds other particles");
  std::vector<Real> solve_state = scheme.migration_data();  // per particle, then two values alike on every rank
  std::vector<Real> masses = scheme.masses();
  typename DistributedParticles<D>::Payload p;
  p.y = &y;
  p.components = field_components(scheme.layout());
  p.masses = &masses;
  if (carried) p.aligned_states = {carried};
  const std::size_t sent = parts.migrate(p, repartition, solve_state, SpmhdScheme<D, K>::kMigrationValues, 2);
  scheme.set_particles(parts.ids(), std::move(masses));
  scheme.restore_migrated(solve_state);
  return sent;
}

#define SPHARK_SPMHD_MIGRATION(K)                                                                                   \
  template std::size_t migrate_spmhd(DistributedParticles<2>&, SpmhdScheme<2, K<2>>&, std::vector<Real>&,           \
                                     std::vector<Real>*, bool);                                                     \
  template std::size_t migrate_spmhd(DistributedParticles<3>&, SpmhdScheme<3, K<3>>&, std::vector<Real>&,           \
                                     std::vector<Real>*, bool);
SPHARK_KERNELS(SPHARK_SPMHD_MIGRATION)
#undef SPHARK_SPMHD_MIGRATION

}  // namespace sphark
