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

// SinkRunSupport::event_due (what makes block steps synchronise, StepperOptions::synchronise):
// true exactly when a gas particle is denser than rho_sink at the last evaluation or the sinks
// would accrete one (inside the accretion radius and bound to the sink).
TEST(SinkEvents, AnEventIsDueExactlyWhenACandidateOrGasToAccreteExists) {
  const ParticlePlacement place = clump();
  SpmhdScheme<3> s(std::vector<Real>(place.size(), place.particle_mass), sink_options());
  std::vector<Real> y = clump_state(s, place), ydot(y.size());
  ASSERT_EQ(s.rhs(0, y.data(), ydot.data()), 0) << s.last_error();
  const Real rho_max = *std::max_element(s.rho().begin(), s.rho().end());
  SinkParams p;
  p.accretion_radius = 0.08;
  p.rho_sink = rho_max * (1 + 1e-12);
  EXPECT_FALSE(SinkRunSupport(p).event_due(s, y.data()));
  p.rho_sink = rho_max * (1 - 1e-12);
  EXPECT_TRUE(SinkRunSupport(p).event_due(s, y.data()));
  SinkEventLog log;
  std::optional<TimeLoopHooks::Resize> r = sink_events(s, 0, y.data(), p, log);
  ASSERT_TRUE(r.has_value());
  std::vector<Real> y1 = r->y, dy1(y1.size());
  ASSERT_EQ(s.rhs(0, y1.data(), dy1.data()), 0) << s.last_error();
  p.rho_sink = 2 * rho_max;  // no candidate any more: only accretion can be due
  const StateLayout& L = s.layout();
  Eigen::Map<Vec<3>> sink_x(y1.data() + L.offset(Species::Sink, Field::Position));
  sink_x = Eigen::Map<const Vec<3>>(y1.data() + L.offset(Field::Position) + 3 * 7);  // on a gas particle
  EXPECT_TRUE(SinkRunSupport(p).event_due(s, y1.data()));
  Real nearest = std::numeric_limits<Real>::infinity();
  sink_x = Vec<3>(0.3, 0, 0);  // outside the clump (radius 0.1)
  for (std::size_t a = 0; a < s.particles(); ++a)
    nearest = std::min(nearest, (Eigen::Map<const Vec<3>>(y1.data() + L.offset(Field::Position) + 3 * a) - Vec<3>(sink_x)).norm());
  p.accretion_radius = nearest * (1 - 1e-12);
  EXPECT_FALSE(SinkRunSupport(p).event_due(s, y1.data()));
  p.accretion_radius = nearest * (1 + 1e-12);
  EXPECT_TRUE(SinkRunSupport(p).event_due(s, y1.data()));
  Eigen::Map<Vec<3>>(y1.data() + L.offset(Species::Sink, Field::Velocity)) = Vec<3>(100, 0, 0);  // unbound: not accreted
  EXPECT_FALSE(SinkRunSupport(p).event_due(s, y1.data()));
}
