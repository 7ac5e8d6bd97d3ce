#pragma once
// The halo of a distributed WcsphSystem (docs/scaling.md, "The API a scheme uses"): the other
// ranks' particles within the kernel support (+ skin) of this rank's, with the state fields the
// pair loops read. The state of the water drop's scheme is x, v, rho [, psi] (continuity
// equation (28): no density solve), and every record field (wcsph_pair_rows.hpp: x, rho,
// V = m/rho, v, P/rho^2, psi/rho^2, c) is a function of it: one exchange of the state per RHS.
// Antuono's renormalised density gradient <grad rho>^L is a sum over neighbours itself: the
// force loop reads it of its neighbours, so it is exchanged once more after the gradient loop.
//
// Arrays hold the local particles first, then the halo (HaloPlan's order); the neighbour rows
// are sorted by global id (keys()), so every row sums the same terms in the same order as the
// serial run of the same global ids: the distributed run reproduces it bit for bit.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sphark/parallel/halo.hpp"
#include "sphark/state/state_layout.hpp"

namespace sphark::wcsph_detail {

// The state fields of particles in particle order, D, D, 1 and 1 values each (psi null without
// cleaning): views of y serially, of local + halo arrays when distributed.
template <int D>
struct ParticleFields {
  const Real *x, *v, *rho, *psi;
};

template <int D>
ParticleFields<D> state_fields(const Real* y, const StateLayout& L) {
  return {y + L.offset(Field::Position), y + L.offset(Field::Velocity), y + L.offset(Field::Density),
          L.has(Field::Psi) ? y + L.offset(Field::Psi) : nullptr};
}

template <int D>
class Halo {
 public:
  Halo(Communicator comm, std::optional<PeriodicBox<D>> box);

  // This rank's particles (global ids < 2^32, the neighbour rows' keys): a new plan at the next
  // gather().
  void set_particles(std::vector<std::int64_t> ids);
  const std::vector<std::int64_t>& ids() const { return ids_; }

  // Collective. The plan (rebuilt unless still valid for these positions, support radius and
  // skin), then the state fields of the halo particles. True if the plan was rebuilt: the halo
  // holds other particles (neighbour lists over it must be rebuilt).
  bool gather(const Real* y, const StateLayout& L, Real support, Real skin);
  ParticleFields<D> fields() const;
  std::size_t local() const { return ids_.size(); }
  std::size_t all() const { return ids_.size() + plan_.halo(); }
  const std::uint32_t* keys() const { return keys_.data(); }

  // Collective: the halo entries of `values` (components per particle, local + halo) from
  // their owners.
  void exchange(std::vector<Real>& values, int components);
  // Collective: the most severe code of any rank, the failing ranks' messages in `message`.
  int agree(int code, std::string& message) const { return comm_.agree(code, message); }
  // Collective: each of values[0 .. n) the maximum over the ranks.
  void max_over_ranks(Real* values, std::size_t n) const { comm_.allreduce(values, n, ReduceOp::Max); }
  // Collective: true if `b` is true on every rank.
  bool on_every_rank(bool b) const { return comm_.allreduce(std::int64_t(b ? 1 : 0), ReduceOp::Min) == 1; }

  const HaloPlan<D>& plan() const { return plan_; }

 private:
  void build_plan(const Real* x, Real skin);

  Communicator comm_;
  HaloPlan<D> plan_;
  bool built_ = false, psi_field_ = false;
  std::vector<std::int64_t> ids_;
  std::vector<std::uint32_t> keys_;            // global ids of local + halo
  std::vector<Real> radius_;                   // the support of every local particle
  std::vector<Real> x_, v_, rho_, psi_;        // local + halo
};

}  // namespace sphark::wcsph_detail
