// The SPMHD pair loop (seed 000, §II), gather form: each particle a sums over its own
// neighbours b and writes only its own derivatives (no races; results independent of threads).
// Its shape is that of an SPH equation (as in PySPH): per particle, init (pair_loop_arrays and
// PairSums), pair (add_pair: one call per operator of sphark/operators/, each citing its
// equation) and finish (finish_particle).
//
// Speed: everything that depends on one particle only (1/h, the kernel-gradient scale, the
// Maxwell stress over Omega rho^2, ...) is computed once per particle per RHS into arrays
// (pair_loop_arrays); the pair loop works with D-vectors (kernel gradients have no component
// beyond D) and the D x D block of the stress (the acceleration has D components).
#include <cmath>

#include "sphark/core/profile.hpp"
#include "sphark/kernels/kernel_list.hpp"
#include "sphark/operators/conjugate_cleaning.hpp"
#include "sphark/operators/mhd_operators.hpp"
#include "sphark/operators/pair_geometry.hpp"
#include "sphark/operators/pressure_force.hpp"
#include "sphark/operators/signal_velocity_dissipation.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"
#include "sphark/schemes/spmhd/unit_kernel.hpp"

namespace sphark {

namespace {

using mhd::Vec3;

// What the pair loop reads, in slot order (prepare() and pair_loop_arrays() fill it).
struct PairLoopInput {
  const Real *x, *v, *u, *psi, *m, *h, *inv_h, *grad_scale, *rho, *omega, *P, *fast_speed, *B;
  const Real *inv_omega_rho2, *stress_over_omega_rho2, *b_over_omega_rho2, *psi_over_omega_rho2;
  const Real* cleaning_speeds;  // c_h,a
  Real cleaning_speed;          // global c_h
  bool evolve, induction, cleaning, constrained, local_ch, subtract_monopole;
  Real alpha_visc, beta_visc, alpha_u, alpha_b, sigma;
};

// Where the pair loop writes: state derivatives (at particle perm[a]) and per-slot diagnostics.
struct PairLoopOutput {
  const std::uint32_t* perm;
  Real *dx_dt, *dv_dt, *du_dt, *dB_dt, *dalpha_dt, *dpsi_dt;
  Real *div_b, *div_v;
};

// init: the sums of one particle a.
template <int D>
struct PairSums {
  Vec<D> dv_dt = Vec<D>::Zero();     // (6) and viscosity; (9) subtracted at finish
  Vec<D> grad_psi = Vec<D>::Zero();  // (23), or the difference gradient
  mhd::Induction<D> induction;       // (7)
  Vec3 resistive = Vec3::Zero();     // (10)
  Real monopole = 0;                 // (9)
  Real div_b = 0;                    // (20)
  Real continuity = 0;               // sum_b m_b v_ab . g_a: div v (25) and the P dV work
  Real du_dt_dissipation = 0;        // heating of viscosity, conductivity and resistivity
};

// Particle a's own quantities, loaded once.
template <int D>
struct ParticleA {
  std::size_t a;
  Real h, inv_h, grad_scale, rho;
  Vec3 B;
  Vec<D> v, b_over_omega_rho2;
  Eigen::Matrix<Real, D, D> stress_over_omega_rho2;
};

template <int D>
Vec<D> velocity_of(const PairLoopInput& in, std::size_t i) {
  return in.v ? Vec<D>(Eigen::Map<const Vec<D>>(in.v + D * i)) : Vec<D>(Vec<D>::Zero());
}

// pair: neighbour b of particle a, |x_ab| < support * max(h_a, h_b), x_ab != 0.
template <int D, class K>
inline void add_pair(PairSums<D>& s, const ParticleA<D>& pa, const PairLoopInput& in, std::size_t b,
                     const Vec<D>& x_ab, Real r2) {
  using MatD = Eigen::Matrix<Real, D, D>;
  const std::size_t a = pa.a;
  const Real r = std::sqrt(r2), inv_r = 1.0 / r;
  // grad_a W_ab(h_a) = grad_factor_a x_ab, grad_a W_ab(h_b) = grad_factor_b x_ab
  const Real grad_factor_a = pa.grad_scale * UnitKernel<K>::f_over_r(r * pa.inv_h, pa.h * inv_r);
  const Real grad_factor_b = in.grad_scale[b] * UnitKernel<K>::f_over_r(r * in.inv_h[b], in.h[b] * inv_r);
  const Vec<D> g_a = grad_factor_a * x_ab, g_b = grad_factor_b * x_ab;
  const Real m_b = in.m[b];
  const Vec3 B_b = Eigen::Map<const Vec3>(in.B + 3 * b), B_ab = pa.B - B_b;

  s.div_b += difference_divergence_term(m_b, pa.B.template head<D>(), B_b.template head<D>(), g_a);  // eq. (20)
  if (in.psi) {
    if (in.constrained)  // eq. (23), the conjugate of (20)
      s.grad_psi += symmetric_gradient_term(m_b, in.psi_over_omega_rho2[a], RadialGradient<D>{grad_factor_a, x_ab},
                                            in.psi_over_omega_rho2[b], RadialGradient<D>{grad_factor_b, x_ab})
                        .vector();
    else
      s.grad_psi += difference_gradient_term(m_b, in.psi[a], in.psi[b], g_a);
  }
  if (!in.evolve) return;

  const Vec<D> v_ab = pa.v - velocity_of<D>(in, b);
  s.dv_dt += mhd::maxwell_force_term(m_b, pa.stress_over_omega_rho2, g_a,
                                     Eigen::Map<const MatD>(in.stress_over_omega_rho2 + D * D * b), g_b);  // eq. (6)
  s.monopole += mhd::monopole_term(m_b, pa.b_over_omega_rho2, g_a,
                                   Eigen::Map<const Vec<D>>(in.b_over_omega_rho2 + 3 * b), g_b);  // eq. (9)
  s.continuity += continuity_term<D>(m_b, v_ab, g_a);  // eq. (25)
  if (in.induction) s.induction.pair(m_b, v_ab, pa.B, g_a);  // eq. (7)

  // Dissipation with the mean kernel gradient gbar = (g_a + g_b)/2: rhat . gbar = (F_a + F_b) r / 2.
  const Vec<D> rhat = inv_r * x_ab;
  const Real rhat_dot_gbar = 0.5 * (grad_factor_a + grad_factor_b) * r;
  const Real inv_rho_ab = 1.0 / (0.5 * (pa.rho + in.rho[b]));
  const Real w_ab = v_ab.dot(rhat);
  if (in.alpha_visc > 0 && approaching(w_ab)) {
    const ViscousPairTerm<D> visc = signal_velocity_viscosity_term<D>(
        m_b, in.alpha_visc, in.beta_visc, in.fast_speed[a], in.fast_speed[b], w_ab, inv_rho_ab, rhat, rhat_dot_gbar);
    s.dv_dt += visc.dv_dt;
    s.du_dt_dissipation += visc.du_dt;
  }
  if (in.alpha_u > 0)
    s.du_dt_dissipation +=
        conductivity_term(m_b, in.alpha_u, in.P[a], in.P[b], in.u[a], in.u[b], inv_rho_ab, rhat_dot_gbar);
  if (in.alpha_b > 0) {  // eq. (10)
    const mhd::ResistivePairTerm res =
        mhd::resistivity_term<D>(m_b, in.alpha_b, v_ab, w_ab, rhat, inv_rho_ab, B_ab, rhat_dot_gbar);
    s.resistive += res.dB_dt;
    s.du_dt_dissipation += res.du_dt;
  }
}

// finish: particle a's derivatives from its sums.
template <int D>
inline void finish_particle(const PairSums<D>& s, const ParticleA<D>& pa, const PairLoopInput& in,
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
    if (in.subtract_monopole) mhd::subtract_monopole_force<D>(dv_dt, pa.B, s.monopole);  // eq. (9)
    Eigen::Map<Vec<D>>(out.dx_dt + D * p) = pa.v;
    Eigen::Map<Vec<D>>(out.dv_dt + D * p) = dv_dt;
    if (out.du_dt) out.du_dt[p] = in.P[a] * in.inv_omega_rho2[a] * s.continuity + s.du_dt_dissipation;
    if (in.induction) dB_dt += s.induction.finish(inv_omega_rho) + pa.rho * s.resistive;  // eqs. (7), (10)
    else out.dalpha_dt[p] = 0;  // alpha advected with the flow: d alpha / dt = 0
  }
  if (in.induction) Eigen::Map<Vec3>(out.dB_dt + 3 * p) = dB_dt;
}

}  // namespace

