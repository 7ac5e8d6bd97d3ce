#pragma once
// Migration of a distributed GhostWcsph's particles (docs/scaling.md, "The lattice"): the state
// and what each particle's density solve reached (GhostWcsph::migration_data) move with the
// particles, so that the run goes on as the serial one.
#include <vector>

#include "sphark/parallel/distributed_particles.hpp"
#include "sphark/schemes/ghost_wcsph/ghost_wcsph.hpp"

namespace sphark {

// Collective, between steps: every particle of `scheme` to the owner of its position in y (this
// rank's state), with `carried` (aligned with y; may be null); the domains recomputed first when
// `repartition`. Returns the particles this rank sent.
template <class K>
std::size_t migrate_ghost_wcsph(DistributedParticles<2>& parts, GhostWcsph<K>& scheme, std::vector<Real>& y,
                                std::vector<Real>* carried, bool repartition);

}  // namespace sphark
