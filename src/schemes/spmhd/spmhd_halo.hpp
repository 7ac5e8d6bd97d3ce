#pragma once
// The halo of a distributed SpmhdScheme (docs/scaling.md, "SPMHD"): the other ranks' particles
// within reach of this rank's. Halo particle k (the plan's order) is particle local() + k of the
// scheme's particle numbering; the arrays below hold the halo's values only (this rank's are read
// where they live: the state, the scheme's arrays). Two exchanges per RHS at most:
//   geometry  (positions, masses, the list radii a rebuild would use) when the positions moved,
//             before the neighbour lists and the density solve;
//   fields    (v, u, B, psi of the state, and after a solve h, rho, Omega) before the force pass:
//             the records of spmhd_pair_row.hpp are functions of these, computed by every rank
//             for its halo as the owner computes them for its own particles.
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
  std::size_t halo() const { return plan_.halo(); }
  std::size_t all() const { return ids_.size() + plan_.halo(); }
  // Global ids of local + halo (the neighbour rows' sort keys).
  const std::vector<std::uint32_t>& keys() const { return keys_; }

  // Collective. A new plan unless the current one still holds every pair for these positions
  // (the state's, particle order) and radii; true if it was rebuilt (the halo holds other
  // particles). The skin: `skin_fraction` of the mean radius over every rank.
  bool update_plan(const Real* x, const std::vector<Real>& radius, Real skin_fraction);

  // Collective: the halo's positions, masses and list radii (local values in particle order).
  void exchange_geometry(const Real* x, const Real* masses, const Real* radius);
  // Collective: the halo's state fields of y (this rank's, the scheme's layout) and, when
  // `density` (particle order, h, rho, Omega of each local particle) is given, theirs.
  void exchange_fields(const Real* y, const StateLayout& L, const std::vector<Real>* density);

  std::vector<Real> x, m, radius;                // exchange_geometry
  std::vector<Real> v, u, B, psi, density;       // exchange_fields (density: h, rho, Omega per particle)

 private:
  Communicator comm_;
  HaloPlan<D> plan_;
  bool built_ = false;
  std::vector<std::int64_t> ids_;
  std::vector<std::uint32_t> keys_;
  std::vector<typename HaloPlan<D>::SplitField> fields_;  // kept between exchanges
};

}  // namespace sphark::spmhd_detail
