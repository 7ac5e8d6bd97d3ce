// Eq. (9) of seed 000 (the tensile-instability correction) left out for gas near a sink
// (SpmhdOptions::tensile_sink_exclusion), on the self-gravitating magnetised clump with a sink:
//  - a radius beyond every gas particle: the RHS conserves momentum to round-off, as the scheme
//    without the correction does (the correction is the only non-conservative term);
//  - a radius covering some: the particles outside it have their derivatives bit for bit, those
//    inside differ, the momentum budget's tensile part is what the RHS injects, and the
//    injection the exclusion removes is the change of the RHS's momentum rate;
//  - radius 0: the scheme as before, bit for bit;
//  - weighted by plasma beta (Phantom's switch): each particle's acceleration is the one without
//    the correction plus its weight (1 below beta_full, 0 above beta_none, linear between) times
//    the whole correction, and the budget still accounts for all the injection.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sphark/schemes/spmhd/spmhd_scheme.hpp"
#include "../support/sink_clump.hpp"

using namespace sphark;

namespace {

struct Evaluated {
  std::vector<Real> ydot;
  Vec<3> rate = Vec<3>::Zero();  // sum of m dv/dt over gas and sinks
  Real scale = 0;                // sum of |m dv/dt|
  SpmhdScheme<3>::MomentumBudget budget;
};

Evaluated evaluate(test::Clump& c) {
  SpmhdScheme<3>& s = *c.scheme;
  Evaluated e;
  e.ydot.assign(s.size(), 0);
  EXPECT_EQ(s.rhs(0, c.y.data(), e.ydot.data()), 0) << s.last_error();
  const StateLayout& L = s.layout();
  const std::size_t n = L.particles(Species::Gas), ns = L.particles(Species::Sink);
  const auto add = [&](Real m, const Real* a) {
    const Vec<3> f = m * Eigen::Map<const Vec<3>>(a);
    e.rate += f;
    e.scale += f.norm();
  };
  for (std::size_t a = 0; a < n; ++a) add(s.masses()[a], &e.ydot[L.offset(Field::Velocity) + 3 * a]);
  for (std::size_t k = 0; k < ns; ++k)
    add(c.y[L.offset(Species::Sink, Field::Mass) + k], &e.ydot[L.offset(Species::Sink, Field::Velocity) + 3 * k]);
  e.budget = s.momentum_budget(0, c.y.data());
  return e;
}

// Gas particle a's distance to the sink.
Real sink_distance(const test::Clump& c, std::size_t a) {
  const StateLayout& L = c.scheme->layout();
  return (Eigen::Map<const Vec<3>>(&c.y[L.offset(Field::Position) + 3 * a]) -
          Eigen::Map<const Vec<3>>(&c.y[L.offset(Species::Sink, Field::Position)]))
      .norm();
}

}  // namespace

TEST(TensileExclusion, EveryGasParticleExcludedConservesMomentum) {
  test::Clump with = test::clump(), without = test::clump(10.0);  // the clump's radius is 0.1
  const Evaluated a = evaluate(with), b = evaluate(without);
  ASSERT_GT(a.rate.norm(), 1e-10 * a.scale);  // the correction injects momentum here (measured 7e-9)
  EXPECT_LT(b.rate.norm(), 1e-13 * b.scale);
  EXPECT_EQ(b.budget.tensile.norm(), 0);
  EXPECT_LT((a.budget.total - a.rate).norm(), 1e-13 * a.scale);
}

TEST(TensileExclusion, OnlyTheParticlesInsideTheRadiusChange) {
  const Real radius = 0.04;
  test::Clump all = test::clump(), near = test::clump(radius), zero = test::clump(0.0);
  const Evaluated a = evaluate(all), b = evaluate(near), z = evaluate(zero);
  EXPECT_EQ(a.ydot, z.ydot);  // radius 0: the scheme as before
  const StateLayout& L = all.scheme->layout();
  std::size_t inside = 0, changed = 0;
  for (std::size_t p = 0; p < L.particles(Species::Gas); ++p) {
    const bool in = sink_distance(all, p) < radius;
    inside += in;
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = L.offset(Field::Velocity) + 3 * p + k;
      if (!in) {
        EXPECT_EQ(a.ydot[i], b.ydot[i]) << p;
      }
      changed += in && a.ydot[i] != b.ydot[i];
    }
  }
  std::printf("%zu of %zu gas particles within %.2f of the sink\n", inside, L.particles(Species::Gas), radius);
  EXPECT_GT(inside, 0u);
  EXPECT_LT(inside, L.particles(Species::Gas));
  EXPECT_GT(changed, 0u);
  // the budget follows the RHS: what eq. (9) injects is the whole non-conservation
  EXPECT_LT((b.budget.total - b.rate).norm(), 1e-13 * b.scale);
  EXPECT_LT((b.budget.total - b.budget.tensile).norm(), 1e-12 * b.scale);
  // what leaving eq. (9) out near the sink removes from the injection is what it removes from the
  // RHS's momentum rate
  EXPECT_GT((a.budget.tensile - b.budget.tensile).norm(), 1e-3 * a.budget.tensile.norm());
  EXPECT_LT(((a.budget.tensile - b.budget.tensile) - (a.rate - b.rate)).norm(), 1e-13 * a.scale);
}

namespace {
// Plasma beta 2P/|B|^2 of each gas particle of the clump, in particle order.
std::vector<Real> plasma_beta(const test::Clump& c) {
  const StateLayout& L = c.scheme->layout();
  const std::vector<Real>& P = c.scheme->pressure();
  std::vector<Real> beta(L.particles(Species::Gas));
  for (std::size_t a = 0; a < beta.size(); ++a)
    beta[a] = 2 * P[a] / Eigen::Map<const Vec<3>>(&c.y[L.offset(Field::MagneticField) + 3 * a]).squaredNorm();
  return beta;
}
}  // namespace

TEST(TensileBetaSwitch, EachParticleGetsItsShareOfTheCorrection) {
  test::Clump whole = test::clump();
  const Evaluated a = evaluate(whole);
  std::vector<Real> beta = plasma_beta(whole), sorted = beta;
  std::sort(sorted.begin(), sorted.end());
  // the ramp between the quartiles: a quarter of the particles whole, a half weighted, a quarter none
  const Real full = sorted[sorted.size() / 4], none = sorted[3 * sorted.size() / 4];
  ASSERT_LT(full, none);
  test::Clump weighted = test::clump(0, full, none), without = test::clump(10.0);
  const Evaluated w = evaluate(weighted), o = evaluate(without);
  const StateLayout& L = whole.scheme->layout();
  std::size_t ramped = 0;
  for (std::size_t p = 0; p < beta.size(); ++p) {
    const Real share = beta[p] < full ? 1.0 : beta[p] < none ? (none - beta[p]) / (none - full) : 0.0;
    ramped += share > 0 && share < 1;
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = L.offset(Field::Velocity) + 3 * p + k;
      const Real expected = o.ydot[i] + share * (a.ydot[i] - o.ydot[i]);
      EXPECT_NEAR(w.ydot[i], expected, 1e-12 * (std::abs(a.ydot[i]) + std::abs(o.ydot[i]))) << p;
    }
  }
  EXPECT_GT(ramped, beta.size() / 4);
  EXPECT_GT((w.rate - a.rate).norm(), 1e-3 * a.rate.norm());  // the switch changes the injection
  EXPECT_LT((w.budget.total - w.rate).norm(), 1e-13 * w.scale);
  EXPECT_LT((w.budget.total - w.budget.tensile).norm(), 1e-12 * w.scale);
}
