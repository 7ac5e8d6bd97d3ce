// The distributed design on a real SPH operator (sph_demo.hpp): 100 fixed steps of a periodic
// 2D flow of 576 particles on 1-4 ranks (ERK and leapfrog), with RCB repartitioning, migration every 10 steps (conservation checked
// by migrate()), Stepper::resize after each, the halo plan kept while valid, and the density
// and forces through two exchanges per RHS. Every field of every particle, matched by global
// id, equals the serial run's to <= 1e-12 relative (by construction bit for bit).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <array>
#include <map>

#include "mpi_env.hpp"
#include "sph_demo.hpp"
#include "sphark/integrate/stepper.hpp"
#include "sphark/parallel/decomposition.hpp"
#include "sphark/parallel/migration.hpp"

namespace sphark {
namespace {

using testing::SphDemo;
using testing::world;

constexpr int kSide = 24;
constexpr Real kDt = 5e-4;

PeriodicBox<2> unit_periodic() {
  PeriodicBox<2> b;
  b.periodic = {true, true};
  return b;
}

// Particle k of the global set: lattice position, a smooth swirl plus a shear, h and mass
// varying in space.
struct Initial {
  Vec<2> x, v;
  Real m, h;
};
Initial initial(std::int64_t k) {
  const Real dx = 1.0 / kSide, two_pi = 2 * kPi;
  const Real px = (Real(k % kSide) + 0.5) * dx, py = (Real(k / kSide) + 0.5) * dx;
  return {Vec<2>(px, py),
          Vec<2>(2.0 * std::sin(two_pi * py) + 0.3, -2.0 * std::sin(two_pi * px)),
          dx * dx * (1 + 0.1 * std::cos(two_pi * py)),
          1.3 * dx * (1 + 0.15 * std::sin(two_pi * px))};
}

struct Outcome {
  std::map<std::int64_t, std::array<Real, 5>> fields;  // x, y, vx, vy, rho by id
  long steps = 0;
  std::size_t migrated = 0, halo = 0;  // particles moved between ranks after the first step; halo size
  long plan_builds = 0, exchanges = 0, rhs_evals = 0;
};

// This rank's particles and state (x..., v...) for the ids given.
void load(SphDemo& sys, std::vector<Real>& y, const std::vector<std::int64_t>& ids) {
  std::vector<Real> m, h;
  const std::size_t n = ids.size();
  y.assign(4 * n, 0.0);
  for (std::size_t a = 0; a < n; ++a) {
    const Initial p = initial(ids[a]);
    y[2 * a] = p.x[0], y[2 * a + 1] = p.x[1], y[2 * n + 2 * a] = p.v[0], y[2 * n + 2 * a + 1] = p.v[1];
    m.push_back(p.m);
    h.push_back(p.h);
  }
  sys.set_particles(ids, m, h);
}

// Moves every particle to its owner (RCB, recomputed when repartition), with mass, h, state
// and (leapfrog) the carried next-kick derivative; then hands the new state to the stepper.
std::size_t migrate_and_resize(const Communicator& c, SphDemo& sys, std::vector<Real>& y, Stepper& stepper,
                               Decomposition<2>& dec, bool repartition) {
  const std::size_t n = sys.count();
  if (repartition) dec = partition_rcb<2>(c, y.data(), nullptr, n, unit_periodic());
  std::vector<int> owner(n);
  dec.owners(y.data(), n, owner.data());
  std::vector<std::int64_t> ids = sys.ids();
  std::vector<Real> m = sys.mass(), h = sys.smoothing_length(), carried = stepper.carried_data();
  ParticleData d;
  d.ids = &ids;
  d.arrays = {{&m, 1}, {&h, 1}};
  d.states = {{&y, {2, 2}}};
  if (!carried.empty()) d.states.push_back({&carried, {2, 2}});
  d.mass.array = 0;
  d.velocity.state = 0;
  d.velocity.field = 1;
  d.dim = 2;
  const MigrationStats stats = migrate(c, owner, d);
  sys.set_particles(std::move(ids), std::move(m), std::move(h));
  stepper.resize({y.data(), nullptr, carried.empty() ? nullptr : carried.data()});
  return stats.sent;
}

Outcome run(const Communicator& c, const std::string& method) {
  SphDemo sys(c, unit_periodic(), {});
  std::vector<std::int64_t> ids;
  for (std::int64_t k = c.rank(); k < kSide * kSide; k += c.size()) ids.push_back(k);  // scattered start
  std::vector<Real> y;
  load(sys, y, ids);
  StepperOptions o;
  o.method = method;
  o.fixed_dt = kDt;
  o.communicator = c;
  auto stepper = make_stepper(sys, o, 0.0, y.data());
  Decomposition<2> dec(unit_periodic());
  Outcome out;
  if (c.size() > 1) migrate_and_resize(c, sys, y, *stepper, dec, true);  // scattered start to RCB domains
  Real t = 0;
  for (int k = 1; k <= 10; ++k) {
    stepper->advance(10 * k * kDt, y.data(), t);
    if (c.size() > 1 && k < 10) out.migrated += migrate_and_resize(c, sys, y, *stepper, dec, k == 5);
  }
  out.halo = sys.halo().halo();
  out.plan_builds = sys.halo().stats().builds;  // since the last migration (a new plan each time)
  out.exchanges = sys.halo().stats().exchanges;
  out.rhs_evals = stepper->stats().rhs_evals;
  std::vector<Real> ydot(y.size());
  EXPECT_EQ(sys.rhs(t, y.data(), ydot.data()), 0);  // collective; fills the densities
  const std::vector<Real> rho = sys.density();
  const std::size_t n = sys.count();
  for (std::size_t a = 0; a < n; ++a)
    out.fields[sys.ids()[a]] = {y[2 * a], y[2 * a + 1], y[2 * n + 2 * a], y[2 * n + 2 * a + 1], rho[a]};
  out.steps = stepper->stats().steps;
  return out;
}

void check_demo(const std::string& method) {
  const Outcome serial = run(Communicator{}, method), dist = run(world(), method);
  Real worst = 0;
  std::size_t missing = 0;
  for (const auto& [id, f] : dist.fields) {
    const auto it = serial.fields.find(id);
    if (it == serial.fields.end()) {
      ++missing;
      continue;
    }
    for (int k = 0; k < 5; ++k) worst = std::max(worst, std::abs(f[k] - it->second[k]) / std::max(1.0, std::abs(it->second[k])));
  }
  worst = testing::global_max(worst);
  EXPECT_EQ(testing::global_sum(std::int64_t(missing)), 0);
  EXPECT_EQ(testing::global_sum(std::int64_t(dist.fields.size())), kSide * kSide);
  EXPECT_LE(worst, 1e-12) << method;
  EXPECT_EQ(dist.steps, 100);
  EXPECT_EQ(serial.steps, 100);
  const std::int64_t migrated = testing::global_sum(std::int64_t(dist.migrated));
  const std::int64_t halo = testing::global_sum(std::int64_t(dist.halo));
  if (world().size() > 1) {
    EXPECT_GT(migrated, 0);
    EXPECT_GT(halo, 0);
  }
  if (world().rank() == 0)
    std::printf("%s on %d ranks: max relative difference to serial %.3g, %lld particles migrated after the start, "
                "halo %lld; rank 0: %ld rhs, %ld plan builds and %ld exchanges (builds' id exchange included)\n",
                method.c_str(), world().size(), worst, static_cast<long long>(migrated), static_cast<long long>(halo),
                dist.rhs_evals, dist.plan_builds, dist.exchanges);
}

TEST(SphDemo, ErkMatchesSerialOnEveryRankCount) { check_demo("ARKODE_BOGACKI_SHAMPINE_4_2_3"); }
TEST(SphDemo, LeapfrogMatchesSerialOnEveryRankCount) { check_demo("leapfrog"); }

}  // namespace
}  // namespace sphark
