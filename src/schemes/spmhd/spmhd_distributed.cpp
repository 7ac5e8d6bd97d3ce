// The distributed parts of SpmhdScheme (docs/scaling.md, "SPMHD"): the steps of the serial
// prepare() (spmhd_scheme.cpp, spmhd_density.cpp) over this rank's particles and a halo of the
// others', with every decision that steers a collective step taken by all ranks together:
//   1. positions moved on some rank (one Allreduce; else only the halo's state is exchanged);
//   2. the halo plan, checked against the list radii a rebuild would use (HaloPlan::still_valid);
//   3. one exchange of the state fields, masses and those radii;
//   4. the Verlet lists rebuilt when any rank needs it (the serial rule with the largest
//      displacement and the smallest slack of every rank: one Allreduce), over local + halo,
//      rows for the local particles only, sorted by global id;
//   5. the density / h solve of the local particles; failures and h beyond the lists agreed
//      (another attempt on every rank, as the serial solve retries);
//   6. h, rho and Omega of the halo from their owners.
// The per-particle records of the pair loop are then computed for local and halo slots alike
// (their inputs are equal to the owners'), and the force loop runs over the local rows.
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "sphark/core/profile.hpp"
#include "sphark/integrate/callback_errors.hpp"
#include "sphark/kernels/kernel_list.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"
#include "spmhd_halo.hpp"

namespace sphark {

template <int D, class K>
void SpmhdScheme<D, K>::distribute(Communicator comm, const std::vector<std::int64_t>& ids) {
  if (opt_.field != FieldRepresentation::MagneticField || opt_.self_gravity || opt_.sink_particles)
    throw std::invalid_argument(
        "SpmhdScheme::distribute: the magnetic field only (no Euler potentials, self-gravity or sinks distributed yet)");
  if (opt_.ch_spread > 0)  // (a halo particle's spread c_h would need the halo's own neighbours)
    throw std::invalid_argument("SpmhdScheme::distribute: ch_spread is not distributed yet");
  if (!opt_.evolve_particles) all_fixed_x_ = positions();  // every particle's, particle order
  std::vector<Real> masses(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] < 0 || static_cast<std::size_t>(ids[i]) >= m_.size())
      throw std::invalid_argument("SpmhdScheme::distribute: global id " + std::to_string(ids[i]) + " is not a particle");
    masses[i] = m_[static_cast<std::size_t>(ids[i])];
  }
  halo_ = std::make_unique<spmhd_detail::Halo<D>>(std::move(comm), ns_.box());
  set_particles(ids, std::move(masses));
}

template <int D, class K>
void SpmhdScheme<D, K>::set_particles(std::vector<std::int64_t> ids, std::vector<Real> masses) {
  if (!halo_) throw std::logic_error("SpmhdScheme::set_particles: the scheme is not distributed");
  if (masses.size() != ids.size()) throw std::invalid_argument("SpmhdScheme::set_particles: one mass per particle");
  halo_->set_particles(std::move(ids));
  n_ = halo_->local();
  m_ = std::move(masses);
  layout_ = layout_.with_count(Species::Gas, n_);
  h_.assign(n_, opt_.h_initial > 0 ? opt_.h_initial : 0);  // resume() sets the migrated starts
  h_unset_ = !(opt_.h_initial > 0);
  solved_ = false;
  x_.assign(D * n_, 0);
  if (!opt_.evolve_particles) {  // fixed particles: theirs (slots = particles until the first list build)
    fixed_x_.resize(D * n_);
    for (std::size_t a = 0; a < n_; ++a)
      for (int k = 0; k < D; ++k) fixed_x_[D * a + k] = all_fixed_x_[D * static_cast<std::size_t>(halo_->ids()[a]) + k];
    x_ = fixed_x_;
  }
  allocate_per_particle();
  key_.assign(halo_->ids().begin(), halo_->ids().end());
  built_ = false;
  ++version_;
  evaluated_version_ = -1;
  full_rhs_at_x_ = false;
}

