// Barotropic EOS (Price & Bate 2007; Phantom ieos = 8) in the collapse's code units:
// P against the closed-form products of Price & Bate in every band, continuity of P at every
// break (relative jump at round-off), c_s^2 against a finite-difference dP/drho in every band
// and on both sides of every break, u(rho) against Gauss-Legendre quadrature of P / rho^2, and
// monotonicity (with the one band where P falls: Phantom's ambient join).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "sphark/core/units.hpp"
#include "sphark/operators/barotropic_eos.hpp"

using namespace sphark;

namespace {
constexpr Real kSphereDensity = 7.43e-18;  // g/cm^3, issue #16
constexpr Real kSoundSpeed = 21888.0;      // cm/s

BarotropicEos collapse_eos() {
  return BarotropicEos(sphere_in_box_params(CodeUnits::collapse(), kSoundSpeed, kSphereDensity));
}

// log-spaced densities from rho_lo to rho_hi (code units)
std::vector<Real> log_grid(Real lo, Real hi, int n) {
  std::vector<Real> r(n);
  for (int i = 0; i < n; ++i) r[i] = lo * std::pow(hi / lo, static_cast<Real>(i) / (n - 1));
  return r;
}
}  // namespace

TEST(Units, GravitationalConstantIsOneInCodeUnits) {
  const CodeUnits u = CodeUnits::collapse();
  const Real T = u.time_s();
  EXPECT_NEAR(cgs::gravitational_constant * u.mass_g * T * T / std::pow(u.length_cm, 3), 1.0, 1e-15);
  EXPECT_NEAR(u.density_g_cm3(), cgs::solar_mass / 1e48, 1e-15 * u.density_g_cm3());
  EXPECT_NEAR(u.velocity(u.velocity_cm_s()), 1.0, 1e-15);
  // issue #16: t_ff = sqrt(3 pi / (32 G rho)) = 7.71e11 s for rho = 7.43e-18 g/cm^3
  const Real t_ff_code = std::sqrt(3 * kPi / (32 * u.density(kSphereDensity)));
  EXPECT_NEAR(t_ff_code * T / 7.71e11, 1.0, 1e-3);
}

TEST(BarotropicEos, PressureMatchesPriceBateProductsInEveryBand) {
  const BarotropicEos eos = collapse_eos();
  const BarotropicEosParams& p = eos.params();
  const Real c2 = p.sound_speed * p.sound_speed, ca2 = p.ambient_sound_speed * p.ambient_sound_speed;
  const Real rhoT = 0.5 * p.rho0;
  ASSERT_EQ(eos.bands(), 7);
  // Phantom's eos_info_barotropic: P = cs^2 rho1 (rho2/rho1)^g1 (rho3/rho2)^g2 ... (rho/rho_k)^gk
  auto expected = [&](Real rho) {
    if (rho < rhoT) return ca2 * rho;
    if (rho < p.rho0) return rho * ca2 * std::pow(10.0, std::log10(c2 / ca2) * std::log10(rho / rhoT) /
                                                            std::log10(p.rho0 / rhoT));
    if (rho < p.rho1) return c2 * rho;
    const Real a = c2 * p.rho1;
    if (rho < p.rho2) return a * std::pow(rho / p.rho1, p.gamma1);
    const Real b = a * std::pow(p.rho2 / p.rho1, p.gamma1);
    if (rho < p.rho3) return b * std::pow(rho / p.rho2, p.gamma2);
    const Real c = b * std::pow(p.rho3 / p.rho2, p.gamma2);
    if (rho < p.rho4) return c * std::pow(rho / p.rho3, p.gamma3);
    return c * std::pow(p.rho4 / p.rho3, p.gamma3) * std::pow(rho / p.rho4, p.gamma4);
  };
  for (Real rho : log_grid(1e-6 * p.rho0, 1e3 * p.rho4, 997)) {
    const Real P = eos.pressure(rho);
    EXPECT_NEAR(P / expected(rho), 1.0, 1e-13) << rho;
  }
  EXPECT_NEAR(eos.band_start(1), rhoT, 1e-15 * rhoT);
  EXPECT_NEAR(p.rho0 * CodeUnits::collapse().density_g_cm3(), kSphereDensity / 7.5, 1e-30);
}

