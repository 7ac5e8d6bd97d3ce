// The whole state of a distributed run (parallel/global_state.hpp), as checkpoints hold it: each
// rank's particles, dealt out in a scrambled order, gathered on rank 0 into the field-major
// state by global id, bit for bit; share_of takes any rank's share back out of it, bit
// for bit; ids that are not 0 .. N-1 each once are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "mpi_env.hpp"
#include "sphark/parallel/global_state.hpp"

namespace sphark {
namespace {

using testing::world;

constexpr std::size_t kParticles = 37;
const std::vector<int> kComponents = {2, 2, 1};  // x, v, rho

StateLayout whole_layout() {
  StateLayout L(kParticles);
  L.add(Field::Position, 2).add(Field::Velocity, 2).add(Field::Density, 1);
  return L;
}

Real value(std::size_t id, int field, int k) { return std::sin(0.3 + 1.7 * double(id) + 0.61 * field + 0.2 * k); }

// The field-major state of every particle, particle k = id k.
std::vector<Real> whole_state() {
  std::vector<Real> y;
  for (int f = 0; f < 3; ++f)
    for (std::size_t id = 0; id < kParticles; ++id)
      for (int k = 0; k < kComponents[f]; ++k) y.push_back(value(id, f, k));
  return y;
}

// This rank's ids: every P-th of a scrambled order of 0 .. N-1 (37 is prime: 11 id mod 37 visits each once).
std::vector<std::int64_t> my_ids() {
  std::vector<std::int64_t> ids;
  for (std::size_t i = static_cast<std::size_t>(world().rank()); i < kParticles; i += static_cast<std::size_t>(world().size()))
    ids.push_back(static_cast<std::int64_t>((11 * i) % kParticles));
  return ids;
}

TEST(GlobalState, GatheredOnRankZeroByIdAndSelectedBack) {
  const std::vector<Real> all = whole_state();
  const std::vector<std::int64_t> ids = my_ids();
  const std::vector<Real> mine = share_of(whole_layout(), all, ids);
  ASSERT_EQ(mine.size(), ids.size() * 5);
  for (std::size_t i = 0; i < ids.size(); ++i)  // field 1 (v), component 1 of particle i
    EXPECT_EQ(mine[2 * ids.size() + 2 * i + 1], value(static_cast<std::size_t>(ids[i]), 1, 1));
  const std::vector<Real> gathered = gather_particles(world(), ids, mine, kComponents);
  const bool wrong = world().rank() == 0 ? gathered != all : !gathered.empty();
  EXPECT_EQ(testing::ranks_failing(wrong), 0);
}

TEST(GlobalState, RefusesIdsThatAreNotEachParticleOnce) {
  std::vector<std::int64_t> ids = my_ids();
  if (world().rank() == 0) ids[0] = ids.size() > 1 ? ids[1] : 0;  // rank 0: an id twice (or 0 twice with others)
  const std::vector<Real> mine(ids.size() * 5, 1.0);
  bool threw = false;
  try {
    gather_particles(world(), ids, mine, kComponents);
  } catch (const std::runtime_error&) {
    threw = true;
  }
  EXPECT_EQ(threw, world().rank() == 0);
  EXPECT_THROW(share_of(whole_layout(), whole_state(), {std::int64_t(kParticles)}), std::invalid_argument);
  EXPECT_THROW(share_of(whole_layout(), whole_state(), {-1}), std::invalid_argument);
  EXPECT_THROW(share_of(whole_layout().with_count(Species::Gas, kParticles + 1), whole_state(), {0}),
               std::invalid_argument);
}

}  // namespace
}  // namespace sphark
