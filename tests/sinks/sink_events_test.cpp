// Sink particles in the SPMHD state (issue #15): a cold, converging, bound clump of gas whose
// densest particle is above rho_sink makes a sink at the next event; then gas inside the accretion
// radius is accreted. Each event keeps mass, linear momentum and angular momentum (orbital + spin)
// of gas + sinks to round-off and every surviving gas particle's state bit for bit; with sinks in
// the state the RHS still conserves momentum to round-off (sink-gas and sink-sink gravity).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "sphark/initial/spheres.hpp"
#include "sphark/sinks/sink_events.hpp"
#include "sphark/sinks/sink_run.hpp"

using namespace sphark;

namespace {
constexpr std::size_t kN = 400;

SpmhdOptions sink_options() {
  SpmhdOptions o;
  o.self_gravity = true;
  o.gravity_solver = GravitySolver::Direct;
  o.sink_particles = true;
  o.alpha_u = 0;
  return o;
}

// A cold clump with rho ~ 1/r in the ball of radius 0.1 (the stretched lattice of
// initial/spheres.hpp: the densest particle sits at the potential minimum), converging
// (v = -x), slowly rotating about z.
ParticlePlacement clump() {
  SphereSpec spec;
  spec.particles = kN;
  spec.radius = 0.1;
  return evrard_sphere(spec);
}
std::vector<Real> clump_state(const SpmhdScheme<3>& s, const ParticlePlacement& place) {
  std::vector<Real> y(s.size(), 0);
  const StateLayout& L = s.layout();
  auto x = vector_field<3>(y.data(), L, Field::Position);
  auto v = vector_field<3>(y.data(), L, Field::Velocity);
  auto u = scalar_field(y.data(), L, Field::InternalEnergy);
  for (std::size_t a = 0; a < s.particles(); ++a) {
    x.col(a) = Eigen::Map<const Vec<3>>(place.x.data() + 3 * a);
    v.col(a) = -x.col(a) + Vec<3>(-0.2 * x(1, a), 0.2 * x(0, a), 0);
    u(a) = 1e-4;
  }
  return y;
}

struct Totals {
  Real mass = 0;
  Vec<3> momentum = Vec<3>::Zero(), angular = Vec<3>::Zero();
};
Totals totals(const SpmhdScheme<3>& s, const Real* y) {
  Totals t;
  const StateLayout& L = s.layout();
  const auto x = vector_field<3>(y, L, Field::Position), v = vector_field<3>(y, L, Field::Velocity);
  for (std::size_t a = 0; a < s.particles(); ++a) {
    const Real m = s.masses()[a];
    t.mass += m;
    t.momentum += m * v.col(a);
    t.angular += m * Vec<3>(x.col(a)).cross(Vec<3>(v.col(a)));
  }
  for (const Sink& k : sinks_of(s, y, 0)) {
    t.mass += k.mass;
    t.momentum += k.mass * k.v;
    t.angular += k.mass * k.x.cross(k.v) + k.spin;
  }
  return t;
}

// "To round-off": within the rounding bound of a sum of n terms, n eps times the sum of their
// magnitudes (mass: total mass; momentum: M |v|_max ~ M r_max ~ 0.1; angular momentum: M r_max^2).
void expect_same(const Totals& a, const Totals& b, std::size_t n) {
  const Real bound = static_cast<Real>(n) * std::numeric_limits<Real>::epsilon() * a.mass;
  EXPECT_NEAR(a.mass, b.mass, bound);
  EXPECT_LT((a.momentum - b.momentum).norm(), 0.2 * bound);
  EXPECT_LT((a.angular - b.angular).norm(), 0.02 * bound);
}
}  // namespace

