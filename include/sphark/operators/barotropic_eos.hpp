#pragma once
// Barotropic equation of state for star formation: Price & Bate (2007, MNRAS 377, 77, sec. 2),
// the form of Phantom's ieos = 8 (src/main/eos_barotropic.f90; Bate, Bonnell & Bromm 2003).
//
// Every band is a power law in the isothermal sound speed squared q = P / rho:
//   q(rho) = q_k (rho / rho_k)^(e_k)   for rho_k <= rho < rho_{k+1},
// with q_k chosen so that q (hence P = rho q) is continuous at every break:
//   ambient     rho < rho_T            e = 0            q = c_amb^2 (warm medium)
//   join        rho_T <= rho < rho_0   e = -s           log-linear in log q vs log rho (Phantom):
//                                                       q(rho_T) = c_amb^2, q(rho_0) = c_s^2,
//                                                       s = ln(c_amb^2 / c_s^2) / ln(rho_0 / rho_T)
//   isothermal  rho_0 <= rho < rho_1   e = 0            P = c_s^2 rho
//   then        rho_1 .. rho_2         e = gamma_1 - 1  (gamma_1 = 7/5)
//               rho_2 .. rho_3         e = gamma_2 - 1  (gamma_2 = 1.1)
//               rho_3 .. rho_4         e = gamma_3 - 1  (gamma_3 = 5/3)
//               rho_4 ..               e = gamma_4 - 1  (gamma_4 = 1.1)
// Phantom's defaults: rho_1..4 = 1e-14, 1e-10, 1e-3, 1e-1 g/cm^3; rho_0 = rho_sphere / 7.5,
// rho_T = (1 - 0.5) rho_0; c_amb = c_s sqrt(30) for a density contrast of 30.
//
// Derived quantities (closed forms, band by band):
//   dP/drho = q (1 + e)
//   u(rho)  = int_{rho_1}^{rho} P / r^2 dr = int q dln(rho): in a band, u_k + (q - q_k) / e,
//             or u_k + q_k ln(rho / rho_k) where e = 0. u(rho_1) = 0 (any constant would do:
//             only differences of u enter the energy budget).
//   c_s     = sqrt(dP/drho) in every band with dP/drho > 0. In the join, 1 + e = 1 - s < 0 for
//             c_amb^2 / c_s^2 > rho_0 / rho_T (s = 4.91 for Phantom's 30 and 2): P FALLS with
//             rho there (by the factor (rho_T / rho_0) c_amb^2 / c_s^2 = 15 across the join),
//             so there is no adiabatic sound speed; like Phantom (gamma = 1 there) we return
//             the isothermal speed sqrt(P / rho) as the signal speed.
#include <array>
#include <cmath>
#include <cstddef>

#include "sphark/core/types.hpp"
#include "sphark/core/units.hpp"

namespace sphark {

struct BarotropicEosParams {
  Real sound_speed = 0;  // c_s, code units: P = c_s^2 rho between rho_0 and rho_1
  // band edges rho_1 < rho_2 < rho_3 < rho_4, code units
  Real rho1 = 0, rho2 = 0, rho3 = 0, rho4 = 0;
  Real gamma1 = 7.0 / 5.0, gamma2 = 1.1, gamma3 = 5.0 / 3.0, gamma4 = 1.1;
  // ambient medium: q = c_amb^2 below rho_T = rho0 (1 - join_width), joined to c_s^2 at rho0.
  // ambient_sound_speed = 0: no ambient band (P = c_s^2 rho all the way down).
  Real ambient_sound_speed = 0;
  Real rho0 = 0;
  Real join_width = 0.5;  // Phantom's drhocrit
};

// Phantom's ieos = 8 thresholds in cgs (Price & Bate 2007), converted to code units.
BarotropicEosParams price_bate_params(const CodeUnits& units, Real sound_speed_cm_s);

// The collapse of issue #16: price_bate_params plus an ambient medium of density
// rho_sphere / contrast at sound speed c_s sqrt(contrast) (pressure equilibrium),
// joined between rho_0 / 2 and rho_0 = rho_sphere / 7.5 (Phantom's setup_sphereinbox).
BarotropicEosParams sphere_in_box_params(const CodeUnits& units, Real sound_speed_cm_s, Real sphere_density_g_cm3,
                                         Real density_contrast = 30);

class BarotropicEos {
 public:
  static constexpr int kMaxBands = 7;

  // Throws std::invalid_argument unless c_s > 0, 0 < rho_1 < rho_2 < rho_3 < rho_4, every
  // gamma >= 1, and (with an ambient) 0 < join_width < 1, 0 < rho_0 < rho_1.
  explicit BarotropicEos(const BarotropicEosParams& p);

  Real pressure_over_density(Real rho) const {  // q = P / rho
    const Band& b = band_of(rho);
    return b.exponent == 0 ? b.q_anchor : b.q_anchor * std::pow(rho / b.rho_anchor, b.exponent);
  }
  Real pressure(Real rho) const { return rho * pressure_over_density(rho); }
  Real dp_drho(Real rho) const { return pressure_over_density(rho) * (1 + band_of(rho).exponent); }
  Real sound_speed(Real rho) const;
  // u(rho) = int_{rho_1}^{rho} P / r^2 dr (negative below rho_1).
  Real specific_energy(Real rho) const;
  // Specific THERMAL energy, for the sink-creation energy checks (not u(rho) above, which is
  // the work integral and is negative below rho_1): P / ((gamma - 1) rho) in the power-law bands
  // (Phantom's ptmass_create for ieos = 8), and 3/2 P / rho in the isothermal bands and the join,
  // where Phantom's formula would divide by gamma - 1 = 0 (3/2 P / rho is its fallback for other
  // equations of state: a monatomic-like gas kept isothermal by cooling). Jumps at rho_1.
  Real thermal_energy(Real rho) const {
    const Real e = band_of(rho).exponent;
    return pressure_over_density(rho) * (e > 0 ? 1 / e : 1.5);
  }
  // The band's effective gamma = 1 + e (Phantom's gamma_barotropic reports 1 in the join).
  Real gamma(Real rho) const { return 1 + band_of(rho).exponent; }

  int bands() const { return bands_; }
  // lower edge of band k (band 0 starts at 0); k = 1 .. bands() - 1 are the breaks.
  Real band_start(int k) const { return band_[k].rho_start; }
  int band_index(Real rho) const;
  const BarotropicEosParams& params() const { return p_; }

 private:
  // q = q_anchor (rho / rho_anchor)^exponent, u = u_anchor + int_{rho_anchor}^{rho} q dln(rho).
  // The anchor is the band's lower edge; for band 0 (which starts at 0) its upper edge.
  struct Band {
    Real rho_start = 0;
    Real rho_anchor = 0, q_anchor = 0, u_anchor = 0;
    Real exponent = 0;
  };
  const Band& band_of(Real rho) const { return band_[band_index(rho)]; }
  // int_{rho_anchor}^{rho} q dln(rho) within band b
  static Real energy_rise(const Band& b, Real rho);

  BarotropicEosParams p_;
  std::array<Band, kMaxBands> band_{};
  int bands_ = 0;
};

}  // namespace sphark