template <int D, class K>
std::vector<Real> SpmhdScheme<D, K>::migration_data() const {
  constexpr int W = kMigrationValues;
  std::vector<Real> out(W * n_ + 2);
  for (std::size_t s = 0; s < n_; ++s) {
    Real* p = out.data() + W * perm_[s];
    p[0] = h_eval_[s], p[1] = h_[s], p[2] = rho_[s], p[3] = omega_[s], p[4] = divv_[s];
    for (int k = 0; k < D; ++k) p[5 + k] = x_[D * s + k];
  }
  out[W * n_] = t_h_;
  out[W * n_ + 1] = (solved_ ? 1 : 0) + (h_rate_known_ ? 2 : 0);
  return out;
}

template <int D, class K>
void SpmhdScheme<D, K>::restore_migrated(std::span<const Real> data) {
  constexpr int W = kMigrationValues;
  if (data.size() != W * n_ + 2) throw std::invalid_argument("SpmhdScheme::restore_migrated: data of other particles");
  for (std::size_t a = 0; a < n_; ++a) {  // slots = particles until the next list build
    const Real* p = data.data() + W * a;
    h_eval_[a] = p[0], h_[a] = p[1], rho_[a] = p[2], omega_[a] = p[3], divv_[a] = p[4];
    for (int k = 0; k < D; ++k) x_[D * a + k] = p[5 + k];
  }
  set_h_time(data[W * n_]);
  const int flags = static_cast<int>(data[W * n_ + 1]);
  solved_ = (flags & 1) != 0;
  h_rate_known_ = (flags & 2) != 0;
  h_unset_ = false;
  built_ = false;
  ++version_;
  evaluated_version_ = -1;
  full_rhs_at_x_ = false;
}

template <int D, class K>
const std::vector<std::int64_t>& SpmhdScheme<D, K>::ids() const {
  static const std::vector<std::int64_t> none;
  return halo_ ? halo_->ids() : none;
}

template <int D, class K>
const Communicator& SpmhdScheme<D, K>::communicator() const {
  static const Communicator serial;
  return halo_ ? halo_->comm() : serial;
}

template <int D, class K>
const Real* SpmhdScheme<D, K>::particle_positions(const Real* y) const {
  return opt_.evolve_particles ? y + layout_.offset(Field::Position) : fixed_x_.data();
}

template <int D, class K>
const std::uint32_t* SpmhdScheme<D, K>::slot_keys() const {
  return halo_ ? key_.data() : perm_.data();
}

// A new halo of all - n_ particles: their slots n_ .. all - 1 in the plan's order until the next
// list build sorts them; every array a neighbour reads gets their entries.
template <int D, class K>
void SpmhdScheme<D, K>::resize_slots(std::size_t all) {
  n_all_ = all;
  perm_.resize(all);
  key_.resize(all);
  for (std::size_t s = n_; s < all; ++s) perm_[s] = static_cast<std::uint32_t>(s);
  for (std::size_t s = 0; s < all; ++s) key_[s] = halo_->keys()[perm_[s]];
  for (std::vector<Real>* v : {&h_, &ms_, &radii_, &rho_, &omega_, &P_, &sound_speed_, &fast_speed_,
                               &cleaning_speeds_, &inv_omega_rho2_})
    v->resize(all);
  x_.resize(D * all);
  v_.resize(D * all);
  B_.resize(3 * all);
  if (layout_.has(Field::InternalEnergy)) u_.resize(all);
  if (layout_.has(Field::Psi)) psi_.resize(all);
}

// Steps 1-6 of the file's comment. Every rank returns the same code.
template <int D, class K>
int SpmhdScheme<D, K>::distributed_prepare_positions(Real t, const Real* y) {
  spmhd_detail::Halo<D>& halo = *halo_;
  const Real* xs = particle_positions(y);
  for (std::size_t s = 0; s < n_; ++s)
    for (int k = 0; k < D; ++k) x_from_state_[D * s + k] = xs[D * perm_[s] + k];
  // the serial memo: the solve is skipped while the positions are those it was made for
  const bool moved_here = !solved_ || !std::equal(x_from_state_.begin(), x_from_state_.end(), x_.begin());
  std::int64_t flags[3] = {moved_here ? 1 : 0, h_unset_ ? 1 : 0, built_ ? 0 : 1};
  halo.comm().allreduce(flags, 3, ReduceOp::Max);
  std::string message;
  if (flags[0] == 0 && flags[2] == 0) return 0;  // the halo's positions are unchanged too
  halo_density_stale_ = true;  // (every rank alike) exchange_halo_fields sends h, rho, Omega
  if (flags[0] == 0) {  // migrated particles, solved where they are: the halo and lists only
    const int code = distributed_density_attempt(t, y, -1, message);
    if (code != 0) error_ = message;
    return code;
  }
  std::copy(x_from_state_.begin(), x_from_state_.end(), x_.begin());
  if (flags[1] != 0) first_smoothing_lengths(xs, h_unset_);
  predict_smoothing_lengths(t);
  h_guess_.assign(h_.begin(), h_.begin() + n_);  // every attempt starts from the same guesses
  int code = 2;
  for (int attempt = 0; attempt < 8 && code == 2; ++attempt) code = distributed_density_attempt(t, y, attempt, message);
  if (code == 2) {
    code = 1;
    message = "density: smoothing lengths keep growing beyond the neighbour lists";
  }
  if (code != 0) {
    built_ = solved_ = false;  // x_ is not what the lists and h were made for
    error_ = message;
    return code;
  }
  set_h_time(t);
  solved_ = true;
  return 0;
}

