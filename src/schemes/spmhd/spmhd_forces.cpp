// The SPMHD pair loop (seed 000, §II), gather form: each particle a sums over its own
// neighbours b and writes only its own derivatives (no races; results independent of threads).
//
// Speed: everything that depends on one particle only (1/h, the kernel-gradient scale, the
// Maxwell stress over Omega rho^2, ...) is computed once per particle per RHS into arrays
// (pair_loop_arrays); the pair loop works with D-vectors (kernel gradients have no component
// beyond D) and the D x D block of the stress (the acceleration has D components). Compared
// with evaluating the 3 x 3 stress of both particles per pair, results change at round-off only.
#include <cmath>

#include "sphark/core/profile.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"
#include "sphark/schemes/spmhd/unit_kernel.hpp"

namespace sphark {

template <int D, class K>
void SpmhdScheme<D, K>::pair_loop_arrays(const Real* /*y*/) {
  const Real* psi = opt_.cleaning != Cleaning::None ? psi_.data() : nullptr;
#pragma omp parallel for schedule(static)
  for (std::size_t a = 0; a < n_; ++a) {
    const Real hi = 1.0 / h_[a];
    Real s = hi * hi;
    for (int k = 0; k < D; ++k) s *= hi;
    hinv_[a] = hi;
    fscale_[a] = s;  // f_over_r(r, h) = f_over_r(r / h, 1) / h^(D+2)
    const Real o = 1.0 / (omega_[a] * rho_[a] * rho_[a]);
    o_[a] = o;
    const Real* B = B_.data() + 3 * a;
    const Real ptot = P_[a] + 0.5 * (B[0] * B[0] + B[1] * B[1] + B[2] * B[2]);
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) oM_[D * D * a + D * i + j] = o * (B[i] * B[j] - (i == j ? ptot : 0.0));  // eq. (8)
    for (int k = 0; k < 3; ++k) oB_[3 * a + k] = o * B[k];
    opsi_[a] = psi ? o * psi[a] * (opt_.local_ch ? chs_[a] : 1.0) : 0;  // local_ch: the state is psi / c_h
  }
}