template <int D, class K>
void SpmhdScheme<D, K>::pair_loop_arrays(const Real* /*y*/) {
  const Real* psi = opt_.cleaning != Cleaning::None ? psi_.data() : nullptr;
#pragma omp parallel for schedule(static)
  for (std::size_t a = 0; a < n_; ++a) {
    const Real inv_h = 1.0 / h_[a];
    Real s = inv_h * inv_h;
    for (int k = 0; k < D; ++k) s *= inv_h;
    inv_h_[a] = inv_h;
    grad_scale_[a] = s;  // f_over_r(r, h) = f_over_r(r / h, 1) / h^(D+2)
    const Real o = 1.0 / (omega_[a] * rho_[a] * rho_[a]);
    inv_omega_rho2_[a] = o;
    const Real* B = B_.data() + 3 * a;
    mhd::maxwell_stress_over_omega_rho2<D>(B, P_[a], o, stress_over_omega_rho2_.data() + D * D * a);  // eq. (8)
    for (int k = 0; k < 3; ++k) b_over_omega_rho2_[3 * a + k] = o * B[k];
    // local_ch: the state is psi / c_h
    psi_over_omega_rho2_[a] = psi ? o * psi[a] * (opt_.local_ch ? cleaning_speeds_[a] : 1.0) : 0;
  }
}