TEST(BarotropicEos, PressureIsContinuousAtEveryBreak) {
  for (bool ambient : {true, false}) {
    BarotropicEosParams prm = sphere_in_box_params(CodeUnits::collapse(), kSoundSpeed, kSphereDensity);
    if (!ambient) prm.ambient_sound_speed = 0;
    const BarotropicEos eos(prm);
    ASSERT_EQ(eos.bands(), ambient ? 7 : 5);
    for (int k = 1; k < eos.bands(); ++k) {
      const Real rho = eos.band_start(k);
      const Real below = std::nextafter(rho, 0.0);
      ASSERT_EQ(eos.band_index(below), k - 1);
      ASSERT_EQ(eos.band_index(rho), k);
      const Real P_below = eos.pressure(below) * (rho / below);  // the 1-ulp step in rho removed
      const Real jump = std::abs(eos.pressure(rho) - P_below) / eos.pressure(rho);
      EXPECT_LT(jump, 8 * std::numeric_limits<Real>::epsilon() * (1 + std::abs(eos.gamma(rho))))
          << "break " << k << " at rho = " << rho;
      const Real u_jump = std::abs(eos.specific_energy(rho) - eos.specific_energy(below));
      EXPECT_LT(u_jump, 1e-14 * (std::abs(eos.specific_energy(rho)) + eos.pressure(rho) / rho)) << k;
    }
  }
}

TEST(BarotropicEos, SoundSpeedSquaredIsDpDrhoInEveryBandAndAtTheBreaks) {
  const BarotropicEos eos = collapse_eos();
  auto P = [&](Real rho) { return eos.pressure(rho); };
  for (int k = 0; k < eos.bands(); ++k) {
    const Real lo = k == 0 ? 1e-3 * eos.band_start(1) : eos.band_start(k);
    const Real hi = k + 1 < eos.bands() ? eos.band_start(k + 1) : 1e3 * lo;
    const bool join = k == 1;  // P falls with rho there: the signal speed is sqrt(P / rho)
    for (Real f : {0.1, 0.37, 0.5, 0.81}) {
      const Real rho = lo * std::pow(hi / lo, f), d = 1e-5 * rho;
      const Real fd = (P(rho + d) - P(rho - d)) / (2 * d);
      EXPECT_NEAR(eos.dp_drho(rho) / fd, 1.0, 1e-8) << "band " << k << " rho " << rho;
      const Real c2 = eos.sound_speed(rho) * eos.sound_speed(rho);
      if (join) {
        EXPECT_LT(fd, 0) << rho;
        EXPECT_NEAR(c2 / (P(rho) / rho), 1.0, 1e-14);
      } else {
        EXPECT_NEAR(c2 / fd, 1.0, 1e-8) << "band " << k << " rho " << rho;
      }
    }
    // one-sided differences from inside the band at its edges (first order: step 1e-7)
    if (k > 0 && !join) {
      const Real d = 1e-7 * lo;
      const Real fd = (P(lo + d) - P(lo)) / d;
      EXPECT_NEAR(eos.sound_speed(lo) * eos.sound_speed(lo) / fd, 1.0, 1e-6) << "lower edge of band " << k;
    }
    if (k + 1 < eos.bands() && !join) {
      const Real top = std::nextafter(hi, 0.0), d = 1e-7 * hi;
      const Real fd = (P(top) - P(top - d)) / d;
      EXPECT_NEAR(eos.sound_speed(top) * eos.sound_speed(top) / fd, 1.0, 1e-6) << "upper edge of band " << k;
    }
  }
}

// Gauss-Legendre (8 points) on m equal pieces of [ln a, ln b]: int_a^b P / rho^2 drho
// = int q dln(rho), q smooth within a band.
static Real quadrature(const BarotropicEos& eos, Real a, Real b, int m = 64) {
  static const std::array<Real, 4> x = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                        0.9602898564975363};
  static const std::array<Real, 4> w = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                        0.1012285362903763};
  const Real la = std::log(a), lb = std::log(b), step = (lb - la) / m;
  Real sum = 0;
  for (int i = 0; i < m; ++i) {
    const Real mid = la + (i + 0.5) * step;
    for (int k = 0; k < 4; ++k)
      for (Real s : {-1.0, 1.0}) {
        const Real rho = std::exp(mid + s * x[k] * 0.5 * step);
        sum += w[k] * 0.5 * step * eos.pressure(rho) / rho;
      }
  }
  return sum;
}

