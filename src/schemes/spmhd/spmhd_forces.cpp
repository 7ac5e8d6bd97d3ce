// The SPMHD pair loop (seed 000, §II), gather form: each particle a sums over its own
// neighbours b and writes only its own derivatives (no races; results independent of threads).
// Its shape is that of an SPH equation (as in PySPH): per particle, init (pair_loop_arrays: the
// particle's record), pair (spmhd_pair_row.hpp, add_pairs: one call per operator of
// sphark/operators/, each citing its equation, in lanes of W neighbours) and finish
// (finish_particle).
//
// Speed: everything that depends on one particle only (1/h, the kernel-gradient scale, the
// Maxwell stress over Omega rho^2, ...) is computed once per particle per RHS into its record
// (pair_loop_arrays); the pair loop works with D-vectors (kernel gradients have no component
// beyond D) and the D x D block of the stress (the acceleration has D components).
#include <omp.h>

#include <cmath>

#include "sphark/core/cache_hints.hpp"
#include "sphark/core/profile.hpp"
#include "sphark/kernels/kernel_list.hpp"
#include "sphark/operators/mhd_operators.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"
#include "sphark/simd/dispatch.hpp"
#include "spmhd_pair_row.hpp"

namespace sphark {

namespace {

using mhd::Vec3;
using spmhd_detail::PairSums;
using spmhd_detail::Record;

// What finish_particle reads, in slot order.
struct FinishInput {
  const Real *psi, *omega, *P, *inv_omega_rho2, *cleaning_speeds;
  Real cleaning_speed;  // global c_h
  bool evolve, induction, cleaning, constrained, local_ch, subtract_monopole;
  Real sigma;
  const Real* tensile_weight;  // per slot, or nullptr (1 everywhere)
};

// Where the pair loop writes: state derivatives (at particle perm[a]) and per-slot diagnostics.
struct PairLoopOutput {
  const std::uint32_t* perm;
  Real *dx_dt, *dv_dt, *du_dt, *dB_dt, *dalpha_dt, *dpsi_dt;
  Real *div_b, *div_v;
};

// Particle a's own quantities for finish.
template <int D>
struct ParticleA {
  std::size_t a;
  Real h, rho;
  Vec3 B;
  Vec<D> v;
};

// finish: particle a's derivatives from its sums.
template <int D>
inline void finish_particle(const PairSums<D>& s, const ParticleA<D>& pa, const FinishInput& in,
                            const PairLoopOutput& out) {
  const std::size_t a = pa.a, p = out.perm[a];
  const Real inv_omega_rho = 1.0 / (in.omega[a] * pa.rho);
  const Real div_b = s.div_b * -inv_omega_rho;  // eq. (20)
  out.div_b[a] = div_b;
  Vec3 dB_dt = Vec3::Zero();
  if (in.cleaning) {
    // Constrained: dB/dt = -rho_a sum(...) (23). Previous form: dB/dt = -(difference grad psi).
    dB_dt.template head<D>() -= in.constrained ? Vec<D>(pa.rho * s.grad_psi) : Vec<D>(inv_omega_rho * s.grad_psi);
    const Real ch_factor = in.local_ch ? in.cleaning_speeds[a] : in.cleaning_speed * in.cleaning_speed;
    out.dpsi_dt[p] = mhd::psi_rate(ch_factor, div_b, in.psi[a], in.sigma > 0, in.sigma * in.cleaning_speeds[a] / pa.h,
                                   in.evolve && in.constrained, inv_omega_rho, s.continuity);  // eqs. (19), (25)
  }
  if (in.evolve) {
    out.div_v[a] = s.continuity * -inv_omega_rho;
    Vec<D> dv_dt = s.dv_dt;
    if (in.subtract_monopole)  // eq. (9), weighted near sinks and by beta (SpmhdScheme::tensile_weights)
      mhd::subtract_monopole_force<D>(dv_dt, pa.B, in.tensile_weight ? in.tensile_weight[a] * s.monopole : s.monopole);
    Eigen::Map<Vec<D>>(out.dx_dt + D * p) = pa.v;
    Eigen::Map<Vec<D>>(out.dv_dt + D * p) = dv_dt;
    if (out.du_dt) out.du_dt[p] = in.P[a] * in.inv_omega_rho2[a] * s.continuity + s.du_dt_dissipation;
    if (in.induction) dB_dt += s.induction.finish(inv_omega_rho) + pa.rho * s.resistive;  // eqs. (7), (10)
    else out.dalpha_dt[p] = 0;  // alpha advected with the flow: d alpha / dt = 0
  }
  if (in.induction) Eigen::Map<Vec3>(out.dB_dt + 3 * p) = dB_dt;
}

}  // namespace

// init: everything that depends on one particle, once per RHS, into its record (spmhd_pair_row.hpp).
template <int D, class K>
void SpmhdScheme<D, K>::pair_loop_arrays(const Real* /*y*/) {
  using R = Record<D>;
  const Real* psi = opt_.cleaning != Cleaning::None ? psi_.data() : nullptr;
  const bool energy = layout_.has(Field::InternalEnergy);  // not with a barotropic EOS
  // Self-gravity's grad-h term (Price & Monaghan 2007, §3; gravity/gravity_grad_h.hpp),
  //   dv_a/dt += -(G/2) sum_b m_b [zeta_a/Omega_a grad_a W_ab(h_a) + zeta_b/Omega_b grad_a W_ab(h_b)],
  // has the shape of eq. (6) with an isotropic stress: it rides in S = M / (Omega rho^2) as
  // -(G/2) zeta/Omega on the diagonal (the same pairs, the same kernel gradients; one pass).
  const bool grad_h_gravity = opt_.self_gravity && D == 3 && zeta_over_omega_.size() >= n_all_;
  const Real half_g = 0.5 * opt_.G;
  records_.resize(R::size * n_all_);  // this rank's particles and the halo (distributed)
  const bool stream = stream_records(sizeof(Real) * records_.size());
#pragma omp parallel
  {
#pragma omp for schedule(static) nowait
    for (std::size_t a = 0; a < n_all_; ++a) {
      alignas(16) Real r[R::size];
      const Real inv_h = 1.0 / h_[a];
      Real s = inv_h * inv_h;
      for (int k = 0; k < D; ++k) s *= inv_h;
      const Real o = 1.0 / (omega_[a] * rho_[a] * rho_[a]);
      inv_omega_rho2_[a] = o;
      const Real* B = B_.data() + 3 * a;
      for (int k = 0; k < D; ++k) {
        r[R::x + k] = x_[D * a + k];
        r[R::v + k] = opt_.evolve_particles ? v_[D * a + k] : 0;
        r[R::bo + k] = o * B[k];
      }
      r[R::h] = h_[a], r[R::m] = ms_[a], r[R::inv_h] = inv_h;
      r[R::grad_scale] = s;  // f_over_r(r, h) = f_over_r(r / h, 1) / h^(D+2)
      r[R::rho] = rho_[a], r[R::P] = P_[a], r[R::u] = energy ? u_[a] : 0;  // no u with a barotropic EOS
      r[R::fast_speed] = fast_speed_[a];
      // local_ch: the state is psi / c_h
      r[R::psi_o] = psi ? o * psi[a] * (opt_.local_ch ? cleaning_speeds_[a] : 1.0) : 0;
      r[R::psi] = psi ? psi[a] : 0;
      for (int k = 0; k < 3; ++k) r[R::B + k] = B[k];
      mhd::maxwell_stress_over_omega_rho2<D>(B, P_[a], o, r + R::stress);  // eq. (8)
      if (grad_h_gravity)
        for (int k = 0; k < D; ++k) r[R::stress + D * k + k] -= half_g * zeta_over_omega_[a];
      for (int k = R::bo + D; k < R::size; ++k) r[k] = 0;
      store_record(records_.data() + R::size * a, r, R::size, stream);
    }
    if (stream) store_fence();  // each writing thread, before the region's barrier
  }
}

namespace {
template <int D, class K>
using PairRow = PairSums<D> (*)(const spmhd_detail::RowInput<D>&, std::size_t, std::uint32_t*);
template <int D, class K>
PairRow<D, K> pair_row_in_use() {
  switch (pair_loop_simd()) {
    case PairLoopSimd::Avx512: return spmhd_detail::pair_row_avx512<D, K>;
    case PairLoopSimd::Avx2: return spmhd_detail::pair_row_avx2<D, K>;
    case PairLoopSimd::Sse2: return spmhd_detail::pair_row<simd::Real2, D, K>;
    case PairLoopSimd::Scalar: break;
  }
  return spmhd_detail::pair_row<Real, D, K>;
}
}  // namespace

template <int D, class K>
void SpmhdScheme<D, K>::force_pass(const Real* y, Real* ydot, const std::vector<std::uint32_t>* only) {
  ScopedPhase timer(Phase::Forces);
  pair_loop_arrays(y);
  const bool evolve = opt_.evolve_particles, induction = opt_.field == FieldRepresentation::MagneticField;
  const bool cleaning = opt_.cleaning != Cleaning::None;
  const bool energy = layout_.has(Field::InternalEnergy);  // not with a barotropic EOS
  const NeighbourList& L = ns_.list();
  const spmhd_detail::RowInput<D> in{records_.data(), L.indices.data(), L.offsets.data(), MinimumImage<D>(ns_.box()),
                                     K::support, evolve, energy, induction, cleaning,
                                     opt_.cleaning == Cleaning::Constrained, opt_.alpha_visc, opt_.beta_visc,
                                     energy ? opt_.alpha_u : 0.0, induction ? opt_.alpha_b : 0.0};
  const FinishInput fin{cleaning ? psi_.data() : nullptr, omega_.data(), P_.data(), inv_omega_rho2_.data(),
                        cleaning_speeds_.data(), cleaning_speed_, evolve, induction, cleaning,
                        opt_.cleaning == Cleaning::Constrained, opt_.local_ch, opt_.subtract_monopole_force, opt_.sigma,
                        tensile_weights(y)};
  auto derivative = [&](Field f, bool present) { return present ? ydot + layout_.offset(f) : nullptr; };
  const PairLoopOutput out{perm_.data(),
                           derivative(Field::Position, evolve), derivative(Field::Velocity, evolve),
                           derivative(Field::InternalEnergy, energy), derivative(Field::MagneticField, induction),
                           derivative(Field::EulerAlpha, !induction), derivative(Field::Psi, cleaning),
                           divB_.data(), divv_.data()};
  const PairRow<D, K> row = pair_row_in_use<D, K>();
  const std::vector<RowSpan>& spans = ns_.row_spans();
  const std::size_t room = max_list_ + 8;  // a row plus a padded block
  row_scratch_.resize(room * static_cast<std::size_t>(omp_get_max_threads()));
  std::size_t pairs = 0;
  if (only && interacting_rows_.size() < only->size()) interacting_rows_.resize(only->size());
#pragma omp parallel reduction(+ : pairs)
  {
    std::uint32_t* inside = row_scratch_.data() + room * static_cast<std::size_t>(omp_get_thread_num());
    const std::size_t rows = only ? only->size() : n_;
#pragma omp for schedule(dynamic, 64)
    for (std::size_t i = 0; i < rows; ++i) {
      const std::size_t a = only ? (*only)[i] : i;
      if (a < spans.size())  // the records at the rows' leading edge (core/cache_hints.hpp)
        prefetch_lines(&records_[Record<D>::size * std::min<std::size_t>(spans[a].second + kPrefetchSlotsAhead, n_all_ - 1)],
                       sizeof(Real) * Record<D>::size);
      const PairSums<D> sums = row(in, a, inside);
      pairs += sums.pairs;
      if (only) interacting_rows_[i].assign(inside, inside + sums.pairs);  // (for active_stable_dt)
      const ParticleA<D> pa{a, h_[a], rho_[a], Eigen::Map<const Vec3>(&B_[3 * a]),
                            evolve ? Vec<D>(Eigen::Map<const Vec<D>>(&v_[D * a])) : Vec<D>(Vec<D>::Zero())};
      finish_particle(sums, pa, fin, out);
    }
  }
  h_rate_known_ = true;  // div v (of every row, or of the active ones) for predict_smoothing_lengths
  interacting_rows_valid_ = only != nullptr;
  interacting_pairs_ = pairs;
  pairs_total_ += static_cast<double>(pairs);
}

#define SPHARK_SPMHD_FORCES(D, K)                                                 \
  template void SpmhdScheme<D, K>::pair_loop_arrays(const Real*);                 \
  template void SpmhdScheme<D, K>::force_pass(const Real*, Real*, const std::vector<std::uint32_t>*);
#define SPHARK_SPMHD_FORCES_2D_3D(K) SPHARK_SPMHD_FORCES(2, K<2>) SPHARK_SPMHD_FORCES(3, K<3>)
SPHARK_KERNELS(SPHARK_SPMHD_FORCES_2D_3D)
#undef SPHARK_SPMHD_FORCES_2D_3D
#undef SPHARK_SPMHD_FORCES

}  // namespace sphark
