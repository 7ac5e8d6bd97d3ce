// The cleaning subsystem (fixed particles, seed 000 §II-C and §IV-A): the constrained form
// conserves E = sum m (B^2/(2 rho) + psi^2/(2 rho c_h^2)) to round-off (eqs. (21)-(23)); with
// damping dE/dt = -sum m psi^2/(rho c_h^2 tau) (eq. (24)); the previous form does not conserve E.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <random>

#include "sphark/scenes/cleaning_disc/cleaning_disc.hpp"
#include "sphark/scenes/orszag_tang/orszag_tang.hpp"

namespace sphark {
namespace {

struct EnergyRate {
  Real rate = 0;   // dE/dt from the RHS
  Real scale = 0;  // sum of the magnitudes of its terms
};

struct DiscCase {
  ParticleSet2D p = disc_square_lattice(1.0, 0.04, 1.0);
  SpmhdScheme<2> scheme;
  std::vector<Real> y, ydot;

  DiscCase(Cleaning form, Real sigma, Real overclean = 1) : DiscCase(options(form, sigma, overclean)) {}
  explicit DiscCase(const SpmhdOptions& o) : scheme(p.m, o, std::nullopt, p.x) {
    y.assign(scheme.size(), 0);
    ydot.assign(scheme.size(), 0);
    disc_initial_field(scheme, p, y.data());
    // A generic psi and in-plane B perturbation, so that every term of (21) is exercised.
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<Real> U(-1, 1);
    auto B = vector_field<3>(y.data(), scheme.layout(), Field::MagneticField);
    auto psi = scalar_field(y.data(), scheme.layout(), Field::Psi);
    for (std::size_t a = 0; a < p.size(); ++a) {
      B(1, a) += 0.05 * U(rng);
      psi(a) = 0.1 * U(rng);
    }
    EXPECT_EQ(scheme.rhs(0, y.data(), ydot.data()), 0) << scheme.last_error();
  }
  static SpmhdOptions options(Cleaning form, Real sigma, Real overclean) {
    SpmhdOptions o;
    o.overclean = overclean;
    o.evolve_particles = false;
    o.cleaning = form;
    o.sigma = sigma;
    o.fixed_ch = 1.0;
    return o;
  }
  // min_a min(C h_a / c_f,a, C_h h_a / c_h), C_h = 0 meaning C (fixed particles, P = 0)
  Real expected_step(Real cleaning_courant) const {
    const Real C = scheme.options().courant, C_h = cleaning_courant > 0 ? cleaning_courant : C;
    const auto& B = scheme.magnetic_field();
    Real dt = std::numeric_limits<Real>::infinity();
    for (std::size_t a = 0; a < p.size(); ++a) {
      const Real h = scheme.h()[a], rho = scheme.rho()[a];
      const Real c_f = std::sqrt((B[3 * a] * B[3 * a] + B[3 * a + 1] * B[3 * a + 1] + B[3 * a + 2] * B[3 * a + 2]) / rho);
      dt = std::min({dt, C * h / c_f, C_h * h / scheme.cleaning_speed()});
    }
    return dt;
  }
  EnergyRate energy_rate() const {
    const StateLayout& L = scheme.layout();
    auto B = vector_field<3>(y.data(), L, Field::MagneticField);
    auto dB = vector_field<3>(ydot.data(), L, Field::MagneticField);
    auto psi = scalar_field(y.data(), L, Field::Psi);
    auto dpsi = scalar_field(ydot.data(), L, Field::Psi);
    // With local_ch the state is psi/c_h,a and the psi energy is m (psi/c_h)^2 / (2 rho).
    const Real ch2 = scheme.options().local_ch ? 1.0 : scheme.cleaning_speed() * scheme.cleaning_speed();
    EnergyRate e;
    for (std::size_t a = 0; a < p.size(); ++a) {
      const Real m = p.m[a], rho = scheme.rho()[a];
      const Real tb = m * B.col(a).dot(dB.col(a)) / rho, tp = m * psi(a) * dpsi(a) / (rho * ch2);
      e.rate += tb + tp;
      e.scale += std::abs(tb) + std::abs(tp);
    }
    return e;
  }
};

TEST(SpmhdCleaning, DiscHasTheSeedsParticleCount) {
  EXPECT_EQ(disc_square_lattice(1.0, 0.04, 1.0).size(), 1976u);
}

TEST(SpmhdCleaning, ConstrainedConservesCleaningEnergyToRoundOff) {
  DiscCase c(Cleaning::Constrained, 0.0);
  const EnergyRate e = c.energy_rate();
  ASSERT_GT(e.scale, 0);
  EXPECT_LT(std::abs(e.rate), 1e-14 * e.scale) << "dE/dt = " << e.rate << ", scale " << e.scale;
}

TEST(SpmhdCleaning, ConstrainedWithDampingOnlyDissipates) {
  DiscCase c(Cleaning::Constrained, 0.3);
  const EnergyRate e = c.energy_rate();
  // seed 000, eq. (24): dE/dt = -sum m psi^2 / (rho c_h^2 tau), 1/tau = sigma c_h / h.
  auto psi = scalar_field(c.y.data(), c.scheme.layout(), Field::Psi);
  const Real ch = c.scheme.cleaning_speed();
  Real expected = 0;
  for (std::size_t a = 0; a < c.p.size(); ++a)
    expected -= c.p.m[a] * psi(a) * psi(a) / (c.scheme.rho()[a] * ch * ch) * (0.3 * ch / c.scheme.h()[a]);
  EXPECT_LT(e.rate, 0);
  EXPECT_NEAR(e.rate, expected, 1e-14 * e.scale);
}

// Overcleaning (c_h = f x the base speed, Tricco, Price & Bate 2016; Phantom's overcleanfac): the
// cleaning speed is exactly f times the base, the energy with the overcleaned c_h is still conserved
// to round-off without damping, and with damping dE/dt is eq. (24) with 1/tau = sigma f c_h / h.
TEST(SpmhdCleaning, OvercleaningKeepsEnergyConservationAndScalesTheSpeed) {
  DiscCase c(Cleaning::Constrained, 0.0, 4.0);
  EXPECT_EQ(c.scheme.cleaning_speed(), 4.0);  // fixed_ch = 1, overclean = 4
  const EnergyRate e = c.energy_rate();
  ASSERT_GT(e.scale, 0);
  EXPECT_LT(std::abs(e.rate), 1e-14 * e.scale) << "dE/dt = " << e.rate << ", scale " << e.scale;

  DiscCase d(Cleaning::Constrained, 0.3, 4.0);
  const EnergyRate ed = d.energy_rate();
  auto psi = scalar_field(d.y.data(), d.scheme.layout(), Field::Psi);
  Real expected = 0;
  for (std::size_t a = 0; a < d.p.size(); ++a)
    expected -= d.p.m[a] * psi(a) * psi(a) / (d.scheme.rho()[a] * 16.0) * (0.3 * 4.0 / d.scheme.h()[a]);
  EXPECT_NEAR(ed.rate, expected, 1e-14 * ed.scale);
  // The time step respects the overcleaned speed: C h_min / c_h (fixed particles: no v term).
  const Real hmin = *std::min_element(d.scheme.h().begin(), d.scheme.h().end());
  EXPECT_DOUBLE_EQ(d.scheme.max_stable_dt(0, d.y.data(), nullptr), d.scheme.options().courant * hmin / 4.0);
}

// The cleaning wave's own Courant number C_h: dt = min_a min(C h_a / c_f,a, C_h h_a / c_h) (fixed
// particles: no |v| term; P = 0: c_f,a = |B_a| / sqrt(rho_a)); C_h = 0 and C_h = C both give the
// single criterion C h / max(c_f, c_h) bit for bit.
TEST(SpmhdCleaning, CleaningCourantNumberSetsTheCleaningWavesStep) {
  auto stable_dt = [](Real cleaning_courant) {
    SpmhdOptions o = DiscCase::options(Cleaning::Constrained, 0.3, 4.0);
    o.cleaning_courant = cleaning_courant;
    DiscCase c(o);
    return std::pair{c.scheme.max_stable_dt(0, c.y.data(), nullptr), c.expected_step(cleaning_courant)};
  };
  const auto [dt_default, expected_default] = stable_dt(0);
  EXPECT_EQ(dt_default, stable_dt(SpmhdOptions{}.courant).first);
  EXPECT_DOUBLE_EQ(dt_default, expected_default);
  const auto [dt_wide, expected_wide] = stable_dt(4.0);  // C_h = 4: the wave criterion binds somewhere
  EXPECT_DOUBLE_EQ(dt_wide, expected_wide);
  EXPECT_GT(dt_wide, 2 * dt_default);
  EXPECT_THROW(stable_dt(-0.1), std::invalid_argument);
}

// Per-particle c_h,a = f |B_a|/sqrt(rho_a) (fixed particles: P = 0), the state holding psi/c_h
// (Tricco, Price & Bate 2016): E = sum m (B^2 + (psi/c_h)^2)/(2 rho) is conserved to round-off
// although c_h varies from particle to particle (the B_x bump of eq. (40)).
TEST(SpmhdCleaning, LocalCleaningSpeedConservesEnergyToRoundOff) {
  SpmhdOptions o = DiscCase::options(Cleaning::Constrained, 0.0, 2.0);
  o.fixed_ch = 0;
  o.local_ch = true;
  DiscCase c(o);
  const auto& ch = c.scheme.cleaning_speeds();
  const auto [lo, hi] = std::minmax_element(ch.begin(), ch.end());
  EXPECT_GT(*hi, 1.3 * *lo);  // genuinely variable (|B| from B0 at the edge to sqrt(2) B0 at the centre)
  auto B = vector_field<3>(c.y.data(), c.scheme.layout(), Field::MagneticField);
  for (std::size_t a = 0; a < c.p.size(); ++a)
    EXPECT_DOUBLE_EQ(ch[a], 2.0 * std::sqrt(B.col(a).squaredNorm() / c.scheme.rho()[a]));
  const EnergyRate e = c.energy_rate();
  ASSERT_GT(e.scale, 0);
  EXPECT_LT(std::abs(e.rate), 1e-14 * e.scale) << "dE/dt = " << e.rate << ", scale " << e.scale;
}

// c_h,a spread over k kernel supports (SpmhdOptions::ch_spread): k passes of c_a <- the largest
// c_b with |x_ab| < support max(h_a, h_b), against a brute-force pass over every pair of the
// particles' own speeds, exactly; the energy still conserved to round-off (c_h,a is only a
// coefficient of a's terms in Tricco, Price & Bate's form).
SpmhdOptions spread_options(int hops) {
  SpmhdOptions o = DiscCase::options(Cleaning::Constrained, 0.0, 2.0);
  o.fixed_ch = 0;
  o.local_ch = true;
  o.ch_spread = hops;
  return o;
}

std::vector<Real> spread_by_every_pair(std::vector<Real> c, const SpmhdScheme<2>& s, int passes) {
  const std::vector<Real>& h = s.h();
  const std::vector<Real> x = s.positions();
  for (int pass = 0; pass < passes; ++pass) {
    std::vector<Real> next = c;
    for (std::size_t a = 0; a < c.size(); ++a)
      for (std::size_t b = 0; b < c.size(); ++b) {
        const Real reach = CubicSpline<2>::support * std::max(h[a], h[b]);
        if ((Eigen::Map<const Vec<2>>(&x[2 * a]) - Eigen::Map<const Vec<2>>(&x[2 * b])).squaredNorm() < reach * reach)
          next[a] = std::max(next[a], c[b]);
      }
    c = next;
  }
  return c;
}

TEST(SpmhdCleaning, SpreadCleaningSpeedIsTheLargestWithinItsSupportsAndConservesEnergy) {
  DiscCase own(spread_options(0)), spread(spread_options(2));
  const std::vector<Real> expected = spread_by_every_pair(own.scheme.cleaning_speeds(), own.scheme, 2);
  const std::vector<Real>& ch = spread.scheme.cleaning_speeds();
  std::size_t raised = 0;
  for (std::size_t a = 0; a < ch.size(); ++a) {
    ASSERT_EQ(ch[a], expected[a]) << "particle " << a;
    raised += ch[a] > own.scheme.cleaning_speeds()[a];
  }
  EXPECT_GT(raised, ch.size() / 10);  // the field varies: many are raised, ...
  EXPECT_LT(raised, ch.size());       // ... the largest is not
  const EnergyRate e = spread.energy_rate();
  ASSERT_GT(e.scale, 0);
  EXPECT_LT(std::abs(e.rate), 1e-14 * e.scale) << "dE/dt = " << e.rate << ", scale " << e.scale;
  SpmhdOptions global = spread_options(2);
  global.local_ch = false;  // a spread of the one global c_h means nothing: refused
  EXPECT_THROW(DiscCase{global}, std::invalid_argument);
}

// A subset evaluation computes the spread only near its rows (the active particles' neighbours
// and ch_spread hops beyond): its derivatives are the full evaluation's bit for bit.
TEST(SpmhdCleaning, ASubsetsSpreadCleaningSpeedsAreTheFullEvaluationsBitForBit) {
  DiscCase c(spread_options(3));
  const std::vector<std::size_t> active = {100, 988, 1500};
  std::vector<Real> f(c.y.size(), 7.0);
  ASSERT_EQ(c.scheme.rhs_subset(0, c.y.data(), active, f.data()), 0) << c.scheme.last_error();
  const std::vector<std::size_t> owner = c.scheme.entry_particles();
  std::size_t compared = 0;
  for (std::size_t k = 0; k < f.size(); ++k)
    if (std::find(active.begin(), active.end(), owner[k]) != active.end()) {
      ASSERT_EQ(f[k], c.ydot[k]) << "entry " << k << " (particle " << owner[k] << ")";
      ++compared;
    }
  EXPECT_EQ(compared, 3u * 4u);  // B (3) and psi of each
}

TEST(SpmhdCleaning, OvercleanBelowOneIsRejected) {
  const ParticleSet2D p = disc_square_lattice(1.0, 0.04, 1.0);
  SpmhdOptions o = DiscCase::options(Cleaning::Constrained, 0.3, 0.5);
  EXPECT_THROW(SpmhdScheme<2>(p.m, o, std::nullopt, p.x), std::invalid_argument);
}

TEST(SpmhdCleaning, NonConservativeFormDoesNotConserveEnergy) {
  DiscCase c(Cleaning::NonConservative, 0.0);
  const EnergyRate e = c.energy_rate();
  // The difference grad psi is not the conjugate of (20): the free edge creates or removes energy.
  std::cout << "non-conservative: dE/dt = " << e.rate << " (relative " << e.rate / e.scale << ")\n";
  EXPECT_GT(std::abs(e.rate), 1e-3 * e.scale);
}

TEST(SpmhdCleaning, StiffDiagonalIsTheDampingRate) {
  DiscCase c(Cleaning::Constrained, 0.3);
  std::vector<Real> diag(c.scheme.size());
  ASSERT_TRUE(c.scheme.has_stiff_diagonal());
  ASSERT_EQ(c.scheme.stiff_diagonal(0, c.y.data(), diag.data()), 0);
  // The damped RHS minus the undamped one is exactly -c psi on the psi entries, 0 elsewhere.
  DiscCase u(Cleaning::Constrained, 0.0);
  const std::size_t o = c.scheme.layout().offset(Field::Psi);
  for (std::size_t k = 0; k < c.scheme.size(); ++k) {
    const Real diff = c.ydot[k] - u.ydot[k];
    if (k < o) {
      EXPECT_EQ(diag[k], 0.0);
      EXPECT_EQ(diff, 0.0);
    } else {
      // round-off of the subtraction only
      EXPECT_NEAR(diff, -diag[k] * c.y[k], 4e-16 * (std::abs(c.ydot[k]) + std::abs(u.ydot[k])));
    }
  }
}

}  // namespace
}  // namespace sphark