template <int D, class K>
void SpmhdScheme<D, K>::force_pass(const Real* y, Real* ydot) {
  ScopedPhase timer(Phase::Forces);
  pair_loop_arrays(y);
  using Vec3 = Eigen::Matrix<Real, 3, 1>;
  using MatD = Eigen::Matrix<Real, D, D>;
  const bool evolve = opt_.evolve_particles;
  const bool induction = opt_.field == FieldRepresentation::MagneticField;
  const Cleaning cleaning = opt_.cleaning;
  const Real* x = x_.data();
  // inputs in slot order (gathered by prepare()); outputs go to particle perm_[a]
  const Real* v = evolve ? v_.data() : nullptr;
  const Real* u = evolve ? u_.data() : nullptr;
  const Real* psi = cleaning != Cleaning::None ? psi_.data() : nullptr;
  const std::uint32_t* perm = perm_.data();
  Real* dx_dt = evolve ? ydot + layout_.offset(Field::Position) : nullptr;
  Real* dv_dt = evolve ? ydot + layout_.offset(Field::Velocity) : nullptr;
  Real* du_dt = evolve ? ydot + layout_.offset(Field::InternalEnergy) : nullptr;
  Real* dB_dt = induction ? ydot + layout_.offset(Field::MagneticField) : nullptr;
  Real* dalpha_dt = induction ? nullptr : ydot + layout_.offset(Field::EulerAlpha);
  Real* dpsi_dt = psi ? ydot + layout_.offset(Field::Psi) : nullptr;
  const Real ch2 = ch_ * ch_;
  const NeighbourList& L = ns_.list();
  const MinimumImage<D> image(ns_.box());
  const Real alpha_visc = opt_.alpha_visc, beta_visc = opt_.beta_visc, alpha_u = opt_.alpha_u;
  const Real alpha_b = induction ? opt_.alpha_b : 0.0;
  const Real *m = ms_.data(), *h = h_.data(), *hinv = hinv_.data(), *fscale = fscale_.data(), *rho = rho_.data();
  const Real *o = o_.data(), *oM = oM_.data(), *oB = oB_.data(), *opsi = opsi_.data(), *Bs = B_.data();
  const Real *cf = cf_.data(), *P = P_.data();
  auto mag = [&](std::size_t i) { return Eigen::Map<const Vec3>(Bs + 3 * i); };
  auto vel = [&](std::size_t i) { return v ? Vec<D>(Eigen::Map<const Vec<D>>(v + D * i)) : Vec<D>(Vec<D>::Zero()); };
  std::size_t pairs = 0;

#pragma omp parallel for schedule(dynamic, 64) reduction(+ : pairs)
  for (std::size_t a = 0; a < n_; ++a) {
    const Real ha = h[a], rhoa = rho[a], oa = o[a], hia = hinv[a], fsa = fscale[a];
    const Vec3 Ba = mag(a);
    const Vec<D> va = vel(a), oBa = Eigen::Map<const Vec<D>>(oB + 3 * a);
    const MatD oMa = Eigen::Map<const MatD>(oM + D * D * a);
    Vec<D> acc = Vec<D>::Zero(), grad_psi = Vec<D>::Zero();
    Vec3 dB_ind = Vec3::Zero(), dB_res = Vec3::Zero();
    Real monopole = 0, divB = 0, divv = 0, dudt_p = 0, dudt_diss = 0;
    for (std::size_t k = L.begin(a); k < L.end(a); ++k) {
      const std::size_t b = L.indices[k];
      const Vec<D> dx = image(x + D * a, x + D * b);
      const Real r2 = dx.squaredNorm(), hb = h[b];
      const Real reach = K::support * std::max(ha, hb);
      if (r2 >= reach * reach || r2 == 0) continue;
      ++pairs;
      const Real r = std::sqrt(r2), rinv = 1.0 / r;
      const Real Fa = fsa * UnitKernel<K>::f_over_r(r * hia, ha * rinv);
      const Real Fb = fscale[b] * UnitKernel<K>::f_over_r(r * hinv[b], hb * rinv);
      const Vec<D> ga = Fa * dx, gb = Fb * dx;  // grad_a W_ab(h_a), grad_a W_ab(h_b)
      const Real mb = m[b];
      const Vec3 Bb = mag(b), Bab = Ba - Bb;
      const Real Ba_ga = Ba.template head<D>().dot(ga);

      divB += mb * Bab.template head<D>().dot(ga);  // seed 000, eq. (20)
      if (psi) {
        if (cleaning == Cleaning::Constrained)
          grad_psi += mb * (opsi[a] * Fa + opsi[b] * Fb) * dx;  // eq. (23)
        else
          grad_psi += mb * (psi[b] - psi[a]) * ga;  // difference gradient (not conjugate to (20))
      }
      if (!evolve) continue;

      const Vec<D> vab = va - vel(b);
      const Real vab_ga = vab.dot(ga);
      acc += mb * (oMa * ga + Eigen::Map<const MatD>(oM + D * D * b) * gb);  // eq. (6)
      monopole += mb * (oBa.dot(ga) + Eigen::Map<const Vec<D>>(oB + 3 * b).dot(gb));  // eq. (9)
      divv += mb * vab_ga;  // continuity form, eq. (25)
      dudt_p += mb * vab_ga;
      if (induction) {  // eq. (7): m_b [ v_ab (B_a . g_a) - B_a (v_ab . g_a) ]
        dB_ind.template head<D>() += mb * Ba_ga * vab;
        dB_ind -= mb * vab_ga * Ba;
      }

      // Dissipation with the mean kernel gradient gbar = (g_a + g_b)/2 (antisymmetric in a, b).
      const Vec<D> rhat = rinv * dx;
      const Real rhat_g = 0.5 * (Fa + Fb) * r;  // rhat . gbar < 0
      const Real rho_ab = 0.5 * (rhoa + rho[b]), rho_ab_inv = 1.0 / rho_ab;
      const Real w = vab.dot(rhat);
      if (alpha_visc > 0 && w < 0) {
        // Monaghan (1997): Pi_ab = -alpha v_sig w / rho_ab, v_sig = (c_a + c_b)/2 - beta w;
        // dv = -m Pi gbar; du = m Pi/2 v_ab.gbar
        const Real vsig = 0.5 * (cf[a] + cf[b]) - beta_visc * w;
        const Real Pi = -alpha_visc * vsig * w * rho_ab_inv;
        acc -= (mb * Pi * rhat_g) * rhat;
        dudt_diss += 0.5 * mb * Pi * w * rhat_g;
      }
      if (alpha_u > 0) {
        // Price (2008) conductivity: du = m alpha_u v_sig^u (u_a - u_b)/rho_ab rhat.gbar
        const Real vsig_u = std::sqrt(std::abs(P[a] - P[b]) * rho_ab_inv);
        dudt_diss += mb * alpha_u * vsig_u * (u[a] - u[b]) * rho_ab_inv * rhat_g;
      }
      if (alpha_b > 0) {
        // seed 000, eq. (10), with its heating term (rho_ab^2, see mhd_operators.hpp). Signal
        // speed |v_ab x rhat| (Price et al. 2018, Phantom): the fast speed of Price & Monaghan
        // (2005) removes most of the Orszag-Tang field by t = 0.5 at 64^2 particles.
        const Real vsig_b = (vab - w * rhat).norm();
        const Real res = mb * alpha_b * vsig_b * rho_ab_inv * rho_ab_inv * rhat_g;
        dB_res += res * Bab;
        dudt_diss -= 0.5 * res * Bab.squaredNorm();
      }
    }
    const Real inv_orho = 1.0 / (omega_[a] * rhoa);
    divB *= -inv_orho;
    divB_[a] = divB;
    Vec3 dB = Vec3::Zero();
    if (psi) {
      // Constrained: dB/dt = -rho_a sum(...) (23). Previous form: dB/dt = -(difference grad psi).
      dB.template head<D>() -= cleaning == Cleaning::Constrained ? Vec<D>(rhoa * grad_psi) : Vec<D>(inv_orho * grad_psi);
      // eq. (19); with local_ch the state is psi/c_h,a (Tricco, Price & Bate 2016): d(psi/c_h)/dt =
      // -c_h div B - (psi/c_h)/tau - (psi/c_h) div v / 2.
      Real dpsi = -(opt_.local_ch ? chs_[a] : ch2) * divB;
      if (opt_.sigma > 0) dpsi -= opt_.sigma * chs_[a] / ha * psi[a];       // -psi / tau
      if (evolve && cleaning == Cleaning::Constrained) dpsi += 0.5 * psi[a] * inv_orho * divv;  // eq. (25)
      dpsi_dt[perm[a]] = dpsi;
    }
    if (evolve) {
      divv *= -inv_orho;
      divv_[a] = divv;
      if (opt_.subtract_monopole_force) acc -= Ba.template head<D>() * monopole;  // eq. (9)
      Eigen::Map<Vec<D>>(dx_dt + D * perm[a]) = va;
      Eigen::Map<Vec<D>>(dv_dt + D * perm[a]) = acc;
      du_dt[perm[a]] = P[a] * oa * dudt_p + dudt_diss;
      if (induction) dB += -inv_orho * dB_ind + rhoa * dB_res;
      else dalpha_dt[perm[a]] = 0;  // alpha advected with the flow: d alpha / dt = 0
    }
    if (induction) Eigen::Map<Vec3>(dB_dt + 3 * perm[a]) = dB;
  }
  interacting_pairs_ = pairs;
  pairs_total_ += static_cast<double>(pairs);
}

#define SPHARK_SPMHD_FORCES(D, K)                                   \
  template void SpmhdScheme<D, K>::pair_loop_arrays(const Real*); \
  template void SpmhdScheme<D, K>::force_pass(const Real*, Real*);
SPHARK_SPMHD_FORCES(2, CubicSpline<2>)
SPHARK_SPMHD_FORCES(3, CubicSpline<3>)
#undef SPHARK_SPMHD_FORCES

}  // namespace sphark