TEST(SinkEvents, ACollapsedClumpMakesASinkThenFeedsItConservingEverything) {
  const ParticlePlacement place = clump();
  SpmhdScheme<3> s(std::vector<Real>(place.size(), place.particle_mass), sink_options());
  std::vector<Real> y = clump_state(s, place);
  std::vector<Real> ydot(y.size());
  ASSERT_EQ(s.rhs(0, y.data(), ydot.data()), 0) << s.last_error();
  Real rho_max = 0;
  for (Real r : s.rho()) rho_max = std::max(rho_max, r);
  SinkParams p;
  p.rho_sink = 0.5 * rho_max;
  p.accretion_radius = 0.08;  // 2 h ~ 0.05 at the centre
  SinkEventLog log;
  const Totals before = totals(s, y.data());
  std::optional<TimeLoopHooks::Resize> r = sink_events(s, 0, y.data(), p, log);
  ASSERT_TRUE(r.has_value()) << "refused: " << (log.refusals.empty() ? "-" : to_string(log.refusals.begin()->first));
  EXPECT_EQ(log.creations, 1);
  EXPECT_EQ(s.sinks(), 1u);
  EXPECT_LT(s.particles(), place.size());
  EXPECT_EQ(r->layout, s.layout());
  expect_same(before, totals(s, r->y.data()), place.size());
  // the RHS with a sink in the state conserves momentum (gas and sink) to round-off
  std::vector<Real> y1 = r->y, dy1(y1.size());
  ASSERT_EQ(s.rhs(0, y1.data(), dy1.data()), 0) << s.last_error();
  const StateLayout& L = s.layout();
  Vec<3> rate = Vec<3>::Zero();
  Real scale = 0;
  const auto dv = vector_field<3>(dy1.data(), L, Field::Velocity);
  for (std::size_t a = 0; a < s.particles(); ++a) {
    rate += s.masses()[a] * dv.col(a);
    scale += s.masses()[a] * dv.col(a).norm();
  }
  const Real M = y1[L.offset(Species::Sink, Field::Mass)];
  const Vec<3> a_sink = Eigen::Map<const Vec<3>>(dy1.data() + L.offset(Species::Sink, Field::Velocity));
  rate += M * a_sink;
  scale += M * a_sink.norm();
  EXPECT_LT(rate.norm(), 1e-14 * scale);
  // move the sink to a gas particle well inside the clump: it accretes the gas within 0.8 r_acc
  Eigen::Map<Vec<3>>(y1.data() + L.offset(Species::Sink, Field::Position)) =
      Eigen::Map<const Vec<3>>(y1.data() + L.offset(Field::Position) + 3 * 7);
  const Totals mid = totals(s, y1.data());
  const std::size_t gas_before = s.particles();
  const std::vector<Real> y_gas_before = y1;
  const StateLayout L_before = s.layout();
  std::optional<TimeLoopHooks::Resize> fed = sink_events(s, 0, y1.data(), p, log);
  ASSERT_TRUE(fed.has_value());
  EXPECT_LT(s.particles(), gas_before);
  EXPECT_GT(log.accreted_particles, 0);
  expect_same(mid, totals(s, fed->y.data()), place.size());
  // a particle far outside r_acc keeps its state bit for bit (the last one survives here)
  const std::size_t last_old = gas_before - 1, last_new = s.particles() - 1;
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(fed->y[s.layout().offset(Field::Position) + 3 * last_new + k],
              y_gas_before[L_before.offset(Field::Position) + 3 * last_old + k]);
    EXPECT_EQ(fed->y[s.layout().offset(Field::Velocity) + 3 * last_new + k],
              y_gas_before[L_before.offset(Field::Velocity) + 3 * last_old + k]);
  }
}

