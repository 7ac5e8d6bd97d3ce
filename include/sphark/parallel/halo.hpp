#pragma once
// Halo exchange: the copies of other ranks' particles that a rank's pair loops need.
//
// build() decides, once per neighbour-list build, which local particles every other rank needs,
// and exchanges their global ids; exchange() then copies any per-particle array (positions,
// velocities, and after a density / h solve rho, h, Omega, P, B, psi, ...) from the owners into
// the halo part of the receivers' arrays, through persistent index lists and buffers (nothing is
// allocated by an exchange once the buffers have grown to the plan's size).
//
// Which particles: b goes to rank p if some periodic image of b lies closer than
// max(r_b, r_max(p)) + skin to the bounding box of p's particles, r_max(p) being the largest
// radius on p. So the local + halo particles of a rank hold every b with |x_a - x_b| <
// max(r_a, r_b) (minimum image) of each of its particles a (variable h), and still do while
// 2 * (largest displacement) + (largest radius growth) <= skin (still_valid()). The test
// compares with a relative margin of 1e-10, so that rounding in the wrapped coordinates cannot
// lose a pair; a few more particles than needed may come along.
//
// Periodic boxes: halo particles carry their owner's coordinates (unshifted), each at most once
// per receiver, and the receiver finds pairs by the minimum image, as the serial NeighbourSearch
// and pair loops do; each periodic length must be at least 2 (r_max + skin) so that the minimum
// image is the only one within range. A rank never sends to itself (its own periodic images are
// minimum images of its own particles).
//
// Layout: arrays hold local() values first, then halo() halo values, by source rank and in the
// sender's order (deterministic). With neighbour rows sorted by global id (NeighbourSearch's
// key), every pair sum then runs over the same terms in the same order on any number of ranks.
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/neighbours/periodic_box.hpp"
#include "sphark/parallel/communicator.hpp"

namespace sphark {

struct HaloStats {
  int send_partners = 0, receive_partners = 0;
  std::size_t sent = 0, received = 0;  // particles per exchange (this rank)
  long builds = 0, exchanges = 0;
};

// The global ids of a scheme's particles, which its neighbour rows use as 32-bit sort keys:
// std::invalid_argument "<who>: global id ... outside [0, 2^32)" unless each fits.
void check_key_ids(const std::vector<std::int64_t>& ids, const char* who);

template <int D>
class HaloPlan {
 public:
  explicit HaloPlan(Communicator comm = {}, std::optional<PeriodicBox<D>> box = std::nullopt);

  // Collective. x: D values per local particle; radius: the interaction radius of each
  // (e.g. kernel support x h); ids: global ids. Throws CollectiveError on every rank if a
  // periodic length is below 2 (r_max + skin).
  void build(const Real* x, const Real* radius, const std::int64_t* ids, std::size_t n, Real skin = 0);

  std::size_t local() const { return local_; }
  std::size_t halo() const { return halo_ids_.size(); }
  const std::vector<std::int64_t>& halo_ids() const { return halo_ids_; }
  const Communicator& communicator() const { return comm_; }

  // Collective: fills field[(local() + k) * components + c], k < halo(), from the owners'
  // field[i * components + c]. field holds (local() + halo()) * components values.
  void exchange(Real* field, int components);
  struct Field {
    Real* data;
    int components;
  };
  // Collective: several arrays in one message per partner.
  void exchange(std::initializer_list<Field> fields) { exchange(std::span<const Field>(fields.begin(), fields.size())); }
  void exchange(std::span<const Field> fields);
  // The same with the local values and the halo's apart: local[i * components + c] (i < local())
  // are sent, halo[k * components + c] (k < halo()) received.
  struct SplitField {
    const Real* local;
    Real* halo;
    int components;
  };
  void exchange(std::span<const SplitField> fields);

  // Collective: true on every rank if the plan built with `skin` still holds every pair for
  // these positions and radii (2 max displacement + max radius growth <= skin on every rank).
  bool still_valid(const Real* x, const Real* radius) const;

  const HaloStats& stats() const { return stats_; }

 private:
  void exchange_bytes(std::size_t width);  // posts sends_ / receives_ already filled

  Communicator comm_;
  std::optional<PeriodicBox<D>> box_;
  std::size_t local_ = 0;
  Real skin_ = 0;
  std::vector<int> send_ranks_, receive_ranks_;
  std::vector<std::size_t> send_start_, receive_start_;  // per partner, into send_index_ / the halo
  std::vector<std::uint32_t> send_index_;                  // local particles to send, by partner
  std::vector<std::int64_t> halo_ids_;
  std::vector<Real> send_buffer_, receive_buffer_, x_built_, r_built_;
  std::vector<Communicator::Send> sends_;
  std::vector<Communicator::Receive> receives_;
  std::vector<SplitField> split_;  // exchange(Field): kept (no allocation once grown)
  HaloStats stats_;
};

}  // namespace sphark
