// The multirate interface of the SPMHD scheme (issue #17): rhs_subset(A) and
// rhs_subset(complement of A) add up to rhs() bit for bit on a self-gravitating, magnetised,
// rotating clump with a sink particle (every term on); each is zero outside its set; the pair
// interactions split between them; particle_stable_dt is what max_stable_dt minimises, capped by
// 4 x the neighbours', and a sink's is the shortest gas step. At moved positions a subset
// solves the density of its rows' neighbourhood only, and its rows are the full rhs()'s bit for
// bit in velocity (the cleaning's global c_h aside, to round-off in B and psi); active_stable_dt
// is the limiter seen from the active particles.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "sphark/initial/spheres.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"
#include "../support/clump_state.hpp"
#include "../support/sink_clump.hpp"

namespace sphark {
namespace {

using test::Clump;
using test::clump;

TEST(SpmhdSubsets, TwoComplementarySubsetsAddUpToTheFullRhsBitForBit) {
  Clump c = clump();
  SpmhdScheme<3>& s = *c.scheme;
  ASSERT_TRUE(s.supports_subsets());
  const std::size_t np = s.num_particles();
  ASSERT_EQ(np, s.particles() + 1);  // gas, then the sink
  std::vector<std::size_t> a_set, b_set;
  for (std::size_t i = 0; i < np; ++i) (i % 3 == 1 || i == np - 1 ? a_set : b_set).push_back(i);
  std::vector<Real> full(c.y.size()), fa(c.y.size(), 7), fb(c.y.size(), 7);
  ASSERT_EQ(s.rhs(0, c.y.data(), full.data()), 0) << s.last_error();
  const std::size_t pairs_full = s.interacting_pairs();
  ASSERT_EQ(s.rhs_subset(0, c.y.data(), a_set, fa.data()), 0) << s.last_error();
  const std::size_t pairs_a = s.interacting_pairs();
  ASSERT_EQ(s.rhs_subset(0, c.y.data(), b_set, fb.data()), 0) << s.last_error();
  const std::size_t pairs_b = s.interacting_pairs();
  EXPECT_EQ(pairs_a + pairs_b, pairs_full);  // the rows split, none is computed twice
  EXPECT_LT(pairs_a, pairs_full / 2);
  const std::vector<std::size_t> owner = s.entry_particles();
  std::size_t nonzero = 0;
  for (std::size_t k = 0; k < c.y.size(); ++k) {
    const bool in_a = owner[k] % 3 == 1 || owner[k] == np - 1;
    EXPECT_EQ(in_a ? fb[k] : fa[k], 0.0) << "entry " << k << " outside its set";
    EXPECT_EQ(in_a ? fa[k] : fb[k], full[k]) << "entry " << k << " (particle " << owner[k] << ")";
    nonzero += full[k] != 0;
  }
  EXPECT_GT(nonzero, c.y.size() / 2);
}

TEST(SpmhdSubsets, ParticleStableStepsAreWhatMaxStableDtMinimises) {
  Clump c = clump();
  SpmhdScheme<3>& s = *c.scheme;
  const std::size_t v0 = s.layout().offset(Field::Velocity);
  for (int k = 0; k < 3; ++k) c.y[v0 + 3 * 5 + k] *= 300;  // particle 5: a short Courant step, its neighbours capped
  std::vector<Real> dt(s.num_particles());
  ASSERT_EQ(s.particle_stable_dt(0, c.y.data(), nullptr, dt.data()), 0) << s.last_error();
  const Real least = *std::min_element(dt.begin(), dt.end() - 1);
  EXPECT_EQ(dt.back(), least);  // the sink: the shortest gas step
  EXPECT_EQ(least, s.max_stable_dt(0, c.y.data(), nullptr));
  const Real most = *std::max_element(dt.begin(), dt.end() - 1);
  EXPECT_GT(most, least);
  // Each step is its own (Courant, force) capped by 4 x its neighbours' own ones.
  std::vector<Real> courant, force;
  ASSERT_EQ(s.stable_steps(0, c.y.data(), nullptr, courant, force), 0);
  const std::vector<Real> h = s.h(), x = s.positions();
  std::size_t capped = 0;
  for (std::size_t a = 0; a < s.particles(); ++a) {
    Real expected = std::min(courant[a], force[a]);
    for (std::size_t b = 0; b < s.particles(); ++b) {
      const Real r = (Eigen::Map<const Vec<3>>(&x[3 * a]) - Eigen::Map<const Vec<3>>(&x[3 * b])).norm();
      if (b != a && r < CubicSpline<3>::support * std::max(h[a], h[b]))
        expected = std::min(expected, 4 * std::min(courant[b], force[b]));
    }
    EXPECT_EQ(dt[a], expected) << "particle " << a;
    capped += expected < std::min(courant[a], force[a]);
  }
  std::printf("neighbour limiter: %zu of %zu particles capped, steps from %.3e to %.3e\n", capped, s.particles(),
              least, most);
  EXPECT_GT(capped, 0u);
}

// The clump's gas moved by a smooth displacement (a few per cent of h), as at a block event.
std::vector<Real> moved(const SpmhdScheme<3>& s, std::vector<Real> y) {
  const std::size_t x0 = s.layout().offset(Field::Position);
  for (std::size_t k = 0; k < 3 * s.particles(); ++k) y[x0 + k] += 2e-4 * std::sin(0.37 * static_cast<Real>(k));
  return y;
}

// The largest |a_k - b_k| over the entries k of the active particles, relative to max |b_k|.
Real relative_difference(const std::vector<Real>& a, const std::vector<Real>& b, const std::vector<std::size_t>& owner,
                         const std::vector<char>& is_active) {
  Real diff = 0, scale = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (is_active[owner[k]]) diff = std::max(diff, std::abs(a[k] - b[k])), scale = std::max(scale, std::abs(b[k]));
  return diff / scale;
}

TEST(SpmhdSubsets, AtMovedPositionsASubsetSolvesItsNeighbourhoodOnlyAndMatchesTheFullRhs) {
  Clump c = clump(), twin = clump();
  SpmhdScheme<3>& s = *c.scheme;
  const std::size_t n = s.particles(), np = s.num_particles();
  std::vector<Real> f(c.y.size()), full(c.y.size()), again(c.y.size());
  ASSERT_EQ(s.rhs(0, c.y.data(), f.data()), 0) << s.last_error();
  ASSERT_EQ(twin.scheme->rhs(0, twin.y.data(), f.data()), 0);
  const std::vector<Real> y = moved(s, c.y);
  std::vector<std::size_t> active;
  for (std::size_t i : {5, 140}) active.push_back(i);  // (in a clump of 287, 27 rows' neighbours cover it all)
  const long before = s.density_solves();
  ASSERT_EQ(s.rhs_subset(1e-3, y.data(), active, f.data()), 0) << s.last_error();
  const long subset_solves = s.density_solves() - before;
  ASSERT_EQ(twin.scheme->rhs(1e-3, y.data(), full.data()), 0);  // the same history, a full evaluation
  std::printf("%zu active of %zu: %ld density solves\n", active.size(), n, subset_solves);
  EXPECT_GT(subset_solves, static_cast<long>(10 * active.size()));  // the rows' neighbours too
  EXPECT_LT(subset_solves, static_cast<long>(n));
  const std::vector<std::size_t> owner = s.entry_particles();
  const StateLayout& L = s.layout();
  const auto in = [&](Field fld, std::size_t k) { return k >= L.offset(fld) && k < L.offset(fld) + L.components(Species::Gas, fld) * n; };
  std::vector<char> is_active(np, 0);
  for (std::size_t i : active) is_active[i] = 1;
  Real scale_b = 0;
  for (std::size_t k = 0; k < y.size(); ++k)
    if (in(Field::MagneticField, k) || in(Field::Psi, k)) scale_b = std::max(scale_b, std::abs(full[k]));
  for (std::size_t k = 0; k < y.size(); ++k) {
    if (!is_active[owner[k]]) {
      EXPECT_EQ(f[k], 0.0) << "entry " << k;
    } else if (in(Field::MagneticField, k) || in(Field::Psi, k)) {  // c_h: the unsolved slots' last fast speeds
      EXPECT_NEAR(f[k], full[k], 1e-9 * scale_b) << "entry " << k;
    } else {
      EXPECT_EQ(f[k], full[k]) << "entry " << k;
    }
  }
  // A full evaluation there solves the remaining slots only, and is then the twin's bit for bit.
  const long mid = s.density_solves();
  ASSERT_EQ(s.rhs(1e-3, y.data(), again.data()), 0);
  EXPECT_EQ(s.density_solves() - mid, static_cast<long>(n) - subset_solves);
  for (std::size_t k = 0; k < y.size(); ++k) ASSERT_EQ(again[k], full[k]) << "entry " << k;
}

// After a subset evaluation at moved positions: the active particles' steps are
// particle_stable_dt's; every other particle's is 4 x the least own step of the active ones within
// reach, and its own step where the evaluation solved its density (+inf elsewhere). A fixed c_h:
// the global one would take the unsolved particles' last fast speeds, and particle_stable_dt,
// which solves them all, other ones.
TEST(SpmhdSubsets, ActiveStableStepsBoundTheOthersByTheLimiterOfTheActiveOnes) {
  Clump c = clump(0, 2, 0, 1.0);
  SpmhdScheme<3>& s = *c.scheme;
  const std::size_t n = s.particles(), np = s.num_particles();
  const std::size_t v0 = s.layout().offset(Field::Velocity);
  for (int k = 0; k < 3; ++k) c.y[v0 + 3 * 7 + k] *= 300;  // particle 7: a short Courant step
  std::vector<Real> f(c.y.size()), all(np), dt(np);
  ASSERT_EQ(s.rhs(0, c.y.data(), f.data()), 0) << s.last_error();
  const std::vector<Real> rho_before = s.rho();
  const std::vector<Real> y = moved(s, c.y);
  const std::vector<std::size_t> active{3, 7, 150};
  ASSERT_EQ(s.rhs_subset(1e-3, y.data(), active, f.data()), 0) << s.last_error();
  std::vector<char> solved(n);  // the densities this evaluation solved
  for (std::size_t i = 0; i < n; ++i) solved[i] = s.rho()[i] != rho_before[i];
  ASSERT_EQ(s.active_stable_dt(1e-3, y.data(), f.data(), active, dt.data()), 0) << s.last_error();
  ASSERT_EQ(s.particle_stable_dt(1e-3, y.data(), f.data(), all.data()), 0);  // (solves the rest)
  std::vector<Real> courant, force;
  ASSERT_EQ(s.stable_steps(1e-3, y.data(), f.data(), courant, force), 0);
  const std::vector<Real> h = s.h(), x = s.positions();
  Real shortest = std::numeric_limits<Real>::infinity();
  for (std::size_t i : active) {
    EXPECT_EQ(dt[i], all[i]) << "active particle " << i;
    shortest = std::min(shortest, all[i]);
  }
  EXPECT_EQ(dt[np - 1], shortest);  // the sink: the shortest active gas step
  std::size_t bounded = 0, own = 0;
  for (std::size_t b = 0; b < n; ++b) {
    if (std::binary_search(active.begin(), active.end(), b)) continue;
    Real bound = std::numeric_limits<Real>::infinity();
    for (std::size_t a : active) {
      const Real r = (Eigen::Map<const Vec<3>>(&x[3 * a]) - Eigen::Map<const Vec<3>>(&x[3 * b])).norm();
      if (r < CubicSpline<3>::support * std::max(h[a], h[b])) bound = std::min(bound, 4 * std::min(courant[a], force[a]));
    }
    bounded += std::isfinite(bound);
    if (solved[b]) bound = std::min(bound, std::min(courant[b], force[b])), ++own;
    EXPECT_EQ(dt[b], bound) << "particle " << b;
  }
  std::printf("%zu particles bounded by %zu active ones, %zu by their own solved steps\n", bounded, active.size(), own);
  EXPECT_GT(bounded, 4 * active.size());
  EXPECT_GT(own, bounded / 2);
  EXPECT_LT(own + active.size(), n);  // some are beyond every active particle's reach
}

// The limiter reads the interacting neighbours of the last subset force pass, and only at that
// pass's state: after an evaluation at y1, active_stable_dt at y2 (each particle moved by up to a
// tenth of an h, so that pairs enter each other's reach) bounds each active particle by its
// neighbours within reach at y2, and caps each of those (brute force), not those at y1.
TEST(SpmhdSubsets, TheLimiterReadsTheForcePassRowsOnlyAtTheirState) {
  Clump c = clump(0, 2, 0, 1.0);
  SpmhdScheme<3>& s = *c.scheme;
  const std::size_t np = s.num_particles(), x0 = s.layout().offset(Field::Position);
  const std::size_t v0 = s.layout().offset(Field::Velocity);
  for (int k = 0; k < 3; ++k) c.y[v0 + 3 * 7 + k] *= 300;  // particle 7: a short step, which bounds its neighbours
  std::vector<Real> f(c.y.size()), dt(np), courant, force;
  ASSERT_EQ(s.rhs(0, c.y.data(), f.data()), 0) << s.last_error();
  const std::vector<Real> y1 = moved(s, c.y);
  std::vector<Real> y2 = y1;
  const Real h0 = s.h()[0];
  for (std::size_t k = 0; k < 3 * s.particles(); ++k) y2[x0 + k] += 0.1 * h0 * std::sin(1.3 * static_cast<Real>(k));
  const std::vector<std::size_t> active{3, 7, 150};
  const auto within_reach = [&](std::size_t a, std::size_t b) {
    const std::vector<Real>&x = s.positions(), &h = s.h();
    const Real r = (Eigen::Map<const Vec<3>>(&x[3 * a]) - Eigen::Map<const Vec<3>>(&x[3 * b])).norm();
    return b != a && r < CubicSpline<3>::support * std::max(h[a], h[b]);
  };
  ASSERT_EQ(s.rhs_subset(1e-3, y1.data(), active, f.data()), 0) << s.last_error();
  std::vector<std::vector<char>> reach_at_y1;
  for (std::size_t a : active) {
    reach_at_y1.emplace_back(s.particles());
    for (std::size_t b = 0; b < s.particles(); ++b) reach_at_y1.back()[b] = within_reach(a, b);
  }
  ASSERT_EQ(s.active_stable_dt(2e-3, y2.data(), f.data(), active, dt.data()), 0) << s.last_error();
  ASSERT_EQ(s.stable_steps(2e-3, y2.data(), f.data(), courant, force), 0);  // (the same state: no solve)
  std::size_t entered = 0, capped_on_entering = 0;
  for (std::size_t i = 0; i < active.size(); ++i)  // the others within reach at y2: capped by the active one
    for (std::size_t b = 0; b < s.particles(); ++b) {
      const Real cap = 4 * std::min(courant[active[i]], force[active[i]]);
      if (std::binary_search(active.begin(), active.end(), b) || !within_reach(active[i], b)) continue;
      EXPECT_LE(dt[b], cap) << "particle " << b << " near active " << active[i];
      capped_on_entering += !reach_at_y1[i][b] && std::min(courant[b], force[b]) > cap;
    }
  EXPECT_GT(capped_on_entering, 0u);  // some entered the reach of the short-stepping one
  for (std::size_t i = 0; i < active.size(); ++i) {
    const std::size_t a = active[i];
    Real least = std::numeric_limits<Real>::infinity();
    for (std::size_t b = 0; b < s.particles(); ++b)
      if (within_reach(a, b)) least = std::min(least, std::min(courant[b], force[b])), entered += !reach_at_y1[i][b];
    EXPECT_EQ(dt[a], std::min(std::min(courant[a], force[a]), 4 * least)) << "active particle " << a;
  }
  EXPECT_GT(entered, 0u);  // the test can tell the two states' rows apart
}

// Two clumps a unit apart (no gravity), then mirrored through the origin (x -> -x: every
// distance, so every density, exactly as it was; the clumps trade places in the cell grid's
// order, so the slots are renumbered). A subset of one clump solves its neighbourhood only; the
// other clump's particles keep their own densities, and the subset's rows are the full rhs()'s.
TEST(SpmhdSubsets, AfterTheSlotsAreRenumberedTheUnsolvedParticlesKeepTheirOwnDensities) {
  SphereSpec spec;
  spec.particles = 200;
  spec.radius = 0.1;
  ParticlePlacement place = evrard_sphere(spec);
  const std::size_t half = place.size();
  for (std::size_t a = 0; a < half; ++a)
    for (int k = 0; k < 3; ++k) place.x.push_back(place.x[3 * a + k] + (k == 0 ? 1.0 : 0.0));
  const std::size_t n = place.size();
  SpmhdOptions o;
  o.cleaning = Cleaning::Constrained;
  SpmhdScheme<3> s(std::vector<Real>(n, place.particle_mass), o), twin(std::vector<Real>(n, place.particle_mass), o);
  std::vector<Real> y(s.size(), 0), f(s.size()), full(s.size());
  test::fill_clump_gas(place, s.layout(), y);
  ASSERT_EQ(s.rhs(0, y.data(), f.data()), 0) << s.last_error();
  ASSERT_EQ(twin.rhs(0, y.data(), f.data()), 0);
  const std::vector<Real> rho_before = s.rho();
  const std::size_t x0 = s.layout().offset(Field::Position);
  for (std::size_t k = 0; k < 3 * n; ++k) y[x0 + k] = -y[x0 + k];
  const std::vector<std::size_t> active{5, 140};  // in the first clump
  const long before = s.density_solves();
  ASSERT_EQ(s.rhs_subset(1e-3, y.data(), active, f.data()), 0) << s.last_error();
  const std::size_t solved = static_cast<std::size_t>(s.density_solves() - before);
  EXPECT_LT(solved, half);
  const std::vector<Real> rho_subset = s.rho();
  for (std::size_t i = 0; i < n; ++i) EXPECT_NEAR(rho_subset[i], rho_before[i], 1e-9 * rho_before[i]) << "particle " << i;
  ASSERT_EQ(twin.rhs(1e-3, y.data(), full.data()), 0);
  std::vector<char> is_active(n, 0);
  for (std::size_t i : active) is_active[i] = 1;
  const Real diff = relative_difference(f, full, s.entry_particles(), is_active);
  std::printf("%zu of %zu solved; active rows within %.2e of the full rhs\n", solved, n, diff);
  EXPECT_LT(diff, 1e-12);
}

// The state of `s` (after change_particles(kept, sinks)) holding the gas particles `kept` of the
// state y of `before` and its sinks.
std::vector<Real> kept_state(const StateLayout& before, const std::vector<Real>& y, const SpmhdScheme<3>& s,
                             const std::vector<std::size_t>& kept) {
  const StateLayout& L = s.layout();
  std::vector<Real> out(s.size(), 0);
  for (Field f : L.fields(Species::Gas)) {
    const int comps = L.components(Species::Gas, f);
    for (std::size_t i = 0; i < kept.size(); ++i)
      for (int k = 0; k < comps; ++k) out[L.offset(f) + comps * i + k] = y[before.offset(f) + comps * kept[i] + k];
  }
  const std::size_t sink0 = L.offset(Species::Sink, Field::Position), old0 = before.offset(Species::Sink, Field::Position);
  std::copy(y.begin() + static_cast<std::ptrdiff_t>(old0), y.end(), out.begin() + static_cast<std::ptrdiff_t>(sink0));
  return out;
}

// Particles removed between evaluations (accretion): the others keep their slots, lists and last
// solves, so the next evaluation builds no lists; its derivatives equal those of a scheme that
// built its lists afresh (the density solve does not depend on the lists' reach) bit for bit.
TEST(SpmhdSubsets, RemovedParticlesLeaveTheOthersListsAndTheSameDerivatives) {
  Clump c = clump(), twin = clump();
  SpmhdScheme<3>& s = *c.scheme;
  std::vector<Real> f(c.y.size());
  ASSERT_EQ(s.rhs(0, c.y.data(), f.data()), 0) << s.last_error();
  ASSERT_EQ(twin.scheme->rhs(0, twin.y.data(), f.data()), 0);
  const std::vector<std::size_t> first_and_sink = {0, s.num_particles() - 1};
  ASSERT_EQ(s.rhs_subset(0, c.y.data(), first_and_sink, f.data()), 0);  // (its per-layout scratch made)
  const StateLayout before = s.layout();
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < s.particles(); ++i)
    if (i != 3 && i != 40 && i != 41 && i != 200) kept.push_back(i);
  s.change_particles(kept, 1);
  twin.scheme->drop_neighbour_lists();  // the other way: everything afresh
  twin.scheme->change_particles(kept, 1);
  const std::vector<Real> y = kept_state(before, c.y, s, kept);
  std::vector<Real> fs(y.size()), ft(y.size());
  const long builds = s.neighbour_builds(), twin_builds = twin.scheme->neighbour_builds();
  ASSERT_EQ(s.rhs(1e-3, y.data(), fs.data()), 0) << s.last_error();
  ASSERT_EQ(twin.scheme->rhs(1e-3, y.data(), ft.data()), 0) << twin.scheme->last_error();
  EXPECT_EQ(s.neighbour_builds(), builds);  // the lists carried over
  EXPECT_EQ(twin.scheme->neighbour_builds(), twin_builds + 1);
  for (std::size_t k = 0; k < y.size(); ++k) ASSERT_EQ(fs[k], ft[k]) << "entry " << k;
  // Subsets of the new layout (the sink among them) still split rhs() bit for bit.
  std::vector<std::size_t> odd, even;
  for (std::size_t i = 0; i < s.num_particles(); ++i) (i % 2 ? odd : even).push_back(i);
  std::vector<Real> fo(y.size()), fe(y.size());
  ASSERT_EQ(s.rhs_subset(1e-3, y.data(), odd, fo.data()), 0) << s.last_error();
  ASSERT_EQ(s.rhs_subset(1e-3, y.data(), even, fe.data()), 0) << s.last_error();
  const std::vector<std::size_t> owner = s.entry_particles();
  for (std::size_t k = 0; k < y.size(); ++k) {
    EXPECT_EQ((owner[k] % 2 ? fe : fo)[k], 0.0) << "entry " << k << " outside its set";
    ASSERT_EQ((owner[k] % 2 ? fo : fe)[k], fs[k]) << "entry " << k;
  }
}

}  // namespace
}  // namespace sphark
