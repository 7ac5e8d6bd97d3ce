// The SPMHD pair loop (seed 000, §II), gather form: each particle a sums over its own
// neighbours b and writes only its own derivatives (no races; results independent of threads).
#include <cmath>

#include "sphark/operators/conjugate_cleaning.hpp"
#include "sphark/operators/mhd_operators.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"

namespace sphark {

template <int D, class K>
void SpmhdScheme<D, K>::force_pass(const Real* y, Real* ydot) {
  using mhd::Mat3;
  using mhd::Vec3;
  const bool evolve = opt_.evolve_particles;
  const bool induction = opt_.field == FieldRepresentation::MagneticField;
  const Cleaning cleaning = opt_.cleaning;
  const Real* x = x_.data();
  const Real* v = evolve ? y + layout_.offset(Field::Velocity) : nullptr;
  const Real* u = evolve ? y + layout_.offset(Field::InternalEnergy) : nullptr;
  const Real* psi = cleaning != Cleaning::None ? y + layout_.offset(Field::Psi) : nullptr;
  Real* dx_dt = evolve ? ydot + layout_.offset(Field::Position) : nullptr;
  Real* dv_dt = evolve ? ydot + layout_.offset(Field::Velocity) : nullptr;
  Real* du_dt = evolve ? ydot + layout_.offset(Field::InternalEnergy) : nullptr;
  Real* dB_dt = induction ? ydot + layout_.offset(Field::MagneticField) : nullptr;
  Real* dalpha_dt = induction ? nullptr : ydot + layout_.offset(Field::EulerAlpha);
  Real* dpsi_dt = psi ? ydot + layout_.offset(Field::Psi) : nullptr;
  const Real ch2 = ch_ * ch_;
  const NeighbourList& L = ns_.list();

  auto vel3 = [&](std::size_t i) {
    Vec3 w = Vec3::Zero();
    if (v) w.template head<D>() = Eigen::Map<const Vec<D>>(v + D * i);
    return w;
  };
  auto mag = [&](std::size_t i) { return Vec3(B_[3 * i], B_[3 * i + 1], B_[3 * i + 2]); };

#pragma omp parallel for schedule(dynamic, 64)
  for (std::size_t a = 0; a < n_; ++a) {
    const Real ha = h_[a], rhoa = rho_[a], oa = 1.0 / (omega_[a] * rhoa * rhoa);
    const Vec3 Ba = mag(a), va = vel3(a);
    const Mat3 Ma = mhd::maxwell_stress(Ba, P_[a]);
    Vec3 acc = Vec3::Zero(), dB_ind = Vec3::Zero(), grad_psi = Vec3::Zero(), dB_res = Vec3::Zero();
    Real monopole = 0, divB = 0, divv = 0, dudt_p = 0, dudt_diss = 0;
    for (std::size_t k = L.begin(a); k < L.end(a); ++k) {
      const std::size_t b = L.indices[k];
      const Vec<D> dxab = ns_.separation(x, a, b);
      const Real r2 = dxab.squaredNorm(), hb = h_[b];
      const Real reach = K::support * std::max(ha, hb);
      if (r2 >= reach * reach || r2 == 0) continue;
      const Real r = std::sqrt(r2);
      Vec3 dx3 = Vec3::Zero();
      dx3.template head<D>() = dxab;
      const Real Fa = K::f_over_r(r, ha), Fb = K::f_over_r(r, hb);
      const Vec3 ga = Fa * dx3, gb = Fb * dx3;  // grad_a W_ab(h_a), grad_a W_ab(h_b)
      const Real mb = m_[b], ob = 1.0 / (omega_[b] * rho_[b] * rho_[b]);
      const Vec3 Bb = mag(b);

      divB += difference_divergence_term(mb, Ba, Bb, ga);  // seed 000, eq. (20)
      if (psi) {
        if (cleaning == Cleaning::Constrained)
          grad_psi += symmetric_gradient_term(mb, psi[a] * oa, ga, psi[b] * ob, gb);  // eq. (23)
        else
          grad_psi += mhd::difference_gradient_pair(mb, psi[a], psi[b], ga);
      }
      if (!evolve) continue;

      const Vec3 vb = vel3(b), vab = va - vb;
      const Mat3 Mb = mhd::maxwell_stress(Bb, P_[b]);
      acc += mhd::momentum_pair(mb, Ma, oa, ga, Mb, ob, gb);  // eq. (6)
      monopole += mhd::monopole_pair(mb, Ba, oa, ga, Bb, ob, gb);  // eq. (9)
      divv += difference_divergence_term(mb, va, vb, ga);  // continuity form, eq. (25)
      dudt_p += mb * vab.dot(ga);
      if (induction) dB_ind += mhd::induction_pair(mb, vab, Ba, ga);  // eq. (7)

      // Dissipation with the mean kernel gradient gbar = (g_a + g_b)/2 (antisymmetric in a, b).
      const Vec3 rhat = dx3 / r;
      const Real rhat_g = 0.5 * (Fa + Fb) * r;  // rhat . gbar < 0
      const Real rho_ab = 0.5 * (rhoa + rho_[b]);
      const Real w = vab.dot(rhat);
      const Real vsig = 0.5 * (cf_[a] + cf_[b]) - opt_.beta_visc * std::min(w, 0.0);
      if (opt_.alpha_visc > 0 && w < 0) {
        // Monaghan (1997): Pi_ab = -alpha v_sig w / rho_ab; dv = -m Pi gbar; du = m Pi/2 v_ab.gbar
        const Real Pi = -opt_.alpha_visc * vsig * w / rho_ab;
        acc -= mb * Pi * rhat_g * rhat;
        dudt_diss += 0.5 * mb * Pi * w * rhat_g;
      }
      if (opt_.alpha_u > 0) {
        // Price (2008) conductivity: du = m alpha_u v_sig^u (u_a - u_b)/rho_ab rhat.gbar
        const Real vsig_u = std::sqrt(std::abs(P_[a] - P_[b]) / rho_ab);
        dudt_diss += mb * opt_.alpha_u * vsig_u * (u[a] - u[b]) / rho_ab * rhat_g;
      }
      if (opt_.alpha_b > 0 && induction) {
        // seed 000, eq. (10), with its heating term. Signal speed |v_ab x rhat| (Price et al. 2018,
        // Phantom): the fast speed of Price & Monaghan (2005) removes most of the Orszag-Tang field
        // by t = 0.5 at 64^2 particles.
        const Real vsig_b = (vab - w * rhat).norm();
        const Vec3 Bab = Ba - Bb;
        dB_res += mhd::resistivity_pair(mb, opt_.alpha_b * vsig_b, rho_ab, Bab, rhat_g);
        dudt_diss -= 0.5 * mb * opt_.alpha_b * vsig_b / (rho_ab * rho_ab) * Bab.squaredNorm() * rhat_g;
      }
    }
    const Real inv_orho = 1.0 / (omega_[a] * rhoa);
    divB *= -inv_orho;
    divB_[a] = divB;
    Vec3 dB = Vec3::Zero();
    if (psi) {
      // Constrained: dB/dt = -rho_a sum(...) (23). Previous form: dB/dt = -(difference grad psi).
      dB -= cleaning == Cleaning::Constrained ? Vec3(rhoa * grad_psi) : Vec3(inv_orho * grad_psi);
      Real dpsi = -ch2 * divB;                                               // eq. (19)
      if (opt_.sigma > 0) dpsi -= opt_.sigma * ch_ / ha * psi[a];           // -psi / tau
      if (evolve && cleaning == Cleaning::Constrained) dpsi += 0.5 * psi[a] * inv_orho * divv;  // eq. (25)
      dpsi_dt[a] = dpsi;
    }
    if (evolve) {
      divv *= -inv_orho;
      divv_[a] = divv;
      if (opt_.subtract_monopole_force) acc -= Ba * monopole;  // eq. (9)
      Eigen::Map<Vec<D>>(dx_dt + D * a) = va.template head<D>();
      Eigen::Map<Vec<D>>(dv_dt + D * a) = acc.template head<D>();
      du_dt[a] = P_[a] * oa * dudt_p + dudt_diss;
      if (induction) dB += -inv_orho * dB_ind + rhoa * dB_res;
      else dalpha_dt[a] = 0;  // alpha advected with the flow: d alpha / dt = 0
    }
    if (induction) {
      dB_dt[3 * a + 0] = dB[0];
      dB_dt[3 * a + 1] = dB[1];
      dB_dt[3 * a + 2] = dB[2];
    }
  }
}

template void SpmhdScheme<2, CubicSpline<2>>::force_pass(const Real*, Real*);

}  // namespace sphark
