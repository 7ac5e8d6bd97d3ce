#pragma once
// Migration of a distributed SpmhdScheme's particles (docs/scaling.md, "SPMHD"): the state, the
// masses and what each particle's density solve reached (SpmhdScheme::migration_data: the last
// iterate, h, rho, Omega, div v and the positions they were solved at) move with their
// particles, so that the run goes on as the serial one: no solve where the serial run skips it,
// the next from the same start.
#include <vector>

#include "sphark/parallel/distributed_particles.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"

namespace sphark {

// Collective, between steps: every particle of `scheme` (distributed over parts' ranks) to the
// owner of its position in y (this rank's state, the scheme's layout), with `carried` (entries
// aligned with y, e.g. the leapfrog's derivative; may be null); the domains recomputed first when
// `repartition`. The scheme then holds this rank's new particles. Returns the particles sent.
template <int D, class K>
std::size_t migrate_spmhd(DistributedParticles<D>& parts, SpmhdScheme<D, K>& scheme, std::vector<Real>& y,
                          std::vector<Real>* carried, bool repartition);

}  // namespace sphark
