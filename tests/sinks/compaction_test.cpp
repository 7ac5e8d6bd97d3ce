// Removing particles from SoA fields: the survivors keep their values bit for bit and their
// order; bad removal lists are refused.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <stdexcept>
#include <vector>

#include "sphark/core/compaction.hpp"

using namespace sphark;

TEST(Compaction, SurvivorsKeepTheirValuesBitForBit) {
  const std::size_t n = 1000;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<Real> U(-1e3, 1e3);
  std::vector<Real> pos(3 * n), rho(n);
  std::vector<std::uint32_t> id(n);
  for (auto& p : pos) p = U(rng);
  for (auto& r : rho) r = U(rng) * 1e-20;  // values across the range, subnormal-adjacent included
  for (std::size_t a = 0; a < n; ++a) id[a] = static_cast<std::uint32_t>(7 * a + 1);
  std::vector<std::uint32_t> removed;
  for (std::uint32_t a = 0; a < n; ++a)
    if (rng() % 5 == 0 || a == 0 || a == n - 1) removed.push_back(a);
  const std::vector<Real> pos0 = pos, rho0 = rho;
  const std::vector<std::uint32_t> id0 = id;
  compact(pos, 3, removed);
  compact(rho, 1, removed);
  compact(id, 1, removed);
  const std::vector<std::uint32_t> kept = surviving_indices(n, removed);
  ASSERT_EQ(kept.size(), n - removed.size());
  ASSERT_EQ(rho.size(), kept.size());
  ASSERT_EQ(pos.size(), 3 * kept.size());
  for (std::size_t i = 0; i < kept.size(); ++i) {
    EXPECT_EQ(std::memcmp(&pos[3 * i], &pos0[3 * kept[i]], 3 * sizeof(Real)), 0) << i;
    EXPECT_EQ(std::memcmp(&rho[i], &rho0[kept[i]], sizeof(Real)), 0) << i;
    EXPECT_EQ(id[i], id0[kept[i]]);
    if (i > 0) {
      EXPECT_LT(kept[i - 1], kept[i]);
    }
  }
}

TEST(Compaction, NothingAndEverything) {
  std::vector<Real> f = {1, 2, 3, 4};
  compact(f, 2, {});
  EXPECT_EQ(f, (std::vector<Real>{1, 2, 3, 4}));
  EXPECT_EQ(compact_field(f.data(), 2, 2, {0, 1}), 0u);
  compact(f, 2, {0, 1});
  EXPECT_TRUE(f.empty());
}

TEST(Compaction, RefusesBadRemovalLists) {
  std::vector<Real> f(10, 1.0);
  EXPECT_THROW(compact(f, 1, {3, 3}), std::invalid_argument);   // duplicate
  EXPECT_THROW(compact(f, 1, {4, 2}), std::invalid_argument);   // not ascending
  EXPECT_THROW(compact(f, 1, {10}), std::invalid_argument);     // out of range
  EXPECT_THROW(compact(f, 3, {0}), std::invalid_argument);      // size not a multiple of 3
  EXPECT_EQ(f.size(), 10u);
}
