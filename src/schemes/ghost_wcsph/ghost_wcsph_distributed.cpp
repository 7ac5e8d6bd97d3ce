// The distributed parts of GhostWcsph (docs/scaling.md, "The lattice"): the serial prepare()
// (ghost_wcsph.cpp) over this rank's particles, its ghosts and a halo, every decision that steers
// a collective step taken from every rank's values:
//   1. the layer's width and the list radius from the largest h of all particles (Allreduce);
//   2. this rank's ghosts (seed 004 §2), a halo plan reaching the list radius plus twice the
//      layer (a halo particle's ghost lies within twice the layer of it), one exchange of the
//      halo's positions and velocities, and their ghosts placed here (the same arithmetic on the
//      same values as their owner's);
//   3. lists over this rank's particles and ghosts, the halo's and their ghosts, rows for this
//      rank's own, keyed so that every row runs in the serial order (a particle: its global id;
//      a ghost: N + its source's: serially the ghosts follow the particles in source order);
//   4. the density / h solve (seed 004 eq. (1)), its retries with a larger list radius and the
//      width's on every rank together (sums and maxima of the outcomes);
//   5. h, rho and Omega of the halo from their owners; every ghost takes its source's.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>

#include "ghost_halo.hpp"
#include "sphark/kernels/kernel_list.hpp"
#include "sphark/operators/density_summation.hpp"
#include "sphark/schemes/ghost_wcsph/ghost_wcsph.hpp"

