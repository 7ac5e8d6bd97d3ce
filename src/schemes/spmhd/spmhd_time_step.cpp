// The time-step limits of SpmhdScheme (seed 000: the Courant condition on the fastest wave, the
// cleaning wave with its own Courant number, and with self-gravity the force criterion of
// spmhd_gravity.cpp): max_stable_dt for the global step, stable_steps per particle (multirate).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "sphark/integrate/callback_errors.hpp"
#include "sphark/kernels/kernel_list.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"

namespace sphark {

template <int D, class K>
Real SpmhdScheme<D, K>::finite_courant_step(std::size_t a, const Real* v) const {
  const Real flow = v ? (1 + opt_.beta_visc) * Eigen::Map<const Vec<D>>(v + D * a).norm() : 0;
  const Real wave_vsig = fast_speed_[a] + flow, cleaning_vsig = cleaning_speeds_[a] + flow;
  if (!std::isfinite(wave_vsig) || !std::isfinite(cleaning_vsig) || !std::isfinite(h_[a]))
    return std::numeric_limits<Real>::quiet_NaN();
  // C h / (max(c_f, c_h) + flow) when both Courant numbers are C (rounding is monotonic)
  const Real c_h_courant = opt_.cleaning_courant > 0 ? opt_.cleaning_courant : opt_.courant;
  const Real dt_wave = wave_vsig > 0 ? opt_.courant * h_[a] / wave_vsig : std::numeric_limits<Real>::infinity();
  const Real dt_cleaning = cleaning_vsig > 0 ? c_h_courant * h_[a] / cleaning_vsig : std::numeric_limits<Real>::infinity();
  return std::min(dt_wave, dt_cleaning);
}

template <int D, class K>
Real SpmhdScheme<D, K>::courant_step(std::size_t a, const Real* v) {
  const Real dt = finite_courant_step(a, v);
  if (std::isnan(dt)) error_ = "max_stable_dt: non-finite signal speed or h at particle " + std::to_string(perm_[a]);
  return dt;
}

template <int D, class K>
Real SpmhdScheme<D, K>::max_stable_dt(Real t, const Real* y, const Real* ydot) noexcept {
  constexpr Real failed = std::numeric_limits<Real>::quiet_NaN();  // documented in the header
  try {
    if (prepare(t, y) != 0) return failed;  // error_ says why
  } catch (...) {
    error_ = current_exception_message("SpmhdScheme::max_stable_dt");
    return failed;
  }
  const Real* v = opt_.evolve_particles ? v_.data() : nullptr;  // in slot order (prepare)
  // courant_step is pure unless a particle's step is not finite (then it names it in error_):
  // the minimum in parallel over finite signal speeds, the failing particle found again serially.
  Real dt = std::numeric_limits<Real>::infinity();
  bool finite = true;
#pragma omp parallel for schedule(static) reduction(min : dt) reduction(&& : finite)
  for (std::size_t a = 0; a < n_; ++a) {
    const Real dt_a = finite_courant_step(a, v);
    finite = finite && !std::isnan(dt_a);
    dt = std::min(dt, dt_a);
  }
  if (!finite) {
    for (std::size_t a = 0; a < n_; ++a)
      if (std::isnan(courant_step(a, v))) break;  // sets error_
    return failed;
  }
  if (opt_.self_gravity) {  // the force criterion, with the accelerations of ydot or of f(t, y)
    if (!ydot) {
      if (evaluate(t, y) != 0) return failed;
      ydot = scratch_.data();
    }
    dt = std::min(dt, force_time_step(ydot));
  }
  return dt;
}

template <int D, class K>
Real SpmhdScheme<D, K>::own_step(std::size_t a, const Real* ydot) {
  const Real force = opt_.self_gravity ? force_step(a, ydot) : std::numeric_limits<Real>::infinity();
  return std::min(courant_step(a, v_.data()), force);  // (NaN if the Courant step is)
}

template <int D, class K>
int SpmhdScheme<D, K>::prepare_steps(Real t, const Real* y, const Real*& ydot) noexcept {
  try {
    if (!opt_.evolve_particles) throw std::logic_error("per-particle steps: fixed particles");
    if (opt_.self_gravity && !ydot) {
      if (evaluate(t, y) != 0) return 1;
      ydot = scratch_.data();
      return 0;
    }
    return prepare(t, y);  // error_ says why
  } catch (...) {
    error_ = current_exception_message("SpmhdScheme::stable_steps");
    return 1;
  }
}

template <int D, class K>
int SpmhdScheme<D, K>::stable_steps(Real t, const Real* y, const Real* ydot, std::vector<Real>& courant,
                                     std::vector<Real>& force) noexcept {
  if (prepare_steps(t, y, ydot) != 0) return 1;
  const Real* v = v_.data();  // in slot order (prepare)
  courant.assign(n_, std::numeric_limits<Real>::infinity());
  force.assign(n_, std::numeric_limits<Real>::infinity());
  for (std::size_t a = 0; a < n_; ++a) {
    courant[perm_[a]] = courant_step(a, v);
    if (std::isnan(courant[perm_[a]])) return 1;
    if (opt_.self_gravity) force[perm_[a]] = force_step(a, ydot);
  }
  return 0;
}

#define SPHARK_SPMHD_TIME_STEP(D, K)                                                                        \
  template Real SpmhdScheme<D, K>::finite_courant_step(std::size_t, const Real*) const;                  \
  template Real SpmhdScheme<D, K>::courant_step(std::size_t, const Real*);                               \
  template Real SpmhdScheme<D, K>::max_stable_dt(Real, const Real*, const Real*) noexcept;              \
  template Real SpmhdScheme<D, K>::own_step(std::size_t, const Real*);                                  \
  template int SpmhdScheme<D, K>::prepare_steps(Real, const Real*, const Real*&) noexcept;               \
  template int SpmhdScheme<D, K>::stable_steps(Real, const Real*, const Real*, std::vector<Real>&,      \
                                               std::vector<Real>&) noexcept;
#define SPHARK_SPMHD_TIME_STEP_2D_3D(K) SPHARK_SPMHD_TIME_STEP(2, K<2>) SPHARK_SPMHD_TIME_STEP(3, K<3>)
SPHARK_KERNELS(SPHARK_SPMHD_TIME_STEP_2D_3D)
#undef SPHARK_SPMHD_TIME_STEP_2D_3D
#undef SPHARK_SPMHD_TIME_STEP

}  // namespace sphark
