#include "sphark/operators/barotropic_eos.hpp"

#include <stdexcept>
#include <string>

namespace sphark {

BarotropicEosParams price_bate_params(const CodeUnits& units, Real sound_speed_cm_s) {
  BarotropicEosParams p;
  p.sound_speed = units.velocity(sound_speed_cm_s);
  p.rho1 = units.density(1e-14);  // Price & Bate (2007), sec. 2; Phantom rhocrit1..4
  p.rho2 = units.density(1e-10);
  p.rho3 = units.density(1e-3);
  p.rho4 = units.density(1e-1);
  return p;
}

BarotropicEosParams sphere_in_box_params(const CodeUnits& units, Real sound_speed_cm_s, Real sphere_density_g_cm3,
                                         Real density_contrast) {
  BarotropicEosParams p = price_bate_params(units, sound_speed_cm_s);
  p.ambient_sound_speed = p.sound_speed * std::sqrt(density_contrast);
  p.rho0 = units.density(sphere_density_g_cm3) / 7.5;  // Phantom setup_sphereinbox: rhocrit0
  p.join_width = 0.5;
  return p;
}

namespace {
void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("BarotropicEos: " + what);
}
}  // namespace

BarotropicEos::BarotropicEos(const BarotropicEosParams& p) : p_(p) {
  require(p.sound_speed > 0, "sound speed must be positive");
  require(0 < p.rho1 && p.rho1 < p.rho2 && p.rho2 < p.rho3 && p.rho3 < p.rho4,
          "need 0 < rho1 < rho2 < rho3 < rho4");
  require(p.gamma1 >= 1 && p.gamma2 >= 1 && p.gamma3 >= 1 && p.gamma4 >= 1, "every gamma must be >= 1");
  const Real cs2 = p.sound_speed * p.sound_speed;
  // (lower edge, exponent) of each band, in order of density
  std::array<Real, kMaxBands> start{}, exponent{};
  int n = 0;
  int first_isothermal = 0;
  if (p.ambient_sound_speed > 0) {
    require(0 < p.join_width && p.join_width < 1, "join width must lie in (0, 1)");
    require(0 < p.rho0 && p.rho0 < p.rho1, "need 0 < rho0 < rho1");
    const Real rho_t = p.rho0 * (1 - p.join_width);
    const Real qa = p.ambient_sound_speed * p.ambient_sound_speed;
    start[n] = 0, exponent[n++] = 0;                                              // ambient
    start[n] = rho_t, exponent[n++] = -std::log(qa / cs2) / std::log(p.rho0 / rho_t);  // join
    first_isothermal = n;
    start[n] = p.rho0, exponent[n++] = 0;
  } else {
    start[n] = 0, exponent[n++] = 0;
  }
  start[n] = p.rho1, exponent[n++] = p.gamma1 - 1;
  start[n] = p.rho2, exponent[n++] = p.gamma2 - 1;
  start[n] = p.rho3, exponent[n++] = p.gamma3 - 1;
  start[n] = p.rho4, exponent[n++] = p.gamma4 - 1;
  bands_ = n;
  for (int k = 0; k < n; ++k) {
    band_[k].rho_start = start[k];
    band_[k].exponent = exponent[k];
    band_[k].rho_anchor = k == 0 ? start[1] : start[k];
  }
  // q: c_s^2 in the isothermal band, carried across every break by continuity.
  band_[first_isothermal].q_anchor = cs2;
  for (int k = first_isothermal + 1; k < n; ++k) {
    const Band& b = band_[k - 1];
    band_[k].q_anchor = b.q_anchor * std::pow(band_[k].rho_start / b.rho_anchor, b.exponent);
  }
  if (first_isothermal > 0) {  // join: anchored at rho_T with q = c_amb^2; ambient: c_amb^2
    band_[1].q_anchor = p.ambient_sound_speed * p.ambient_sound_speed;
    band_[0].q_anchor = band_[1].q_anchor;
  }
  // u: zero at rho_1 (lower edge of band first_isothermal + 1), integrated outwards both ways.
  const int k1 = first_isothermal + 1;
  band_[k1].u_anchor = 0;
  for (int k = k1 + 1; k < n; ++k) band_[k].u_anchor = band_[k - 1].u_anchor + energy_rise(band_[k - 1], band_[k].rho_start);
  for (int k = k1 - 1; k >= 1; --k) band_[k].u_anchor = band_[k + 1].u_anchor - energy_rise(band_[k], band_[k + 1].rho_start);
  band_[0].u_anchor = band_[1].u_anchor;  // band 0 is anchored at band 1's lower edge
}

int BarotropicEos::band_index(Real rho) const {
  int k = 0;
  while (k + 1 < bands_ && rho >= band_[k + 1].rho_start) ++k;
  return k;
}

Real BarotropicEos::sound_speed(Real rho) const {
  const Band& b = band_of(rho);
  const Real q = pressure_over_density(rho);
  // sqrt(dP/drho); the isothermal signal speed where P falls with rho (the ambient join)
  return std::sqrt(q * (1 + b.exponent > 1 ? 1 + b.exponent : 1));
}

Real BarotropicEos::energy_rise(const Band& b, Real rho) {
  if (b.exponent == 0) return b.q_anchor * std::log(rho / b.rho_anchor);
  return b.q_anchor * (std::pow(rho / b.rho_anchor, b.exponent) - 1) / b.exponent;
}

Real BarotropicEos::specific_energy(Real rho) const {
  const Band& b = band_of(rho);
  return b.u_anchor + energy_rise(b, rho);
}

}  // namespace sphark