TEST(BarotropicEos, SpecificEnergyIsTheIntegralOfPOverRhoSquared) {
  const BarotropicEos eos = collapse_eos();
  const Real rho1 = eos.params().rho1;
  EXPECT_EQ(eos.specific_energy(rho1), 0.0);
  std::vector<Real> breaks;
  for (int k = 1; k < eos.bands(); ++k) breaks.push_back(eos.band_start(k));
  for (Real rho : log_grid(1e-4 * eos.band_start(1), 1e4 * eos.params().rho4, 61)) {
    // integrate from rho_1 to rho, piece by piece between the breaks
    const Real lo = std::min(rho, rho1), hi = std::max(rho, rho1);
    Real integral = 0, a = lo;
    for (Real b : breaks) {
      if (b > a && b < hi) integral += quadrature(eos, a, b), a = b;
    }
    integral += quadrature(eos, a, hi);
    if (rho < rho1) integral = -integral;
    const Real scale = std::abs(integral) + eos.pressure_over_density(rho);
    EXPECT_NEAR(eos.specific_energy(rho), integral, 1e-12 * scale) << rho;
  }
}

TEST(BarotropicEos, MonotoneExceptWherePhantomsAmbientJoinLetsPressureFall) {
  const BarotropicEos eos = collapse_eos();
  const Real rhoT = eos.band_start(1), rho0 = eos.band_start(2);
  const std::vector<Real> rho = log_grid(1e-6 * rhoT, 1e4 * eos.params().rho4, 4001);
  for (std::size_t i = 1; i < rho.size(); ++i) {
    const bool touches_join = rho[i] > rhoT && rho[i - 1] < rho0;
    const bool inside_join = rho[i - 1] >= rhoT && rho[i] < rho0;
    if (!touches_join) {
      EXPECT_GT(eos.pressure(rho[i]), eos.pressure(rho[i - 1])) << rho[i];
    } else if (inside_join) {
      EXPECT_LT(eos.pressure(rho[i]), eos.pressure(rho[i - 1])) << rho[i];
    }
    EXPECT_GT(eos.specific_energy(rho[i]), eos.specific_energy(rho[i - 1])) << rho[i];  // P / rho^2 > 0
    EXPECT_GT(eos.sound_speed(rho[i]), 0.0);
  }
  // across the join P falls by (rho_T / rho_0) c_amb^2 / c_s^2 = 0.5 * 30 = 15
  EXPECT_NEAR(eos.pressure(std::nextafter(rhoT, 0.0)) / eos.pressure(rho0), 15.0, 1e-12);
  // pressure equilibrium of the set-up: ambient at rho_sphere / 30 and the sphere both at c_s^2 rho_sphere
  const Real rho_s = CodeUnits::collapse().density(kSphereDensity);
  EXPECT_NEAR(eos.pressure(rho_s / 30) / eos.pressure(rho_s), 1.0, 1e-14);
}

TEST(BarotropicEos, ThermalEnergyForTheSinkChecks) {
  const BarotropicEos eos = collapse_eos();
  const BarotropicEosParams& p = eos.params();
  const Real rhos[] = {0.1 * p.rho0, 0.75 * p.rho0, 10 * p.rho0, 10 * p.rho1, 10 * p.rho2, 10 * p.rho3, 10 * p.rho4};
  const Real gammas[] = {1, 1, 1, p.gamma1, p.gamma2, p.gamma3, p.gamma4};
  for (int k = 0; k < 7; ++k) {
    const Real q = eos.pressure(rhos[k]) / rhos[k];
    const Real expected = gammas[k] > 1 ? q / (gammas[k] - 1) : 1.5 * q;
    EXPECT_NEAR(eos.thermal_energy(rhos[k]) / expected, 1.0, 1e-14) << k;
  }
}

TEST(BarotropicEos, RejectsBadParameters) {
  BarotropicEosParams p = price_bate_params(CodeUnits::collapse(), kSoundSpeed);
  EXPECT_NO_THROW(BarotropicEos{p});
  BarotropicEosParams q = p;
  q.rho3 = q.rho2;
  EXPECT_THROW(BarotropicEos{q}, std::invalid_argument);
  q = p;
  q.sound_speed = 0;
  EXPECT_THROW(BarotropicEos{q}, std::invalid_argument);
  q = p;
  q.gamma2 = 0.9;
  EXPECT_THROW(BarotropicEos{q}, std::invalid_argument);
  q = p;
  q.ambient_sound_speed = 2 * p.sound_speed;  // ambient without rho0
  EXPECT_THROW(BarotropicEos{q}, std::invalid_argument);
}