namespace sphark {

namespace {
constexpr int kMaxRetries = 4;
constexpr Real kPlanSkin = 0.1;  // of the plan's radius
}  // namespace

template <class K>
void GhostWcsph<K>::distribute(Communicator comm, const std::vector<std::int64_t>& ids) {
  for (const std::int64_t id : ids)
    if (id < 0 || static_cast<std::size_t>(id) >= n_)
      throw std::invalid_argument("GhostWcsph::distribute: global id " + std::to_string(id) + " is not a particle");
  if (2 * n_ >= std::size_t(1) << 32) throw std::invalid_argument("GhostWcsph::distribute: too many particles for 32-bit keys");
  halo_ = std::make_unique<ghost_detail::Halo>(std::move(comm), box_);
  halo_->global = n_;
  set_particles(ids);
}

template <class K>
void GhostWcsph<K>::set_particles(std::vector<std::int64_t> ids) {
  if (!halo_) throw std::logic_error("GhostWcsph::set_particles: the scheme is not distributed");
  check_key_ids(ids, "GhostWcsph");
  halo_->ids = std::move(ids);
  halo_->built = false;
  n_ = halo_->ids.size();
  layout_ = layout_.with_count(Species::Gas, n_);
  h_.assign(n_, p_.eta * std::sqrt(p_.mass / p_.rho0));  // restore_migrated() sets the solved ones
  rho_.assign(n_, p_.rho0);
  omega_.assign(n_, 1);
  x_prepared_.assign(2 * n_, 0);
  ghost_h_.assign(n_, 0);
  ghosts_.reserve(n_);
  prepared_ = relink_ = false;
  evaluated_y_.clear();
}

template <class K>
const std::vector<std::int64_t>& GhostWcsph<K>::ids() const {
  static const std::vector<std::int64_t> none;
  return halo_ ? halo_->ids : none;
}

template <class K>
const Communicator& GhostWcsph<K>::communicator() const {
  static const Communicator serial;
  return halo_ ? halo_->comm : serial;
}

template <class K>
std::vector<Real> GhostWcsph<K>::migration_data() const {
  constexpr int W = kMigrationValues;
  std::vector<Real> out(W * n_ + 1, std::numeric_limits<Real>::quiet_NaN());
  for (std::size_t a = 0; a < n_; ++a) {
    Real* p = out.data() + W * a;
    p[0] = h_[a], p[1] = rho_[a], p[2] = omega_[a];
    p[4] = x_prepared_[2 * a], p[5] = x_prepared_[2 * a + 1];
  }
  for (std::size_t k = 0; k < ghosts_.size(); ++k) out[W * ghosts_.sources()[k] + 3] = ghost_h_[k];
  out[W * n_] = prepared_ ? 1 : 0;
  return out;
}

template <class K>
void GhostWcsph<K>::restore_migrated(std::span<const Real> data) {
  constexpr int W = kMigrationValues;
  if (data.size() != W * n_ + 1) throw std::invalid_argument("GhostWcsph::restore_migrated: data of other particles");
  halo_->ghost_h_of.resize(n_);
  for (std::size_t a = 0; a < n_; ++a) {
    const Real* p = data.data() + W * a;
    h_[a] = p[0], rho_[a] = p[1], omega_[a] = p[2], halo_->ghost_h_of[a] = p[3];
    x_prepared_[2 * a] = p[4], x_prepared_[2 * a + 1] = p[5];
  }
  relink_ = data[W * n_] != 0;  // solved where they are: the next evaluation there rebuilds the halo only
  prepared_ = false;
  evaluated_y_.clear();
}

// The serial memo (positions unchanged: nothing to do) decided for every rank together; after a
// migration at unchanged positions the halo and the lists are rebuilt without a solve.
template <class K>
int GhostWcsph<K>::prepare_if_moved_distributed(const Real* y) {
  const Real* x = y + layout_.offset(Field::Position);
  const bool known = prepared_ || relink_;
  const bool moved = !known || (n_ > 0 && std::memcmp(x, x_prepared_.data(), 2 * n_ * sizeof(Real)) != 0);
  std::int64_t flags[2] = {moved ? 1 : 0, prepared_ ? 0 : 1};
  halo_->comm.allreduce(flags, 2, ReduceOp::Max);
  if (flags[0] != 0) return distributed_prepare(y, true);
  if (flags[1] != 0) return distributed_prepare(y, false);
  return 0;
}

// Step 2: ghosts, the halo (plan, positions and velocities, their ghosts), the slots and lists.
template <class K>
void GhostWcsph<K>::link_halo(const Real* x, const Real* v, Real width, Real r_build) {
  ghost_detail::Halo& halo = *halo_;
  const GhostOptions opt{width, p_.map, p_.velocity, OnInvalid::Skip};
  ghosts_.clear();
  ghosts_.append(wall_, x, v, n_, opt, &box_);
  const Real reach = r_build + 2 * width;  // a particle within it may have a ghost within r_build
  halo.radius.assign(n_, reach);
  if (!halo.built || !halo.plan.still_valid(x, halo.radius.data())) {
    halo.plan.build(x, halo.radius.data(), halo.ids.data(), n_, kPlanSkin * reach);
    halo.built = true;
  }
  const std::size_t H = halo.plan.halo();
  halo.x.resize(2 * H);
  halo.v.resize(2 * H);
  halo.fields = {{x, halo.x.data(), 2}, {v, halo.v.data(), 2}};
  halo.plan.exchange(std::span<const typename HaloPlan<2>::SplitField>(halo.fields));
  halo.ghosts.clear();
  halo.ghosts.append(wall_, halo.x.data(), halo.v.data(), H, opt, &box_);
  const std::size_t g = ghosts_.size(), gh = halo.ghosts.size(), total = n_ + g + H + gh;
  halo_ghost_begin_ = n_ + g + H;
  for (std::vector<Real>* a : {&xall_, &vall_}) a->resize(2 * total);
  mass_.assign(total, p_.mass);
  for (std::vector<Real>* a : {&rho_, &h_, &omega_, &pressure_, &q_}) a->resize(total);
  auto put = [&](std::size_t at, const Real* from, std::size_t count, std::vector<Real>& to) {
    std::copy(from, from + 2 * count, to.begin() + 2 * static_cast<std::ptrdiff_t>(at));
  };
  put(0, x, n_, xall_), put(0, v, n_, vall_);
  put(n_, ghosts_.positions(), g, xall_), put(n_, ghosts_.velocities(), g, vall_);
  put(n_ + g, halo.x.data(), H, xall_), put(n_ + g, halo.v.data(), H, vall_);
  put(halo_ghost_begin_, halo.ghosts.positions(), gh, xall_), put(halo_ghost_begin_, halo.ghosts.velocities(), gh, vall_);
  const std::uint32_t N = static_cast<std::uint32_t>(halo.global);
  const std::vector<std::int64_t>& hid = halo.plan.halo_ids();
  halo.keys.resize(total);
  for (std::size_t a = 0; a < n_; ++a) halo.keys[a] = static_cast<std::uint32_t>(halo.ids[a]);
  for (std::size_t k = 0; k < g; ++k) halo.keys[n_ + k] = N + static_cast<std::uint32_t>(halo.ids[ghosts_.sources()[k]]);
  for (std::size_t k = 0; k < H; ++k) halo.keys[n_ + g + k] = static_cast<std::uint32_t>(hid[k]);
  for (std::size_t k = 0; k < gh; ++k)
    halo.keys[halo_ghost_begin_ + k] = N + static_cast<std::uint32_t>(hid[halo.ghosts.sources()[k]]);
  search_.build(xall_.data(), total, r_build, halo.keys.data(), nullptr, n_ + g);
}

// Steps 3-4: the serial solve_densities() with the halo; every rank returns the same code.
template <class K>
int GhostWcsph<K>::distributed_solve(const Real* x, const Real* v, Real width, std::string& message) {
  const Communicator& comm = halo_->comm;
  Real h_guess = 0;
  for (std::size_t i = 0; i < n_; ++i) h_guess = std::max(h_guess, h_[i]);
  h_guess = comm.allreduce(h_guess, ReduceOp::Max);
  Real half = kInfinity;  // half the shortest periodic length
  for (int k = 0; k < 2; ++k)
    if (box_.periodic[k]) half = std::min(half, 0.5 * (box_.hi[k] - box_.lo[k]));
  const Real r_cap = 0.999 * half;
  Real r_build = std::min(1.1 * K::support * h_guess, r_cap);
  for (int attempt = 0; attempt < kMaxRetries; ++attempt) {
    link_halo(x, v, width, r_build);
    const std::size_t g = ghosts_.size();
    if (attempt == 0)  // first guess (a retry starts from the last attempt's, as serially)
      for (std::size_t k = 0; k < g; ++k) h_[n_ + k] = h_[ghosts_.sources()[k]];
    const DensitySolveStats st = solve_density<2, K>(search_, xall_.data(), mass_.data(), n_ + g, p_.eta, p_.h_tol,
                                                     r_build / K::support, h_.data(), rho_.data(), omega_.data(), n_,
                                                     h_given_ ? n_ : 0);
    std::int64_t counts[2] = {static_cast<std::int64_t>(st.not_converged), static_cast<std::int64_t>(st.outside_list)};
    comm.allreduce(counts, 2, ReduceOp::Sum);
    const Real h_max = comm.allreduce(st.h_max, ReduceOp::Max);
    if (counts[0] > 0) {
      message = "h-rho solve did not converge for " + std::to_string(counts[0]) + " particle(s)";
      return 1;
    }
    if (counts[1] == 0) {
      h_given_ = false;
      r_build_ = r_build;
      return 0;
    }
    if (r_build >= r_cap) {
      message = "support radius 2h exceeds half the box (h = " + std::to_string(h_max) + ")";
      return 1;
    }
    r_build = std::min(1.1 * K::support * h_max, r_cap);
  }
  message = "h-rho solve: neighbour radius did not settle";
  return 1;
}

// The serial prepare()'s loop over the layer's width (solve), or the halo and lists for the h a
// migration brought (no solve: width and list radius those of the last solve).
template <class K>
int GhostWcsph<K>::distributed_prepare(const Real* y, bool solve) {
  const Real* x = y + layout_.offset(Field::Position);
  const Real* v = y + layout_.offset(Field::Velocity);
  if (!solve) {
    link_halo(x, v, width_used_, r_build_);
    for (std::size_t k = 0; k < ghosts_.size(); ++k)
      ghost_h_[k] = relink_ ? halo_->ghost_h_of[ghosts_.sources()[k]] : ghost_h_[k];
    finish_distributed_prepare(x);
    return 0;
  }
  std::string message;
  for (int attempt = 0; attempt < kMaxRetries; ++attempt) {
    const Real width = p_.map == GhostMap::Mirror ? std::min(width_, mirror_limit_) : width_;
    if (distributed_solve(x, v, width, message) != 0) {
      error_ = message;
      prepared_ = relink_ = false;
      return 1;
    }
    Real h_max = 0;
    for (std::size_t i = 0; i < n_; ++i) h_max = std::max(h_max, h_[i]);
    h_max = halo_->comm.allreduce(h_max, ReduceOp::Max);
    const bool covered = K::support * h_max <= width_ || width < width_;
    width_ = 1.15 * K::support * h_max;  // ghost layer as thick as the largest real support
    if (!covered) continue;
    width_used_ = width;
    std::copy(h_.begin() + static_cast<std::ptrdiff_t>(n_), h_.begin() + static_cast<std::ptrdiff_t>(n_ + ghosts_.size()),
              ghost_h_.begin());
    finish_distributed_prepare(x);
    return 0;
  }
  error_ = "ghost layer width did not settle";
  prepared_ = relink_ = false;
  return 1;
}

// Step 5, and the pressures (seed 000, eq. (26)) of every slot.
template <class K>
void GhostWcsph<K>::finish_distributed_prepare(const Real* x) {
  ghost_detail::Halo& halo = *halo_;
  const std::size_t g = ghosts_.size(), H = halo.plan.halo(), total = halo_ghost_begin_ + halo.ghosts.size();
  ghosts_.gather_scalar(rho_.data(), rho_.data() + n_);  // sources are this rank's particles
  ghosts_.gather_scalar(h_.data(), h_.data() + n_);
  ghosts_.gather_scalar(omega_.data(), omega_.data() + n_);
  halo.local_density.resize(3 * n_);
  for (std::size_t a = 0; a < n_; ++a)
    halo.local_density[3 * a] = h_[a], halo.local_density[3 * a + 1] = rho_[a], halo.local_density[3 * a + 2] = omega_[a];
  halo.density.resize(3 * H);
  halo.fields = {{halo.local_density.data(), halo.density.data(), 3}};
  halo.plan.exchange(std::span<const typename HaloPlan<2>::SplitField>(halo.fields));
  const std::size_t h0 = n_ + g;
  for (std::size_t k = 0; k < H; ++k)
    h_[h0 + k] = halo.density[3 * k], rho_[h0 + k] = halo.density[3 * k + 1], omega_[h0 + k] = halo.density[3 * k + 2];
  halo.ghosts.gather_scalar(rho_.data() + h0, rho_.data() + halo_ghost_begin_);  // sources: the halo's particles
  halo.ghosts.gather_scalar(h_.data() + h0, h_.data() + halo_ghost_begin_);
  halo.ghosts.gather_scalar(omega_.data() + h0, omega_.data() + halo_ghost_begin_);
  Real h_min = kInfinity;
  for (std::size_t a = 0; a < n_; ++a) h_min = std::min(h_min, h_[a]);
  h_min_ = halo.comm.allreduce(h_min, ReduceOp::Min);
  pressures(total);
  std::copy(x, x + 2 * n_, x_prepared_.begin());
  prepared_ = true;
  relink_ = false;
}

#define SPHARK_GHOST_WCSPH_DISTRIBUTED(K)                                                                   \
  template void GhostWcsph<K<2>>::distribute(Communicator, const std::vector<std::int64_t>&);               \
  template void GhostWcsph<K<2>>::set_particles(std::vector<std::int64_t>);                                 \
  template const std::vector<std::int64_t>& GhostWcsph<K<2>>::ids() const;                                  \
  template const Communicator& GhostWcsph<K<2>>::communicator() const;                                      \
  template std::vector<Real> GhostWcsph<K<2>>::migration_data() const;                                      \
  template void GhostWcsph<K<2>>::restore_migrated(std::span<const Real>);                                  \
  template int GhostWcsph<K<2>>::prepare_if_moved_distributed(const Real*);                                 \
  template void GhostWcsph<K<2>>::link_halo(const Real*, const Real*, Real, Real);                          \
  template int GhostWcsph<K<2>>::distributed_solve(const Real*, const Real*, Real, std::string&);           \
  template int GhostWcsph<K<2>>::distributed_prepare(const Real*, bool);                                    \
  template void GhostWcsph<K<2>>::finish_distributed_prepare(const Real*);
SPHARK_KERNELS(SPHARK_GHOST_WCSPH_DISTRIBUTED)
#undef SPHARK_GHOST_WCSPH_DISTRIBUTED

}  // namespace sphark
