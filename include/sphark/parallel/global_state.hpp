#pragma once
// The whole state of a distributed run, as a serial run holds it: field-major (StateLayout: for
// each field in order, every particle's components), particle k = global id k. Checkpoints of
// distributed runs are written in this form (one file, rank 0) and read back on any number of
// ranks, each taking its share (docs/scaling.md, "Checkpoints of distributed runs").
#include <cstdint>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/parallel/communicator.hpp"
#include "sphark/state/state_layout.hpp"

namespace sphark {

// The components per particle of each field of a one-species layout, in state order.
std::vector<int> field_components(const StateLayout& layout);

// The state of the particles `ids` (in that order) out of `all`, the state of every particle
// laid out by `whole` (particle k = id k): resize_species on the first species.
// std::invalid_argument for an id outside the layout or a state that does not fit it.
std::vector<Real> share_of(const StateLayout& whole, const std::vector<Real>& all, const std::vector<std::int64_t>& ids);

// Collective: each rank's field-major values of its particles `ids` (local.size() = ids.size()
// x the components) become, on rank 0, the field-major values of every particle in global id
// order (empty on the other ranks). The particles travel by migrate() (count and ids checked);
// std::runtime_error on rank 0 unless the ids are 0 .. N-1, each once.
std::vector<Real> gather_particles(const Communicator& comm, const std::vector<std::int64_t>& ids,
                                   const std::vector<Real>& local, const std::vector<int>& components);

}  // namespace sphark
