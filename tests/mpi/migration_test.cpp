// Migration: after moving every particle to its RCB owner, each rank holds exactly its
// domain's particles; the global set of ids is the original one, each once; every value of
// every particle arrived bit for bit (arrays and a field-major flat state); count is exact, mass
// and momentum agree to the rounding bound; bad input fails on every rank.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "mpi_env.hpp"
#include "particles.hpp"
#include "sphark/parallel/decomposition.hpp"
#include "sphark/parallel/migration.hpp"

namespace sphark {
namespace {

using testing::world;

// Deterministic per-particle values from the id: the same bits wherever the particle is.
Real value(std::int64_t id, int slot) {
  return std::sin(1.0 + 0.731 * double(id) + 0.377 * slot) * std::pow(10.0, slot % 5 - 2);
}

struct Local {  // one rank's particles: mass, velocity (2) arrays and a flat state x(2), v(2), rho
  std::vector<std::int64_t> ids;
  std::vector<Real> mass, vel, state;
  ParticleData data() {
    ParticleData d;
    d.ids = &ids;
    d.arrays = {{&mass, 1}, {&vel, 2}};
    d.states = {{&state, {2, 2, 1}}};
    d.mass.array = 0;
    d.velocity.state = 0;
    d.velocity.field = 1;
    d.dim = 2;
    return d;
  }
};

// Particles of the global set with i % P == rank (not where they belong).
Local initial_share(const testing::GlobalParticles<2>& g, bool all_on_rank0) {
  Local l;
  const std::size_t n = g.size();
  for (std::size_t i = 0; i < n; ++i)
    if (all_on_rank0 ? world().rank() == 0 : int(i % world().size()) == world().rank()) l.ids.push_back(std::int64_t(i));
  const std::size_t m = l.ids.size();
  l.state.resize(5 * m);
  for (std::size_t a = 0; a < m; ++a) {
    const std::int64_t id = l.ids[a];
    l.mass.push_back(1 + std::abs(value(id, 0)));
    l.vel.push_back(value(id, 1));
    l.vel.push_back(value(id, 2));
    l.state[2 * a] = g.x[2 * id], l.state[2 * a + 1] = g.x[2 * id + 1];
    l.state[2 * m + 2 * a] = value(id, 3), l.state[2 * m + 2 * a + 1] = value(id, 4);
    l.state[4 * m + a] = value(id, 5);
  }
  return l;
}

void check_migration(bool all_on_rank0) {
  const auto g = testing::make_particles<2>(2500, false, 0.05, 21);
  Local l = initial_share(g, all_on_rank0);
  const Decomposition<2> dec = partition_rcb<2>(world(), l.state.data(), nullptr, l.ids.size(), std::nullopt);
  std::vector<int> dest(l.ids.size());
  dec.owners(l.state.data(), l.ids.size(), dest.data());
  ParticleData d = l.data();
  const ConservedTotals before = conserved_totals(world(), d);
  ASSERT_NO_THROW(migrate(world(), dest, d));
  const ConservedTotals after = conserved_totals(world(), d);
  const std::size_t m = l.ids.size();
  std::size_t wrong_owner = 0, wrong_bits = 0;
  for (std::size_t a = 0; a < m; ++a) {
    const std::int64_t id = l.ids[a];
    wrong_owner += dec.owner(Vec<2>(l.state[2 * a], l.state[2 * a + 1])) != world().rank();
    const Real expected[7] = {g.x[2 * id], g.x[2 * id + 1], value(id, 3), value(id, 4), value(id, 5), value(id, 1), value(id, 2)};
    const Real got[7] = {l.state[2 * a], l.state[2 * a + 1], l.state[2 * m + 2 * a], l.state[2 * m + 2 * a + 1],
                         l.state[4 * m + a], l.vel[2 * a], l.vel[2 * a + 1]};
    for (int k = 0; k < 7; ++k) wrong_bits += std::bit_cast<std::uint64_t>(got[k]) != std::bit_cast<std::uint64_t>(expected[k]);
    wrong_bits += std::bit_cast<std::uint64_t>(l.mass[a]) != std::bit_cast<std::uint64_t>(1 + std::abs(value(id, 0)));
  }
  EXPECT_EQ(testing::global_sum(std::int64_t(wrong_owner)), 0);
  EXPECT_EQ(testing::global_sum(std::int64_t(wrong_bits)), 0);
  // The global multiset of ids: every id of 0..N-1 exactly once.
  const std::int64_t count = static_cast<std::int64_t>(m);
  const std::vector<std::int64_t> counts = world().allgather(&count, 1);
  std::int64_t most = *std::max_element(counts.begin(), counts.end());
  std::vector<std::int64_t> padded(l.ids);
  padded.resize(static_cast<std::size_t>(most), -1);
  std::vector<std::int64_t> all = world().allgather(padded.data(), padded.size());
  all.erase(std::remove(all.begin(), all.end(), -1), all.end());
  std::sort(all.begin(), all.end());
  ASSERT_EQ(all.size(), g.size());
  for (std::size_t i = 0; i < all.size(); ++i) EXPECT_EQ(all[i], std::int64_t(i));
  EXPECT_EQ(after.count, before.count);
  EXPECT_EQ(after.id_sum, before.id_sum);
  const Real bound = 2 * Real(g.size() + world().size()) * std::numeric_limits<Real>::epsilon();
  EXPECT_LE(std::abs(after.mass - before.mass), bound * before.abs_mass);
  for (int c = 0; c < 2; ++c) EXPECT_LE(std::abs(after.momentum[c] - before.momentum[c]), bound * before.abs_momentum[c]);
}

TEST(Migration, ToRcbOwnersFromRoundRobin) { check_migration(false); }
TEST(Migration, ToRcbOwnersFromOneRank) { check_migration(true); }

TEST(Migration, BadDestinationFailsOnEveryRank) {
  const auto g = testing::make_particles<2>(200, false, 0.05, 2);
  Local l = initial_share(g, false);
  std::vector<int> dest(l.ids.size(), 0);
  if (world().rank() == world().size() - 1 && !dest.empty()) dest[0] = world().size();  // no such rank
  ParticleData d = l.data();
  EXPECT_THROW(migrate(world(), dest, d), CollectiveError);
  EXPECT_EQ(l.ids.size(), dest.size());  // nothing moved
}

}  // namespace
}  // namespace sphark