// A sink made inside a step (events_among_active; Phantom's check 3): a candidate is due exactly
// when a gas particle was denser than rho_sink at the last evaluation (sink_creation_due); the
// sink is made only when the candidate and every gas particle within r_acc of it are active,
// and then it is the sink sink_events makes, with the gas entries bit for bit where
// entry_source says and no source for the new sink's entries; otherwise nothing happens and
// no refusal is counted.
TEST(SinkEvents, ASinkIsMadeInsideAStepOnlyWhenItsWholeClumpIsActive) {
  const ParticlePlacement place = clump();
  SpmhdScheme<3> s(std::vector<Real>(place.size(), place.particle_mass), sink_options());
  std::vector<Real> y = clump_state(s, place), ydot(y.size());
  ASSERT_EQ(s.rhs(0, y.data(), ydot.data()), 0) << s.last_error();
  const Real rho_max = *std::max_element(s.rho().begin(), s.rho().end());
  SinkParams p;
  p.accretion_radius = 0.08;
  p.rho_sink = rho_max * (1 + 1e-12);
  EXPECT_FALSE(sink_creation_due(s, p));
  p.rho_sink = 0.5 * rho_max;
  EXPECT_TRUE(sink_creation_due(s, p));
  // the clump sink_events would make (on an identical scheme)
  SpmhdScheme<3> s2(std::vector<Real>(place.size(), place.particle_mass), sink_options());
  ASSERT_EQ(s2.rhs(0, y.data(), ydot.data()), 0) << s2.last_error();
  SinkEventLog log2;
  const std::optional<TimeLoopHooks::Resize> between = sink_events(s2, 0, y.data(), p, log2);
  ASSERT_TRUE(between.has_value());
  const StateLayout L = s.layout();
  const std::size_t gas = s.particles();
  std::vector<std::size_t> clump_members;  // the gas sink_events took
  std::vector<char> stays(gas, 0);
  for (std::size_t a = 0; a < s2.particles(); ++a) {  // survivors keep their positions bit for bit
    const Real* x = between->y.data() + between->layout.offset(Field::Position) + 3 * a;
    for (std::size_t b = 0; b < gas; ++b)
      if (std::memcmp(x, y.data() + L.offset(Field::Position) + 3 * b, 3 * sizeof(Real)) == 0) stays[b] = 1;
  }
  for (std::size_t b = 0; b < gas; ++b)
    if (!stays[b]) clump_members.push_back(b);
  ASSERT_GE(clump_members.size(), 2u);
  std::vector<std::size_t> all(gas);
  for (std::size_t a = 0; a < gas; ++a) all[a] = a;
  SinkEventLog log;
  // one member of the clump inactive: nothing, nothing counted
  std::vector<std::size_t> but_one;
  for (std::size_t a : all)
    if (a != clump_members.back()) but_one.push_back(a);
  EXPECT_FALSE(events_among_active(s, 0, y.data(), but_one, p, log).has_value());
  EXPECT_EQ(log.creations, 0);
  EXPECT_TRUE(log.refusals.empty());
  // all active: the sink sink_events makes
  const Totals before = totals(s, y.data());
  const std::optional<TimeLoopHooks::Resize> inside = events_among_active(s, 0, y.data(), all, p, log);
  ASSERT_TRUE(inside.has_value());
  EXPECT_EQ(log.creations, 1);
  EXPECT_EQ(inside->layout, between->layout);
  EXPECT_EQ(inside->y, between->y);
  expect_same(before, totals(s, inside->y.data()), gas);
  ASSERT_EQ(inside->entry_source.size(), inside->y.size());
  const std::size_t sink_first = inside->layout.offset(Species::Sink, Field::Position);
  for (std::size_t k = 0; k < inside->y.size(); ++k) {
    if (k < sink_first) {
      ASSERT_LT(inside->entry_source[k], y.size()) << k;
      ASSERT_EQ(inside->y[k], y[inside->entry_source[k]]) << k;
    } else {
      EXPECT_EQ(inside->entry_source[k], kNoEntrySource) << k;
    }
  }
}

// events_among_active (block steps: gas accreted at the events of its own steps): of the gas the sink
// would accrete, exactly the active particles go; mass, momentum and angular momentum carry over
// to round-off, and every gas entry of the new state is bit for bit the entry entry_source names
// (the sink's entries come from the sink's, with its new values).
namespace {
// The gas particles of `from` (before) that a removal took, from its entry_source.
std::vector<std::size_t> taken(const StateLayout& from, const TimeLoopHooks::Resize& r) {
  const std::size_t n = from.particles(), kept = r.layout.particles();
  std::vector<char> stays(n, 0);
  for (std::size_t a = 0; a < kept; ++a) {
    const std::size_t e = r.entry_source[r.layout.offset(Field::Position) + 3 * a];
    stays.at((e - from.offset(Field::Position)) / 3) = 1;
  }
  std::vector<std::size_t> out;
  for (std::size_t a = 0; a < n; ++a)
    if (!stays[a]) out.push_back(a);
  return out;
}
}  // namespace

