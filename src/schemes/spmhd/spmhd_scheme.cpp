#include "sphark/schemes/spmhd/spmhd_scheme.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>

#include "sphark/core/profile.hpp"
#include "sphark/integrate/callback_errors.hpp"
#include "sphark/kernels/kernel_list.hpp"
#include "sphark/operators/conjugate_cleaning.hpp"
#include "sphark/operators/density_summation.hpp"
#include "sphark/operators/pair_geometry.hpp"
#include "spmhd_halo.hpp"

namespace sphark {

void enable_self_gravity(SpmhdOptions& o, GravitySolver solver, Real theta, GravityOpening opening) {
  o.self_gravity = true;
  o.gravity_solver = solver;
  o.gravity_theta = theta;
  o.gravity_opening = opening;
}

void enable_kernel_softened_sinks(SpmhdOptions& o, Real accretion_radius) {
  o.sink_particles = true;
  o.sink_softening = {PointMassSoftening::Kernel, accretion_radius / CubicSpline<3>::support};
}

Cleaning parse_cleaning(std::string_view s) {
  if (s == "none") return Cleaning::None;
  if (s == "constrained") return Cleaning::Constrained;
  if (s == "nonconservative") return Cleaning::NonConservative;
  throw std::invalid_argument("unknown cleaning form: " + std::string(s));
}

std::string_view cleaning_name(Cleaning c) {
  switch (c) {
    case Cleaning::None: return "none";
    case Cleaning::Constrained: return "constrained";
    case Cleaning::NonConservative: return "nonconservative";
  }
  return "unknown";
}

SubsetDensity parse_subset_density(std::string_view s) {
  if (s == "solved") return SubsetDensity::Solved;
  if (s == "predicted") return SubsetDensity::Predicted;
  throw std::invalid_argument("unknown subset density: " + std::string(s));
}

std::string_view subset_density_name(SubsetDensity d) {
  return d == SubsetDensity::Solved ? "solved" : "predicted";
}

template <int D, class K>
SpmhdScheme<D, K>::SpmhdScheme(std::vector<Real> masses, SpmhdOptions opt, std::optional<PeriodicBox<D>> box,
                               std::vector<Real> fixed_positions)
    : n_(masses.size()), m_(std::move(masses)), opt_(opt), layout_(n_), ns_(std::move(box)) {
  if (n_ == 0) throw std::invalid_argument("SpmhdScheme: no particles");
  if (!(opt_.gamma > 1)) throw std::invalid_argument("SpmhdScheme: gamma must be > 1");
  if (opt_.barotropic) {
    eos_.emplace(*opt_.barotropic);
    opt_.alpha_u = 0;  // no internal energy to conduct
  }
  if (!(opt_.eta > 0)) throw std::invalid_argument("SpmhdScheme: eta must be > 0");
  if (opt_.sigma < 0) throw std::invalid_argument("SpmhdScheme: sigma must be >= 0");
  if (!(opt_.overclean >= 1)) throw std::invalid_argument("SpmhdScheme: overclean must be >= 1");
  if (opt_.ch_spread < 0 || opt_.ch_spread > 16) throw std::invalid_argument("SpmhdScheme: ch_spread must be in [0, 16]");
  if (opt_.ch_spread > 0 && !opt_.local_ch)
    throw std::invalid_argument("SpmhdScheme: ch_spread spreads each particle's own c_h: it needs local_ch");
  if (!(opt_.cleaning_courant >= 0 && std::isfinite(opt_.cleaning_courant)))
    throw std::invalid_argument("SpmhdScheme: cleaning_courant must be finite and >= 0 (0: the Courant number)");
  if (opt_.evolve_particles) {
    layout_.add(Field::Position, D).add(Field::Velocity, D);
    if (!opt_.barotropic) layout_.add(Field::InternalEnergy, 1);
    if (opt_.field == FieldRepresentation::MagneticField) {
      layout_.add(Field::MagneticField, 3);
    } else {
      if (D != 2) throw std::invalid_argument("SpmhdScheme: Euler potentials are implemented for D = 2 (beta = z)");
      if (opt_.cleaning != Cleaning::None) throw std::invalid_argument("SpmhdScheme: Euler potentials need no cleaning");
      layout_.add(Field::EulerAlpha, 1);
    }
    x_.assign(D * n_, 0);
  } else {
    if (opt_.field != FieldRepresentation::MagneticField)
      throw std::invalid_argument("SpmhdScheme: the fixed-particle subsystem evolves B");
    if (fixed_positions.size() != D * n_) throw std::invalid_argument("SpmhdScheme: fixed positions must be D x N");
    layout_.add(Field::MagneticField, 3);
    x_ = std::move(fixed_positions);
  }
  if (opt_.cleaning != Cleaning::None) layout_.add(Field::Psi, 1);

  if (opt_.sink_particles) {  // a second species: sink particles (none yet), after every gas field
    if (D != 3 || !opt_.self_gravity) throw std::invalid_argument("SpmhdScheme: sink particles need D = 3 and self-gravity");
    layout_.add_species(Species::Sink, 0).add(Field::Position, 3).add(Field::Velocity, 3).add(Field::Mass, 1).add(Field::Spin, 3);
  }
  h_.assign(n_, opt_.h_initial > 0 ? opt_.h_initial : 0);  // 0: first guess from the bounding box, in prepare()
  h_unset_ = !(opt_.h_initial > 0);
  allocate_per_particle();
  if (opt_.self_gravity) {
    if (D != 3 || !opt_.evolve_particles) throw std::invalid_argument("SpmhdScheme: self-gravity needs D = 3 and moving particles");
    gravity_ = make_self_gravity<K>(opt_.gravity_solver, GravityOptions{opt_.G, opt_.gravity_theta, 8, opt_.gravity_opening});
  }
}

template <int D, class K>
SpmhdScheme<D, K>::~SpmhdScheme() = default;
template <int D, class K>
SpmhdScheme<D, K>::SpmhdScheme(SpmhdScheme&&) noexcept = default;

template <int D, class K>
std::vector<Real> SpmhdScheme<D, K>::resume_data() const {
  std::vector<Real> data = in_particle_order(h_eval_, 1, out_h_eval_);
  if (opt_.predict_h && h_rate_known_) {
    const std::vector<Real>& rate = div_v();
    data.insert(data.end(), rate.begin(), rate.end());
    data.push_back(t_h_);
  }
  return data;
}

// resume_data(): h per particle [, then div v per particle and the time of h]
template <int D, class K>
OdeSystem::ResumeShape SpmhdScheme<D, K>::resume_shape() const {
  const bool rate = opt_.predict_h && h_rate_known_;
  return {rate ? 2 : 1, rate ? 1 : 0};
}

template <int D, class K>
void SpmhdScheme<D, K>::resume(std::span<const Real> data) {
  if (data.empty()) return;
  const bool with_rate = data.size() == 2 * n_ + 1;
  const std::span<const Real> h = with_rate ? data.first(n_) : data;
  check_resumed_smoothing_lengths(h, n_, "SpmhdScheme::resume");
  if (with_rate && !std::all_of(data.begin() + n_, data.end(), [](Real v) { return std::isfinite(v); }))
    throw std::invalid_argument("SpmhdScheme::resume: a velocity divergence or the time of h is not finite");
  for (std::size_t s = 0; s < n_; ++s) h_[s] = h_eval_[s] = h[perm_[s]];  // slot s holds particle perm_[s]
  solved_at_x_.assign(n_, 0);  // every slot solves afresh from these
  h_unset_ = false;
  solved_ = false;  // the next evaluation solves from these starts
  if (with_rate) {
    for (std::size_t s = 0; s < n_; ++s) divv_[s] = data[n_ + perm_[s]];
    set_h_time(data[2 * n_]);
    h_rate_known_ = true;
  }
  built_ = false;
  ++version_;
  evaluated_version_ = -1;
  full_rhs_at_x_ = false;
}

// Every per-particle buffer for n_ particles (h_ and x_ are set by the caller), slots = particles
// (no halo until the next evaluation).
template <int D, class K>
void SpmhdScheme<D, K>::allocate_per_particle() {
  n_all_ = n_;
  h_eval_ = h_;  // no solve yet: the next starts from h_
  rho_.assign(n_, 0);
  omega_.assign(n_, 1);
  P_.assign(n_, 0);
  sound_speed_.assign(n_, 0);
  fast_speed_.assign(n_, 0);
  cleaning_speeds_.assign(n_, 0);
  B_.assign(3 * n_, 0);
  divB_.assign(n_, 0);
  divv_.assign(n_, 0);
  h_rate_known_ = false;
  t_h_slot_.assign(n_, t_h_);
  solved_at_x_.assign(n_, 0);
  every_slot_solved_ = false;
  scratch_.assign(layout_.size(), 0);
  inv_omega_rho2_.assign(n_, 0);
  list_h_.assign(n_, 0);
  list_h_served_.assign(n_, 0);
  list_h_needed_.assign(n_, 0);
  radii_.assign(n_, 0);
  perm_.resize(n_);
  for (std::size_t i = 0; i < n_; ++i) perm_[i] = static_cast<std::uint32_t>(i);
  ms_ = m_;
  x_from_state_.assign(x_.size(), 0);
  if (opt_.evolve_particles) {
    v_.assign(D * n_, 0);
    if (!opt_.barotropic) u_.assign(n_, 0);
  }
  if (opt_.cleaning != Cleaning::None) psi_.assign(n_, 0);
  if (opt_.field == FieldRepresentation::EulerPotentials) alpha_.assign(n_, 0);
  if (opt_.self_gravity) {
    gravity_acc_.assign(3 * n_, 0);
    gravity_potential_.assign(n_, 0);
    zeta_over_omega_.assign(n_, 0);
  }
}

template <int D, class K>
const std::vector<Real>& SpmhdScheme<D, K>::in_particle_order(const std::vector<Real>& slots, int comps,
                                                               ParticleOrderCache& c) const {
  const std::size_t size = static_cast<std::size_t>(comps) * n_;  // this rank's particles (not the halo)
  if (c.version == version_ && c.data.size() == size) return c.data;
  c.data.resize(size);
  for (std::size_t s = 0; s < n_; ++s)
    for (int k = 0; k < comps; ++k) c.data[comps * perm_[s] + k] = slots[comps * s + k];
  c.version = version_;
  return c.data;
}

template <int D, class K>
std::size_t SpmhdScheme<D, K>::position_offset() const {
  return opt_.evolve_particles ? layout_.offset(Field::Position) : 0;
}
template <int D, class K>
std::size_t SpmhdScheme<D, K>::velocity_offset() const {
  return opt_.evolve_particles ? layout_.offset(Field::Velocity) : 0;
}

// Euler potentials in 2D (beta = z): B = grad alpha x z_hat = (d_y alpha, -d_x alpha, 0), with the
// difference gradient grad alpha_a = 1/(Omega_a rho_a) sum_b m_b (alpha_b - alpha_a) grad_a W_ab(h_a)
// (Price & Bate 2007). seed 000, §II-A1.
template <int D, class K>
void SpmhdScheme<D, K>::euler_potential_field(const Real* x, const Real* alpha) {
  const NeighbourList& L = ns_.list();
#pragma omp parallel for schedule(dynamic, 64)
  for (std::size_t a = 0; a < n_; ++a) {
    Vec<D> grad = Vec<D>::Zero();
    const Real ha = h_[a], r2max = (K::support * ha) * (K::support * ha);
    for (std::size_t k = L.begin(a); k < L.end(a); ++k) {
      const std::size_t b = L.indices[k];
      const Vec<D> dx = ns_.separation(x, a, b);
      const Real r2 = dx.squaredNorm();
      if (r2 >= r2max) continue;
      grad += difference_gradient_term(ms_[b], alpha[a], alpha[b],
                                       RadialGradient<D>{K::f_over_r(std::sqrt(r2), ha), dx}).vector();
    }
    grad *= 1.0 / (omega_[a] * rho_[a]);
    B_[3 * a + 0] = grad[1];
    B_[3 * a + 1] = -grad[0];
    B_[3 * a + 2] = 0;
  }
}

// P, c and the fast speed of slots [begin, end) from rho, u (or the barotropic EOS) and B;
// returns the largest fast speed.
template <int D, class K>
Real SpmhdScheme<D, K>::equation_of_state(std::size_t begin, std::size_t end) {
  const Real* u = opt_.evolve_particles && !opt_.barotropic ? u_.data() : nullptr;
  const BarotropicEos* eos = eos_ ? &*eos_ : nullptr;
  Real cmax = 0;
#pragma omp parallel for schedule(static) reduction(max : cmax)
  for (std::size_t a = begin; a < end; ++a) {
    if (eos) {
      P_[a] = eos->pressure(rho_[a]);
      sound_speed_[a] = eos->sound_speed(rho_[a]);
    } else {
      P_[a] = u ? (opt_.gamma - 1) * rho_[a] * u[a] : 0;
      sound_speed_[a] = std::sqrt(opt_.gamma * P_[a] / rho_[a]);
    }
    const Real b2 = B_[3 * a] * B_[3 * a] + B_[3 * a + 1] * B_[3 * a + 1] + B_[3 * a + 2] * B_[3 * a + 2];
    // fast magnetosonic speed (upper bound)
    fast_speed_[a] = std::sqrt(sound_speed_[a] * sound_speed_[a] + b2 / rho_[a]);
    cmax = std::max(cmax, fast_speed_[a]);
  }
  return cmax;
}

template <int D, class K>
int SpmhdScheme<D, K>::prepare(Real t, const Real* y) {
  ++version_;
  const Real* x = x_.data();
  // gathers values (comps per particle, particle order) into the first `slots` slots
  auto gather = [&](const Real* in, int comps, std::vector<Real>& out, std::size_t slots) {
    const std::uint32_t* p = perm_.data();  // (a list build renumbers the slots)
#pragma omp parallel for schedule(static)
    for (std::size_t s = 0; s < slots; ++s)
      for (int k = 0; k < comps; ++k) out[comps * s + k] = in[comps * p[s] + k];
  };
  if (halo_) {
    if (const int rc = distributed_prepare_positions(t, y)) return rc;  // collective (spmhd_distributed.cpp)
  } else if (opt_.evolve_particles) {
    // Density, h and Omega depend on the positions only: skip the solve when they are unchanged
    // (bit for bit) since the last call, e.g. max_stable_dt or stiff_diagonal after rhs.
    // Subset evaluations solve only the slots their rows read (solved_at_x_).
    gather(y + layout_.offset(Field::Position), D, x_from_state_, n_);
    const bool moved = !built_ || x_from_state_ != x_;
    if (moved) {
      full_rhs_at_x_ = false;
      std::copy(x_from_state_.begin(), x_from_state_.end(), x_.begin());
      solved_at_x_.assign(n_, 0);
    }
    // A second call at the same (t, x) whose served slots are solved (a subset's active_stable_dt
    // after its rhs_subset) would repeat the last call's list check and predictions: skipped.
    const bool unsolved = std::find(solved_at_x_.begin(), solved_at_x_.end(), 0) != solved_at_x_.end();
    if (moved || (unsolved && !served_slots_solved_at(t))) {
      interacting_rows_valid_ = false;
      if (const int rc = ensure_neighbours_and_density(t, x)) {
        built_ = false;  // x_ is not what the lists and h were made for
        return rc;
      }
      t_ensured_ = t, rate_known_at_ensure_ = h_rate_known_;
    }
  } else if (!built_) {
    interacting_rows_valid_ = false;
    if (const int rc = ensure_neighbours_and_density(t, x)) return rc;
  }
  // the other fields of this rank's particles (distributed: the halo's follow before the force
  // pass, exchange_halo_fields; serially every particle is this rank's)
  auto field = [&](Field f) { return y + layout_.offset(f); };
  if (opt_.evolve_particles) {
    gather(field(Field::Velocity), D, v_, n_);
    if (!opt_.barotropic) gather(field(Field::InternalEnergy), 1, u_, n_);
  }
  if (!psi_.empty()) gather(field(Field::Psi), 1, psi_, n_);
  if (opt_.field == FieldRepresentation::MagneticField) {
    gather(field(Field::MagneticField), 3, B_, n_);
  } else {
    ScopedPhase timer(Phase::Forces);
    gather(field(Field::EulerAlpha), 1, alpha_, n_);
    euler_potential_field(x, alpha_.data());
  }
  Real cmax = equation_of_state(0, n_);
  if (halo_) {  // the global c_h
    ScopedPhase timer(Phase::Halo);
    cmax = halo_->comm().allreduce(cmax, ReduceOp::Max);
  }
  cleaning_speed_ = opt_.overclean * (opt_.fixed_ch > 0 ? opt_.fixed_ch : cmax);
  set_cleaning_speeds(0, n_);
  spread_cleaning_speeds();
  if (!std::isfinite(cleaning_speed_)) {
    error_ = "non-finite wave speed";
    return 1;
  }
  return 0;
}

template <int D, class K>
int SpmhdScheme<D, K>::rhs(Real t, const Real* y, Real* ydot) {  // may throw: the stepper's net catches
  ++rhs_calls_;
  ScopedPhase timer(Phase::Rhs);
  if (const int rc = prepare(t, y); rc != 0) return rc;
  if (halo_) exchange_halo_fields(y);  // collective: the halo's records' inputs
  force_pass(y, ydot);
  if (opt_.self_gravity) gravity_pass(ydot);
  if (opt_.sink_particles) sink_pass(y, ydot);
  note_full_evaluation(y);
  return 0;
}

template <int D, class K>
int SpmhdScheme<D, K>::stiff_diagonal(Real t, const Real* y, Real* c) {
  if (const int rc = prepare(t, y); rc != 0) return rc;
  std::fill(c, c + layout_.size(), 0.0);
  if (!has_stiff_diagonal()) return 0;
  Real* cpsi = c + layout_.offset(Field::Psi);
  for (std::size_t a = 0; a < n_; ++a) cpsi[perm_[a]] = opt_.sigma * cleaning_speeds_[a] / h_[a];  // 1/tau_a
  return 0;
}

#define SPHARK_SPMHD_SCHEME(K) \
  template class SpmhdScheme<2, K<2>>;  \
  template class SpmhdScheme<3, K<3>>;
SPHARK_KERNELS(SPHARK_SPMHD_SCHEME)
#undef SPHARK_SPMHD_SCHEME

}  // namespace sphark
