// The multirate interface of WcsphSystem (issue #17; integrate/ode_system.hpp): the derivatives
// of a subset of the particles, each against all its neighbours, and each particle's own stable
// step. Work: the records (Tait pressure, O(N) arithmetic) and the list check for all; the
// inside rows and, with the corrected diffusion, the density gradients (seed 000 §III: delta-SPH
// with Antuono's correction) of the active particles and their list neighbours, whose gradients
// the active rows read; the force rows (seed 000 eqs. (27), (28), (30), (36), (39)) of the
// active particles only. Each row sums as in rhs(): an active particle's derivatives are rhs()'s
// bit for bit.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sphark/core/profile.hpp"
#include "sphark/kernels/kernel_list.hpp"
#include "sphark/operators/tait_eos.hpp"
#include "sphark/schemes/wcsph/wcsph_system.hpp"
#include "wcsph_halo.hpp"
#include "wcsph_rows_in_use.hpp"

namespace sphark {

template <int D, class Kernel>
int WcsphSystem<D, Kernel>::rhs_subset(Real /*t*/, const Real* y, std::span<const std::size_t> active, Real* ydot) {
  if (halo_) throw std::logic_error("WcsphSystem::rhs_subset: not for a distributed system");
  ScopedPhase rhs_timer(Phase::Rhs);
  ++rhs_calls_;
  evaluated_y_.clear();  // the derived arrays are the active particles' only
  const wcsph_detail::ParticleFields<D> f = wcsph_detail::state_fields<D>(y, layout_);
  const std::size_t n = layout_.particles();
  update_neighbours(f.x, n, nullptr, false);
  fill_records(f, n);
  std::fill(ydot, ydot + layout_.size(), 0.0);
  slot_of_particle_.resize(n);
  for (std::size_t s = 0; s < n; ++s) slot_of_particle_[slot_particle_[s]] = static_cast<std::uint32_t>(s);
  // the slots whose inside rows (and gradients) are read: the active ones and their list neighbours
  const NeighbourList& list = search_.list();
  read_slot_.assign(n, 0);
  active_slots_.clear();
  for (std::size_t i : active) {
    if (i >= n) throw std::out_of_range("WcsphSystem::rhs_subset: particle " + std::to_string(i));
    const std::size_t a = slot_of_particle_[i];
    active_slots_.push_back(static_cast<std::uint32_t>(a));
    read_slot_[a] = 1;
    if (corrected_diffusion())
      for (std::size_t k = list.begin(a); k < list.end(a); ++k) read_slot_[list.indices[k]] = 1;
  }
  const wcsph_detail::RowInput<D> in = row_input();
  const wcsph_detail::Rows<D, Kernel> rows = wcsph_detail::rows_in_use<D, Kernel>();
  reserve_inside_rows();
  ScopedPhase forces_timer(Phase::Forces);
#pragma omp parallel for schedule(static)
  for (std::size_t a = 0; a < n; ++a)
    if (read_slot_[a]) {
      inside_count_[a] = rows.inside(in, a, inside_start(a));
      if (corrected_diffusion()) grad_rho_[a] = wcsph_detail::gradient_into_record(rows, in, a, inside_row(a), records_.data());
    }
  const wcsph_detail::ForceStore<D> store = force_store(y, ydot);
  Real max_acc2 = 0;
#pragma omp parallel for schedule(static) reduction(max : max_acc2)
  for (std::size_t k = 0; k < active_slots_.size(); ++k) {
    const std::size_t a = active_slots_[k];
    max_acc2 = std::max(max_acc2, store(slot_particle_[a], rows.forces(in, a, inside_row(a))));
  }
  max_accel_ = std::sqrt(max_acc2);
  return 0;
}

// Each particle's stable_dt with its own speed, sound speed (or the larger cleaning speed) and
// acceleration (from ydot, or from an evaluation at y); min over the particles >= max_stable_dt.
template <int D, class Kernel>
int WcsphSystem<D, Kernel>::particle_stable_dt(Real t, const Real* y, const Real* ydot, Real* dt) {
  if (halo_) throw std::logic_error("WcsphSystem::particle_stable_dt: not for a distributed system");
  if (!ydot) {
    evaluate(t, y);
    ydot = scratch_.data();
  }
  const auto v = vector_field<D>(y, layout_, Field::Velocity);
  const auto dv = vector_field<D>(ydot, layout_, Field::Velocity);
  const auto rho = scalar_field(y, layout_, Field::Density);
  const Real c_clean = p_.cleaning ? p_.cleaning_speed() : 0;
  for (Index a = 0; a < v.cols(); ++a)
    dt[a] = stable_dt(v.col(a).norm(), std::max(c_clean, tait_sound_speed(rho[a], p_.rho0, p_.sound_speed)),
                      Vec<D>(dv.col(a)).norm());
  return 0;
}

#define SPHARK_WCSPH_SUBSETS(K)                                                                            \
  template int WcsphSystem<2, K<2>>::rhs_subset(Real, const Real*, std::span<const std::size_t>, Real*); \
  template int WcsphSystem<3, K<3>>::rhs_subset(Real, const Real*, std::span<const std::size_t>, Real*); \
  template int WcsphSystem<2, K<2>>::particle_stable_dt(Real, const Real*, const Real*, Real*);           \
  template int WcsphSystem<3, K<3>>::particle_stable_dt(Real, const Real*, const Real*, Real*);
SPHARK_KERNELS(SPHARK_WCSPH_SUBSETS)
#undef SPHARK_WCSPH_SUBSETS

}  // namespace sphark
