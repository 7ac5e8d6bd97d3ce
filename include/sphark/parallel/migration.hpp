#pragma once
// Migration: every particle moves to the rank that owns it (e.g. Decomposition::owner of its
// position), with all its per-particle data: the 64-bit global id and any number of SoA arrays
// (components values per particle, particle-major) and of field-major flat states (the StateLayout
// vector: for each field in order, all particles' components). On every rank the particles it
// keeps come first, in their old order, then those received, by source rank and in the
// sender's order: the result depends only on the data, not on timing.
//
// After the move the global count, total mass and momentum are compared with those before
// (Allreduce); a mismatch throws CollectiveError on every rank. The count and an
// order-independent checksum of the ids are exact; mass and momentum are compared to the bound
// of the rounding error of their summation, (n + P) eps sum |m v| (the sums are taken in a
// different order after the move).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/parallel/communicator.hpp"

namespace sphark {

struct ParticleData {
  // SoA arrays: array.size() == components * particles.
  struct Array {
    std::vector<Real>* values;
    int components;
  };
  // Field-major flat state: for each field f in order, particles * components[f] values.
  struct FlatState {
    std::vector<Real>* values;
    std::vector<int> components;
  };
  std::vector<std::int64_t>* ids = nullptr;  // one per particle (required)
  std::vector<Array> arrays;
  std::vector<FlatState> states;
  // Conservation check (optional): mass = one value per particle, and the velocity (dim
  // components), each given as (index into arrays or states, component offset within it).
  struct Ref {
    int array = -1;           // index into `arrays`, or -1
    int state = -1;           // index into `states` (with `field`), or -1
    int field = 0;            // field of that state
  };
  Ref mass, velocity;
  int dim = 0;                // components of the velocity
};

struct ConservedTotals {
  std::int64_t count = 0;
  std::uint64_t id_sum = 0, id_hash = 0;  // sum of ids and of a mix of each id (mod 2^64)
  Real mass = 0, abs_mass = 0;
  Real momentum[3] = {0, 0, 0}, abs_momentum[3] = {0, 0, 0};
};

struct MigrationStats {
  std::size_t sent = 0, received = 0;  // particles, this rank
  std::size_t bytes_sent = 0;
  int partners = 0;                    // ranks this rank sent to
};

// Collective: the global totals of `data` (n = ids->size() particles on this rank).
ConservedTotals conserved_totals(const Communicator& comm, const ParticleData& data);

// Collective: moves particle i to rank destination[i] (destination.size() == particles). Throws
// CollectiveError on every rank if the data is inconsistent on any rank (array sizes) or the
// totals after the move differ from those before.
MigrationStats migrate(const Communicator& comm, const std::vector<int>& destination, ParticleData& data);

}  // namespace sphark