template <int D, class K>
void SpmhdScheme<D, K>::force_pass(const Real* y, Real* ydot) {
  ScopedPhase timer(Phase::Forces);
  pair_loop_arrays(y);
  const bool evolve = opt_.evolve_particles, induction = opt_.field == FieldRepresentation::MagneticField;
  const bool cleaning = opt_.cleaning != Cleaning::None;
  const bool energy = layout_.has(Field::InternalEnergy);  // not with a barotropic EOS
  const PairLoopInput in{x_.data(), evolve ? v_.data() : nullptr, energy ? u_.data() : nullptr,
                         cleaning ? psi_.data() : nullptr, ms_.data(), h_.data(), inv_h_.data(), grad_scale_.data(),
                         rho_.data(), omega_.data(), P_.data(), fast_speed_.data(), B_.data(), inv_omega_rho2_.data(),
                         stress_over_omega_rho2_.data(), b_over_omega_rho2_.data(), psi_over_omega_rho2_.data(),
                         cleaning_speeds_.data(), cleaning_speed_,
                         evolve, induction, cleaning, opt_.cleaning == Cleaning::Constrained, opt_.local_ch,
                         opt_.subtract_monopole_force,
                         opt_.alpha_visc, opt_.beta_visc, opt_.alpha_u, induction ? opt_.alpha_b : 0.0, opt_.sigma};
  auto derivative = [&](Field f, bool present) { return present ? ydot + layout_.offset(f) : nullptr; };
  const PairLoopOutput out{perm_.data(),
                           derivative(Field::Position, evolve), derivative(Field::Velocity, evolve),
                           derivative(Field::InternalEnergy, energy), derivative(Field::MagneticField, induction),
                           derivative(Field::EulerAlpha, !induction), derivative(Field::Psi, cleaning),
                           divB_.data(), divv_.data()};
  const NeighbourList& L = ns_.list();
  const MinimumImage<D> image(ns_.box());
  std::size_t pairs = 0;
#pragma omp parallel for schedule(dynamic, 64) reduction(+ : pairs)
  for (std::size_t a = 0; a < n_; ++a) {
    const ParticleA<D> pa{a, h_[a], inv_h_[a], grad_scale_[a], rho_[a], Eigen::Map<const Vec3>(&B_[3 * a]),
                          velocity_of<D>(in, a), Eigen::Map<const Vec<D>>(&b_over_omega_rho2_[3 * a]),
                          Eigen::Map<const Eigen::Matrix<Real, D, D>>(&stress_over_omega_rho2_[D * D * a])};
    PairSums<D> sums;
    for (std::size_t k = L.begin(a); k < L.end(a); ++k) {
      const std::size_t b = L.indices[k];
      const Vec<D> x_ab = image(in.x + D * a, in.x + D * b);
      const Real r2 = x_ab.squaredNorm();
      const Real reach = K::support * std::max(pa.h, in.h[b]);
      if (r2 >= reach * reach || r2 == 0) continue;
      ++pairs;
      add_pair<D, K>(sums, pa, in, b, x_ab, r2);
    }
    finish_particle(sums, pa, in, out);
  }
  interacting_pairs_ = pairs;
  pairs_total_ += static_cast<double>(pairs);
}

#define SPHARK_SPMHD_FORCES(D, K)                                                 \
  template void SpmhdScheme<D, K>::pair_loop_arrays(const Real*);                 \
  template void SpmhdScheme<D, K>::force_pass(const Real*, Real*);
#define SPHARK_SPMHD_FORCES_2D_3D(K) SPHARK_SPMHD_FORCES(2, K<2>) SPHARK_SPMHD_FORCES(3, K<3>)
SPHARK_KERNELS(SPHARK_SPMHD_FORCES_2D_3D)
#undef SPHARK_SPMHD_FORCES_2D_3D
#undef SPHARK_SPMHD_FORCES

}  // namespace sphark
