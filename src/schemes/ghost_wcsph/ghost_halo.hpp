#pragma once
// The halo of a distributed GhostWcsph (ghost_wcsph_distributed.cpp): the other ranks' real
// particles within reach of this rank's, their positions and velocities (every rank places their
// ghosts itself), and after the density solve their h, rho and Omega.
#include <cstdint>
#include <vector>

#include "sphark/boundaries/ghosts.hpp"
#include "sphark/parallel/halo.hpp"

namespace sphark::ghost_detail {

struct Halo {
  Halo(Communicator c, PeriodicBox<2> box) : comm(c), plan(std::move(c), box) {}
  Communicator comm;
  HaloPlan<2> plan;
  bool built = false;
  std::vector<std::int64_t> ids;           // this rank's particles
  std::size_t global = 0;                  // N: a ghost's key is N + its source's global id
  std::vector<Real> radius;                // the plan's radius of each local particle
  std::vector<Real> x, v;                  // the halo's real particles (plan order)
  std::vector<Real> local_density, density;  // h, rho, Omega: this rank's (sent), the halo's
  GhostLayer<2> ghosts;                    // the ghosts of the halo's particles
  std::vector<std::uint32_t> keys;         // every slot's row key
  std::vector<Real> ghost_h_of;            // after a migration: each particle's ghost's own h (NaN: none)
  std::vector<typename HaloPlan<2>::SplitField> fields;
};

}  // namespace sphark::ghost_detail
