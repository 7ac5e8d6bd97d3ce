// Accretion onto sinks (BBP95 sec. 2.2.3): inside 0.8 r_acc unconditionally; in the annulus
// only bound, most bound to this sink and below the angular momentum of a circular orbit at
// r_acc; mass, momentum and angular momentum (orbital + spin) of gas + sinks conserved to
// round-off; the gas order does not change the outcome.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "sphark/sinks/sink_accretion.hpp"

using namespace sphark;

namespace {
struct Gas {
  std::vector<Real> x, v, m;
  void add(Vec<3> p, Vec<3> w, Real mass) {
    x.insert(x.end(), {p[0], p[1], p[2]});
    v.insert(v.end(), {w[0], w[1], w[2]});
    m.push_back(mass);
  }
  GasView view() const {
    GasView g;
    g.n = m.size(), g.x = x.data(), g.v = v.data(), g.mass = m.data();
    return g;
  }
};

Sink make_sink(Vec<3> x, Vec<3> v, Real mass, Real r_acc, Vec<3> spin = Vec<3>::Zero()) {
  Sink s;
  s.x = x, s.v = v, s.mass = mass, s.accretion_radius = r_acc, s.spin = spin;
  return s;
}

struct Totals {
  Real mass = 0, scale = 0;
  Vec<3> momentum = Vec<3>::Zero(), angular = Vec<3>::Zero();
};

// gas (all, or without `removed`) + sinks
Totals totals(const Gas& g, const std::vector<Sink>& sinks, const std::vector<std::uint32_t>& removed = {}) {
  Totals t;
  std::vector<bool> gone(g.m.size(), false);
  for (std::uint32_t a : removed) gone[a] = true;
  const GasView v = g.view();
  for (std::size_t a = 0; a < g.m.size(); ++a) {
    if (gone[a]) continue;
    t.mass += g.m[a];
    t.momentum += g.m[a] * v.velocity(a);
    t.angular += g.m[a] * v.position(a).cross(v.velocity(a));
    t.scale += g.m[a] * v.position(a).norm() * v.velocity(a).norm();
  }
  for (const Sink& s : sinks) {
    t.mass += s.mass;
    t.momentum += s.mass * s.v;
    t.angular += s.mass * s.x.cross(s.v) + s.spin;
    t.scale += s.mass * s.x.norm() * s.v.norm() + s.spin.norm();
  }
  return t;
}
}  // namespace

TEST(SinkAccretion, TheRulesOfBbp95) {
  SinkParams p;
  const std::vector<Sink> sinks = {make_sink(Vec<3>::Zero(), Vec<3>::Zero(), 1.0, 1.0)};
  Gas g;
  g.add({0.5, 0, 0}, {10, 0, 0}, 1e-3);   // 0: inside 0.8 r_acc, unbound and fast: accreted
  g.add({0, 0.9, 0}, {0, -0.1, 0}, 1e-3);  // 1: annulus, bound, radial: accreted
  g.add({0, 0, 0.9}, {0, 0, 2.0}, 1e-3);   // 2: annulus, unbound (escape speed 1.49): kept
  g.add({0.9, 0, 0}, {0, 1.3, 0}, 1e-3);   // 3: annulus, bound (e = -0.27) but j^2 = 1.37 > G M r_acc: kept
  g.add({0.9, 0, 0}, {0, 1.05, 0}, 1e-3);  // 4: annulus, bound, j^2 = 0.89 < 1: accreted
  g.add({1.1, 0, 0}, {0, 0, 0}, 1e-3);     // 5: outside r_acc: kept
  const std::vector<long> expected = {0, 0, -1, -1, 0, -1};
  for (std::size_t a = 0; a < expected.size(); ++a) EXPECT_EQ(accreting_sink(g.view(), a, sinks, p), expected[a]) << a;
  const SinkUpdate up = accrete(g.view(), sinks, p);
  EXPECT_EQ(up.removed, (std::vector<std::uint32_t>{0, 1, 4}));
  EXPECT_EQ(up.accreted_by, (std::vector<std::uint32_t>{0, 0, 0}));
}

