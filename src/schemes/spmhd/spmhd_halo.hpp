#pragma once
// The halo of a distributed SpmhdScheme (docs/scaling.md, "SPMHD"): the other ranks' particles
// within reach of this rank's, in particle order (this rank's particles 0 .. local() - 1 as the
// state holds them, then the halo in the plan's order). Per RHS: the state fields the pair
// loops read (x, v, u, B, psi), the masses and the list radii a rebuild would use, in one
// exchange; after the density solve h, rho and Omega (the records of spmhd_pair_row.hpp are
// functions of these, computed by every rank for its halo as the owner does for its own).
#include <cstdint>
#include <optional>
#include <vector>

#include "sphark/parallel/halo.hpp"
#include "sphark/state/state_layout.hpp"

namespace sphark::spmhd_detail {

template <int D>
class Halo {
 public:
  Halo(Communicator comm, std::optional<PeriodicBox<D>> box) : comm_(comm), plan_(std::move(comm), std::move(box)) {}

  const Communicator& comm() const { return comm_; }
  void set_particles(std::vector<std::int64_t> ids);
  const std::vector<std::int64_t>& ids() const { return ids_; }
  std::size_t local() const { return ids_.size(); }
  std::size_t all() const { return ids_.size() + plan_.halo(); }
  // Global ids of local + halo (the neighbour rows' sort keys).
  const std::vector<std::uint32_t>& keys() const { return keys_; }

  // Collective. A new plan unless the current one still holds every pair for these positions
  // (the state's, particle order) and radii; true if it was rebuilt (the halo holds other
  // particles). The skin: `skin_fraction` of the mean radius over every rank.
  bool update_plan(const Real* x, const std::vector<Real>& radius, Real skin_fraction);

  // Collective: the state fields of y (this rank's, particle order), the masses and the list
  // radii `radius` of the local particles into local + halo arrays.
  void exchange_state(const Real* y, const StateLayout& L, const std::vector<Real>& masses,
                      const std::vector<Real>& radius);
  // Collective: h, rho, Omega (local entries filled by the caller) of the halo.
  void exchange_density() { plan_.exchange({{h.data(), 1}, {rho.data(), 1}, {omega.data(), 1}}); }

  // The particle-order values of a state field (local + halo), or nullptr if not exchanged.
  const Real* field(Field f) const;

  std::vector<Real> x, v, u, B, psi, m, radius;  // exchange_state
  std::vector<Real> h, rho, omega;               // exchange_density (sized all())

 private:
  Communicator comm_;
  HaloPlan<D> plan_;
  bool built_ = false;
  std::vector<std::int64_t> ids_;
  std::vector<std::uint32_t> keys_;
};

}  // namespace sphark::spmhd_detail