// The clump with a sink made at its centre and moved onto gas particle 7 (the state).
std::vector<Real> clump_with_sink_on_gas(SpmhdScheme<3>& s, const ParticlePlacement& place, const SinkParams& p) {
  std::vector<Real> y = clump_state(s, place), ydot(y.size());
  if (s.rhs(0, y.data(), ydot.data()) != 0) throw std::runtime_error(s.last_error());
  SinkEventLog log;
  std::optional<TimeLoopHooks::Resize> made = sink_events(s, 0, y.data(), p, log);
  if (!made) throw std::runtime_error("no sink");
  std::vector<Real> y1 = made->y;
  const StateLayout& L = s.layout();
  Eigen::Map<Vec<3>>(y1.data() + L.offset(Species::Sink, Field::Position)) =
      Eigen::Map<const Vec<3>>(y1.data() + L.offset(Field::Position) + 3 * 7);
  return y1;
}

TEST(SinkEvents, AccretionAmongTheActiveTakesExactlyThemAndSaysWhereEveryEntryCameFrom) {
  const ParticlePlacement place = clump();
  SpmhdScheme<3> s(std::vector<Real>(place.size(), place.particle_mass), sink_options());
  SinkParams p;
  p.accretion_radius = 0.08;
  {
    std::vector<Real> y = clump_state(s, place), ydot(y.size());
    ASSERT_EQ(s.rhs(0, y.data(), ydot.data()), 0) << s.last_error();
    p.rho_sink = 0.5 * *std::max_element(s.rho().begin(), s.rho().end());
  }
  SpmhdScheme<3> s2(std::vector<Real>(place.size(), place.particle_mass), sink_options());
  const std::vector<Real> y1 = clump_with_sink_on_gas(s, place, p), y2 = clump_with_sink_on_gas(s2, place, p);
  ASSERT_EQ(y1, y2);
  const StateLayout L = s.layout();
  SinkEventLog log;
  const std::size_t gas = s.particles();
  std::vector<std::size_t> every(gas + 1), even;  // (+ the sink, the particle after the gas)
  for (std::size_t a = 0; a <= gas; ++a) every[a] = a;
  for (std::size_t a = 0; a <= gas; a += 2) even.push_back(a);
  even.push_back(gas);
  SinkEventLog unused;
  const std::optional<TimeLoopHooks::Resize> all = events_among_active(s2, 0, y2.data(), every, p, unused);
  ASSERT_TRUE(all.has_value());
  const std::vector<std::size_t> would = taken(L, *all);
  ASSERT_GE(would.size(), 4u);
  std::vector<std::size_t> expected;
  for (std::size_t a : would)
    if (a % 2 == 0) expected.push_back(a);
  ASSERT_LT(expected.size(), would.size());
  ASSERT_GT(expected.size(), 0u);
  const Totals before = totals(s, y1.data());
  const long accreted_before = log.accreted_particles;
  const std::optional<TimeLoopHooks::Resize> r = events_among_active(s, 0, y1.data(), even, p, log);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(taken(L, *r), expected);
  EXPECT_EQ(log.accreted_particles - accreted_before, static_cast<long>(expected.size()));
  EXPECT_EQ(r->layout, s.layout());
  expect_same(before, totals(s, r->y.data()), gas);
  ASSERT_EQ(r->entry_source.size(), r->y.size());
  const std::size_t sinks_new = r->layout.offset(Species::Sink, Field::Position), sinks_old = L.offset(Species::Sink, Field::Position);
  for (std::size_t k = 0; k < r->y.size(); ++k) {
    const std::size_t e = r->entry_source[k];
    ASSERT_LT(e, y1.size()) << k;
    if (k < sinks_new) {
      ASSERT_EQ(r->y[k], y1[e]) << k;
      ASSERT_LT(e, sinks_old) << k;
    } else {
      EXPECT_EQ(e - sinks_old, k - sinks_new) << k;
    }
  }
  // nothing active to take: nothing
  EXPECT_FALSE(events_among_active(s, 0, r->y.data(), {s.particles()}, p, log).has_value());
}