// Steps 2-5, one attempt: 0 (solved), 1 (failed: message), or 2 (some h beyond its list: again).
// attempt -1: the halo and the lists for the h already solved (after a migration), no solve.
template <int D, class K>
int SpmhdScheme<D, K>::distributed_density_attempt(Real t, const Real* y, int attempt, std::string& message) {
  (void)t;
  spmhd_detail::Halo<D>& halo = *halo_;
  const bool solve = attempt >= 0;
  if (attempt > 0) std::copy(h_guess_.begin(), h_guess_.end(), h_.begin());
  new_radius_.resize(n_);
  plan_radius_.resize(n_);
  const Real r_cap = half_period();
  for (std::size_t s = 0; s < n_; ++s) {  // as build_neighbours() computes them (with skin_own_fraction 1: no shorter)
    const Real r = std::min(K::support * std::max(h_[s], list_h_needed_[s]) * (1 + opt_.skin), r_cap);
    new_radius_[perm_[s]] = r;
    plan_radius_[perm_[s]] = built_ ? std::max(r, radii_[s]) : r;  // the lists in use, or a rebuild's
  }
  std::optional<ScopedPhase> timer(std::in_place, Phase::Halo);
  const Real* xs = particle_positions(y);
  const bool new_plan = halo.update_plan(xs, plan_radius_, opt_.skin / (1 + opt_.skin));
  if (new_plan) resize_slots(halo.all());
  halo.exchange_geometry(xs, m_.data(), new_radius_.data());
  for (std::size_t s = n_; s < n_all_; ++s) {
    const std::size_t k = perm_[s] - n_;  // halo particle k
    for (int c = 0; c < D; ++c) x_[D * s + c] = halo.x[D * k + c];
    ms_[s] = halo.m[k];
  }
  // the serial rule (ensure_neighbours_and_density): rebuild when some h_i > (R_i - 2 disp) /
  // support, disp the largest displacement of any particle; here with a 1e-9 margin, so that
  // the rule rearranged never keeps a list the serial form would find short
  Real v[3] = {0, -std::numeric_limits<Real>::infinity(), (!built_ || new_plan || attempt > 0) ? Real(1) : Real(0)};
  if (built_ && !new_plan && n_all_ > 0) v[0] = ns_.max_displacement_since_build(x_.data());
  for (std::size_t s = 0; s < n_; ++s) v[1] = std::max(v[1], K::support * h_[s] - radii_[s]);  // -slack
  halo.comm().allreduce(v, 3, ReduceOp::Max);
  timer.reset();
  const Real disp = v[0];
  const bool rebuild = v[2] > 0 || 2 * disp >= -v[1] * (1 - 1e-9);
  int code = 0;
  DensityStats st;
  try {
    if (rebuild) {
      ScopedPhase lists(Phase::Neighbours);
      code = build_neighbours(x_.data());
      for (std::size_t i = 0; i < n_; ++i) list_h_served_[i] = radii_[i] / K::support;
    } else {
      for (std::size_t i = 0; i < n_; ++i) list_h_served_[i] = (radii_[i] - 2 * disp) / K::support;
    }
    if (code == 0 && solve) {
      ScopedPhase density(Phase::DensityH);
      list_growth_ = list_growth_for_attempt(attempt);
      st = solve_density(x_.data());
    }
    if (code != 0) message = error_;
  } catch (...) {
    code = -1;
    message = current_exception_message("SpmhdScheme::rhs");
  }
  timer.emplace(Phase::Halo);
  if ((code = halo.comm().agree(code, message)) != 0) return 1;
  std::int64_t counts[2] = {static_cast<std::int64_t>(st.outside_list), static_cast<std::int64_t>(st.not_converged)};
  halo.comm().allreduce(counts, 2, ReduceOp::Sum);
  if (counts[0] > 0) return 2;
  if (counts[1] == 0) return 0;
  message = "density: h iteration did not converge for " + std::to_string(counts[1]) + " particle(s)";
  return 1;  // recoverable: a smaller step moves the particles less
}

