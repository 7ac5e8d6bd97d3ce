#include "sphark/schemes/wcsph/wcsph_system.hpp"

#include <omp.h>

#include <algorithm>
#include <exception>
#include <sstream>

#include "sphark/core/cache_hints.hpp"
#include "sphark/core/profile.hpp"
#include "sphark/kernels/kernel_list.hpp"
#include "sphark/operators/tait_eos.hpp"
#include "sphark/simd/dispatch.hpp"
#include "wcsph_halo.hpp"
#include "wcsph_pair_rows.hpp"
#include "wcsph_rows_in_use.hpp"

namespace sphark {

namespace {
template <int D>
StateLayout wcsph_layout(std::size_t n, bool cleaning) {
  StateLayout L(n);
  L.add(Field::Position, D).add(Field::Velocity, D).add(Field::Density, 1);
  if (cleaning) L.add(Field::Psi, 1);
  return L;
}
}  // namespace

template <int D, class Kernel>
WcsphSystem<D, Kernel>::WcsphSystem(std::size_t particles, WcsphParams<D> params, std::optional<PeriodicBox<D>> box)
    : p_(std::move(params)), layout_(wcsph_layout<D>(particles, p_.cleaning)), search_(std::move(box)) {
  if (!(p_.h > 0) || !(p_.mass > 0) || !(p_.rho0 > 0) || !(p_.sound_speed > 0))
    throw std::invalid_argument("WcsphSystem: h, mass, rho0 and sound_speed must be positive");
  pressure_.assign(particles, 0);
  div_v_.assign(particles, 0);
  grad_rho_.assign(particles, Vec<D>::Zero());
}

template <int D, class Kernel>
WcsphSystem<D, Kernel>::~WcsphSystem() = default;

template <int D, class Kernel>
void WcsphSystem<D, Kernel>::resize_particles(std::size_t n) {
  layout_ = wcsph_layout<D>(n, p_.cleaning);
  pressure_.assign(n, 0);
  div_v_.assign(n, 0);
  grad_rho_.assign(n, Vec<D>::Zero());
  built_ = false;
  evaluated_y_.clear();
}

template <int D, class Kernel>
void WcsphSystem<D, Kernel>::update_neighbours(const Real* x, std::size_t count, const std::uint32_t* keys,
                                               bool force) {
  const Real support = Kernel::support * p_.h;
  const Real skin = p_.skin_fraction * support;
  const std::size_t n = layout_.particles();
  ScopedPhase timer(Phase::Neighbours);
  // the lists hold slots: the displacement check reads the positions in slot order
  if (built_ && !force && search_.max_displacement_since_build(x, slot_particle_.data()) < 0.5 * skin) return;
  // Lists of the particles (rows ascending in particle number, or key), then slots in cell
  // order: slot s is particle slot_particle_[s], and the rows keep their order (sums do not
  // depend on slots). The local particles (0 .. n) take the first slots: rows are theirs only.
  search_.build(x, count, support + skin, keys, nullptr, n);  // the halo's rows are never read: not built
  slot_particle_ = search_.cell_order();
  if (count > n) std::stable_partition(slot_particle_.begin(), slot_particle_.end(), [n](std::uint32_t p) { return p < n; });
  search_.renumber(slot_particle_);
  built_ = true;
  ++builds_;
  run_profile().tally(Tally::ListBuilds, 1);
}

namespace {
using wcsph_detail::ForceRow;
using wcsph_detail::Rows;
using wcsph_detail::RowInput;
using wcsph_detail::rows_in_use;

}  // namespace

template <int D, class Kernel>
void WcsphSystem<D, Kernel>::fill_records(const wcsph_detail::ParticleFields<D>& f, std::size_t count) {
  using wcsph_detail::Record;
  const bool clean = p_.cleaning, viscosity = this->viscosity();
  const Real m = p_.mass;
  records_.resize(Record<D>::size * count);
  pressure_.resize(std::max(pressure_.size(), count));
  const std::uint32_t* particle = slot_particle_.data();
  const bool stream = stream_records(sizeof(Real) * records_.size());
#pragma omp parallel
  {
#pragma omp for schedule(static) nowait
    for (std::size_t a = 0; a < count; ++a) {  // slot a: particle p
      const std::size_t p = particle[a];
      const Real rho = f.rho[p];
      pressure_[p] = tait_pressure(rho, p_.rho0, p_.sound_speed);
      alignas(16) Real r[Record<D>::size];
      for (int k = 0; k < D; ++k) {
        r[Record<D>::x + k] = f.x[D * p + k];
        r[Record<D>::v + k] = f.v[D * p + k];
        r[Record<D>::grad_rho + k] = 0;
      }
      r[Record<D>::rho] = rho;
      r[Record<D>::volume] = m / rho;
      r[Record<D>::p_over_rho2] = pressure_[p] / (rho * rho);
      r[Record<D>::q_psi] = clean ? f.psi[p] / (rho * rho) : 0;  // Omega = 1 for constant h
      r[Record<D>::sound_speed] = viscosity ? tait_sound_speed(rho, p_.rho0, p_.sound_speed) : 0;
      for (int k = 3 * D + 5; k < Record<D>::size; ++k) r[k] = 0;
      store_record(records_.data() + Record<D>::size * a, r, Record<D>::size, stream);
    }
    if (stream) store_fence();  // each writing thread, before the region's barrier
  }
}

template <int D, class Kernel>
wcsph_detail::RowInput<D> WcsphSystem<D, Kernel>::row_input() const {
  const Real h = p_.h;
  const bool subsystem = p_.cleaning_subsystem_only;
  Real grad_scale = 1 / (h * h);
  for (int k = 0; k < D; ++k) grad_scale /= h;
  const NeighbourList& nl = search_.list();
  return {records_.data(), nl.indices.data(), nl.offsets.data(), MinimumImage<D>(search_.box()),
          p_.mass, h, 1 / h, grad_scale, Kernel::support * h * Kernel::support * h, p_.alpha,
          p_.cleaning, subsystem, viscosity(), p_.delta * h * p_.sound_speed > 0 && !subsystem, corrected_diffusion()};
}

template <int D, class Kernel>
std::uint32_t* WcsphSystem<D, Kernel>::inside_start(std::size_t a) {
  return inside_.data() + search_.list().begin(a) + kInsidePad * a;
}

template <int D, class Kernel>
wcsph_detail::InsideRow WcsphSystem<D, Kernel>::inside_row(std::size_t a) const {
  return {inside_.data() + search_.list().begin(a) + kInsidePad * a, inside_count_[a]};
}

template <int D, class Kernel>
void WcsphSystem<D, Kernel>::prepare_rows(const wcsph_detail::ParticleFields<D>& f, std::size_t count) {
  fill_records(f, count);  // before `in`: it holds records_.data()
  const RowInput<D> in = row_input();
  const Rows<D, Kernel> rows = rows_in_use<D, Kernel>();
  const std::size_t n = layout_.particles();
  reserve_inside_rows();
  ScopedPhase forces_timer(Phase::Forces);
#pragma omp parallel for schedule(static)
  for (std::size_t a = 0; a < n; ++a) inside_count_[a] = rows.inside(in, a, inside_start(a));
  if (!corrected_diffusion()) return;
  ScopedPhase timer(Phase::DensityH);
#pragma omp parallel for schedule(static)
  for (std::size_t a = 0; a < n; ++a)
    grad_rho_[a] = wcsph_detail::gradient_into_record(rows, in, a, inside_row(a), records_.data());
}

// The pairs inside the support: inside_count_[a] of them from inside_start(a) on, a row's room
// its list length plus the padding a block may write past it.
template <int D, class Kernel>
void WcsphSystem<D, Kernel>::reserve_inside_rows() {
  inside_.resize(search_.list().pairs() + kInsidePad * layout_.particles());
  inside_count_.resize(layout_.particles());
}

template <int D, class Kernel>
wcsph_detail::ForceStore<D> WcsphSystem<D, Kernel>::force_store(const Real* y, Real* ydot) {
  const StateLayout& L = layout_;
  const bool clean = p_.cleaning;
  return {y + L.offset(Field::Position), y + L.offset(Field::Velocity), y + L.offset(Field::Density),
          clean ? y + L.offset(Field::Psi) : nullptr, ydot + L.offset(Field::Position),
          ydot + L.offset(Field::Velocity), ydot + L.offset(Field::Density),
          clean ? ydot + L.offset(Field::Psi) : nullptr, div_v_.data(), &p_.body_force, p_.cleaning_speed(),
          p_.cleaning_rate(), p_.delta * p_.h * p_.sound_speed, clean, p_.cleaning_subsystem_only};
}

template <int D, class Kernel>
void WcsphSystem<D, Kernel>::forces(const Real* y, Real* ydot) {
  const std::size_t n = layout_.particles();
  const RowInput<D> in = row_input();
  const Rows<D, Kernel> rows = rows_in_use<D, Kernel>();
  const wcsph_detail::ForceStore<D> store = force_store(y, ydot);
  const std::uint32_t* particle = slot_particle_.data();
  ScopedPhase forces_timer(Phase::Forces);
  Real max_acc2 = 0;
#pragma omp parallel for schedule(static) reduction(max : max_acc2)
  for (std::size_t a = 0; a < n; ++a)  // slot a: particle particle[a]
    max_acc2 = std::max(max_acc2, store(particle[a], rows.forces(in, a, inside_row(a))));
  max_accel_ = std::sqrt(max_acc2);
}

// The state is finite with rho > 0 (the stepper's guard checks it before every call).
template <int D, class Kernel>
int WcsphSystem<D, Kernel>::rhs(Real /*t*/, const Real* y, Real* ydot) {
  ScopedPhase rhs_timer(Phase::Rhs);
  ++rhs_calls_;
  evaluated_y_.clear();  // set again once every derived array is y's
  if (halo_) return distributed_rhs(y, ydot);
  const wcsph_detail::ParticleFields<D> f = wcsph_detail::state_fields<D>(y, layout_);
  const std::size_t n = layout_.particles();
  update_neighbours(f.x, n, nullptr, false);
  fill_records(f, n);
  rows_in_one_pass(y, ydot);
  evaluated_y_.assign(y, y + layout_.size());
  return 0;
}

template <int D, class Kernel>
int WcsphSystem<D, Kernel>::stiff_diagonal(Real /*t*/, const Real* /*y*/, Real* c) {
  std::fill(c, c + layout_.size(), 0.0);
  if (!p_.cleaning) return 0;
  const std::size_t o = layout_.offset(Field::Psi);
  std::fill(c + o, c + o + layout_.particles(), p_.cleaning_rate());  // psi / tau of eq. (30)
  return 0;
}

template <int D, class Kernel>
void WcsphSystem<D, Kernel>::evaluate(Real t, const Real* y) {
  bool fresh = evaluated_y_.size() == layout_.size() && std::equal(y, y + layout_.size(), evaluated_y_.begin());
  if (halo_) fresh = halo_->on_every_rank(fresh);  // the RHS is collective: every rank or none
  if (fresh) return;
  scratch_.resize(layout_.size());
  if (rhs(t, y, scratch_.data()) != 0) throw std::runtime_error("WcsphSystem: " + error_);
}

// max_a |dv_a/dt| of a derivative: the force criterion's acceleration.
template <int D, class Kernel>
Real WcsphSystem<D, Kernel>::max_acceleration(const Real* ydot) const {
  const auto dv = vector_field<D>(ydot, layout_, Field::Velocity);
  Real max_acc2 = 0;
  for (Index a = 0; a < dv.cols(); ++a) max_acc2 = std::max(max_acc2, Vec<D>(dv.col(a)).squaredNorm());
  return std::sqrt(max_acc2);
}

template <int D, class Kernel>
Real WcsphSystem<D, Kernel>::max_stable_dt(Real t, const Real* y, const Real* ydot) {
  const auto v = vector_field<D>(y, layout_, Field::Velocity);
  const auto rho = scalar_field(y, layout_, Field::Density);
  Real vmax = 0, cmax = p_.cleaning ? p_.cleaning_speed() : 0;
  for (Index a = 0; a < v.cols(); ++a) {
    vmax = std::max(vmax, v.col(a).norm());
    cmax = std::max(cmax, tait_sound_speed(rho[a], p_.rho0, p_.sound_speed));
  }
  Real accel = 0;
  if (ydot) {
    accel = max_acceleration(ydot);
  } else {
    evaluate(t, y);
    accel = max_accel_;
  }
  // Distributed: the maxima over every particle, so that dt is the serial run's bit for bit (a
  // minimum of the ranks' dt would not be: cmax and vmax may be on different ranks).
  Real maxima[3] = {vmax, cmax, accel};
  if (halo_) halo_->max_over_ranks(maxima, 3);
  return stable_dt(maxima[0], maxima[1], maxima[2]);
}

// Courant condition with the viscous signal speed (Monaghan 1992), and the force condition.
template <int D, class Kernel>
Real WcsphSystem<D, Kernel>::stable_dt(Real vmax, Real cmax, Real accel) const {
  Real dt = p_.cfl * p_.h / (cmax + vmax + 1.2 * p_.alpha * cmax);
  if (accel > 0) dt = std::min(dt, p_.cfl * std::sqrt(p_.h / accel));
  return dt;
}

#define SPHARK_WCSPH_SYSTEM(K)          \
  template class WcsphSystem<2, K<2>>; \
  template class WcsphSystem<3, K<3>>;
SPHARK_KERNELS(SPHARK_WCSPH_SYSTEM)
#undef SPHARK_WCSPH_SYSTEM

}  // namespace sphark