TEST(SinkAccretion, MostBoundSinkTakesAnnulusGasAndInnerGasGoesToTheNearest) {
  SinkParams p;
  const std::vector<Sink> sinks = {make_sink({0, 0, 0}, Vec<3>::Zero(), 1.0, 1.0),
                                   make_sink({1.8, 0, 0}, Vec<3>::Zero(), 3.0, 1.0)};
  Gas g;
  g.add({0.9, 0, 0}, Vec<3>::Zero(), 1e-3);       // annulus of both; e = -1.11 vs -3.33: sink 1
  g.add({0.85, 0.1, 0}, {0.6, 0, 0}, 1e-3);       // annulus of both (0.856, 0.955); e = -0.99 vs -2.96: sink 1
  g.add({0.75, 0, 0}, {0, 0, 0}, 1e-3);           // inside 0.8 r_acc of A, annulus of B: A (no checks)
  g.add({-0.85, 0, 0}, {0, 0.2, 0}, 1e-3);        // annulus of A only: A
  EXPECT_EQ(accreting_sink(g.view(), 0, sinks, p), 1);
  EXPECT_EQ(accreting_sink(g.view(), 1, sinks, p), 1);
  EXPECT_EQ(accreting_sink(g.view(), 2, sinks, p), 0);
  EXPECT_EQ(accreting_sink(g.view(), 3, sinks, p), 0);
  // most bound to B but with too much angular momentum about B: nobody takes it
  Gas h;
  h.add({0.9, 0, 0}, {0, 1.9, 0}, 1e-3);  // about B: e = 1.8 - 3.33 < 0 (and A: unbound), j^2 = 2.9 < 3: B
  h.add({0.9, 0, 0}, {0, 2.2, 0}, 1e-3);  // about B: e = 2.42 - 3.33 < 0, j^2 = 3.9 > G M r_acc = 3: kept
  EXPECT_EQ(accreting_sink(h.view(), 0, sinks, p), 1);
  EXPECT_EQ(accreting_sink(h.view(), 1, sinks, p), -1);
}

TEST(SinkAccretion, ConservesMassMomentumAndAngularMomentumToRoundOff) {
  SinkParams p;
  std::mt19937_64 rng(5);
  std::normal_distribution<Real> N(0, 1);
  std::uniform_real_distribution<Real> U(-1, 1);
  const Vec<3> offset(12, -7, 3);
  std::vector<Sink> sinks = {make_sink(offset + Vec<3>(0, 0, 0), {0.3, -0.2, 0.1}, 2.0, 0.6, {0.01, 0.02, 0.5}),
                             make_sink(offset + Vec<3>(1.5, 0.2, 0), {-0.3, 0.4, 0}, 1.0, 0.5, {0, 0, -0.2})};
  Gas g;
  for (int a = 0; a < 4000; ++a) {
    const Vec<3> pos = offset + Vec<3>(0.75, 0.1, 0) + Vec<3>(U(rng), U(rng), U(rng)) * 1.6;
    g.add(pos, Vec<3>(N(rng), N(rng), N(rng)) * 0.8, 1e-3 * (1 + 0.5 * U(rng)));
  }
  const Totals before = totals(g, sinks);
  const SinkUpdate up = accrete(g.view(), sinks, p);
  ASSERT_GT(up.removed.size(), 100u);
  ASSERT_EQ(up.removed.size(), up.accreted_by.size());
  const Totals after = totals(g, up.sinks, up.removed);
  EXPECT_NEAR(after.mass, before.mass, 1e-15 * before.mass);
  EXPECT_LT((after.momentum - before.momentum).norm(), 1e-15 * before.scale);
  EXPECT_LT((after.angular - before.angular).norm(), 1e-15 * before.scale)
      << (after.angular - before.angular).transpose() << " scale " << before.scale;
  // the spins changed (the orbital angular momentum of the gas went in)
  EXPECT_GT((up.sinks[0].spin - sinks[0].spin).norm(), 1e-3 * sinks[0].spin.norm());
  RecordProperty("accreted", std::to_string(up.removed.size()));
}

TEST(SinkAccretion, GasOrderDoesNotChangeTheOutcome) {
  SinkParams p;
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<Real> U(-1, 1);
  const std::vector<Sink> sinks = {make_sink(Vec<3>::Zero(), Vec<3>::Zero(), 1.0, 0.7)};
  Gas g;
  for (int a = 0; a < 500; ++a) g.add(Vec<3>(U(rng), U(rng), U(rng)), Vec<3>(U(rng), U(rng), U(rng)), 1e-3);
  Gas r;  // reversed order
  for (int a = 499; a >= 0; --a) r.add(g.view().position(a), g.view().velocity(a), g.m[a]);
  const SinkUpdate ug = accrete(g.view(), sinks, p), ur = accrete(r.view(), sinks, p);
  ASSERT_EQ(ug.removed.size(), ur.removed.size());
  for (std::size_t k = 0; k < ug.removed.size(); ++k) EXPECT_EQ(ug.removed[k], 499 - ur.removed[ur.removed.size() - 1 - k]);
  const Sink &a = ug.sinks[0], &b = ur.sinks[0];
  EXPECT_NEAR(a.mass, b.mass, 1e-15);
  EXPECT_LT((a.x - b.x).norm(), 1e-15);
  EXPECT_LT((a.v - b.v).norm(), 1e-15);
  EXPECT_LT((a.spin - b.spin).norm(), 1e-16);
}