// Before a force pass (rhs): the halo's state fields, and h, rho, Omega when a solve or a
// migration came since the last exchange; then what their records need besides (as prepare()
// computes it for this rank's particles: the same inputs give the owner's values).
template <int D, class K>
void SpmhdScheme<D, K>::exchange_halo_fields(const Real* y) {
  spmhd_detail::Halo<D>& halo = *halo_;
  {
    ScopedPhase timer(Phase::Halo);
    if (halo_density_stale_) {
      local_density_.resize(3 * n_);
      for (std::size_t s = 0; s < n_; ++s) {
        Real* d = local_density_.data() + 3 * perm_[s];
        d[0] = h_[s], d[1] = rho_[s], d[2] = omega_[s];
      }
    }
    halo.exchange_fields(y, layout_, halo_density_stale_ ? &local_density_ : nullptr);
  }
  const bool energy = layout_.has(Field::InternalEnergy), cleaning = layout_.has(Field::Psi);
  for (std::size_t s = n_; s < n_all_; ++s) {
    const std::size_t k = perm_[s] - n_;  // halo particle k
    for (int c = 0; c < D && opt_.evolve_particles; ++c) v_[D * s + c] = halo.v[D * k + c];
    for (int c = 0; c < 3; ++c) B_[3 * s + c] = halo.B[3 * k + c];
    if (energy) u_[s] = halo.u[k];
    if (cleaning) psi_[s] = halo.psi[k];
    if (halo_density_stale_) h_[s] = halo.density[3 * k], rho_[s] = halo.density[3 * k + 1], omega_[s] = halo.density[3 * k + 2];
  }
  halo_density_stale_ = false;
  equation_of_state(n_, n_all_);
  set_cleaning_speeds(n_, n_all_);
}

#define SPHARK_SPMHD_DISTRIBUTED(D, K)                                                                 \
  template void SpmhdScheme<D, K>::distribute(Communicator, const std::vector<std::int64_t>&);        \
  template void SpmhdScheme<D, K>::set_particles(std::vector<std::int64_t>, std::vector<Real>);       \
  template const std::vector<std::int64_t>& SpmhdScheme<D, K>::ids() const;                           \
  template const Communicator& SpmhdScheme<D, K>::communicator() const;                               \
  template const std::uint32_t* SpmhdScheme<D, K>::slot_keys() const;                                 \
  template const Real* SpmhdScheme<D, K>::particle_positions(const Real*) const;                      \
  template void SpmhdScheme<D, K>::resize_slots(std::size_t);                                          \
  template int SpmhdScheme<D, K>::distributed_prepare_positions(Real, const Real*);                   \
  template int SpmhdScheme<D, K>::distributed_density_attempt(Real, const Real*, int, std::string&);  \
  template void SpmhdScheme<D, K>::exchange_halo_fields(const Real*);                                  \
  template std::vector<Real> SpmhdScheme<D, K>::migration_data() const;                               \
  template void SpmhdScheme<D, K>::restore_migrated(std::span<const Real>);
#define SPHARK_SPMHD_DISTRIBUTED_2D_3D(K) SPHARK_SPMHD_DISTRIBUTED(2, K<2>) SPHARK_SPMHD_DISTRIBUTED(3, K<3>)
SPHARK_KERNELS(SPHARK_SPMHD_DISTRIBUTED_2D_3D)
#undef SPHARK_SPMHD_DISTRIBUTED_2D_3D
#undef SPHARK_SPMHD_DISTRIBUTED

}  // namespace sphark
