// Neighbour lists against brute force (open and periodic boxes, 1-3D), and Verlet-skin reuse.
#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "sphark/neighbours/neighbour_search.hpp"
#include "sphark/simd/dispatch.hpp"

#include "../support/random_points.hpp"

using namespace sphark;

namespace {
using test::random_points;

template <int D>
void expect_matches_brute_force(const NeighbourSearch<D>& ns, const std::vector<Real>& x, Real r) {
  const std::size_t n = x.size() / D;
  const auto& L = ns.list();
  ASSERT_EQ(L.particles(), n);
  std::size_t total = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::uint32_t> expect;
    for (std::size_t j = 0; j < n; ++j)
      if (j != i && ns.separation(x.data(), i, j).norm() < r) expect.push_back(static_cast<std::uint32_t>(j));
    std::vector<std::uint32_t> got(L.indices.begin() + L.begin(i), L.indices.begin() + L.end(i));
    ASSERT_EQ(got, expect) << "particle " << i;
    total += expect.size();
  }
  EXPECT_GT(total, n);  // the test is not vacuous
}

template <int D>
void check(bool periodic) {
  const auto x = random_points<D>(D == 1 ? 200 : 600, 42 + D);
  const Real r = D == 1 ? 0.03 : D == 2 ? 0.08 : 0.17;
  std::optional<PeriodicBox<D>> box;
  if (periodic) {
    PeriodicBox<D> b;
    b.periodic.fill(true);
    box = b;
  }
  NeighbourSearch<D> ns(box);
  ns.build(x.data(), x.size() / D, r);
  expect_matches_brute_force(ns, x, r);
}
}  // namespace

TEST(NeighbourSearch, MatchesBruteForceOpen) {
  check<1>(false);
  check<2>(false);
  check<3>(false);
}

TEST(NeighbourSearch, MatchesBruteForcePeriodic) {
  check<1>(true);
  check<2>(true);
  check<3>(true);
}

// rows = k: the first k particles' rows are those of a full build (the others among their
// neighbours), the rest are empty; on 1 and 3 threads (the rows are split over the threads).
TEST(NeighbourSearch, RowsForTheFirstParticlesOnly) {
  const auto x = random_points<2>(600, 7);
  const std::size_t n = 600, k = 250;
  const Real r = 0.08;
  NeighbourSearch<2> full, part;
  full.build(x.data(), n, r);
  const int threads_before = omp_get_max_threads();
  for (int threads : {1, 3}) {
    omp_set_num_threads(threads);
    part.build(x.data(), n, r, nullptr, nullptr, k);
    const NeighbourList &F = full.list(), &P = part.list();
    ASSERT_EQ(P.particles(), n);
    std::size_t pairs = 0, beyond_k = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (i >= k) {
        EXPECT_EQ(P.count(i), 0u) << "particle " << i;
        continue;
      }
      const std::vector<std::uint32_t> got(P.indices.begin() + P.begin(i), P.indices.begin() + P.end(i)),
          want(F.indices.begin() + F.begin(i), F.indices.begin() + F.end(i));
      ASSERT_EQ(got, want) << "particle " << i << ", " << threads << " threads";
      pairs += got.size();
      for (std::uint32_t j : got) beyond_k += j >= k;
    }
    EXPECT_EQ(P.pairs(), pairs);
    EXPECT_GT(beyond_k, 0u);  // rows reach particles that have none of their own
  }
  omp_set_num_threads(threads_before);
}

TEST(NeighbourSearch, MixedPeriodicity) {
  const auto x = random_points<2>(500, 7);
  PeriodicBox<2> b;
  b.periodic = {true, false};
  NeighbourSearch<2> ns(b);
  ns.build(x.data(), 500, 0.1);
  expect_matches_brute_force(ns, x, 0.1);
}

TEST(NeighbourSearch, RejectsBoxShorterThanTwoRadii) {
  PeriodicBox<2> b;
  b.periodic = {true, true};
  NeighbourSearch<2> ns(b);
  const auto x = random_points<2>(10, 1);
  EXPECT_THROW(ns.build(x.data(), 10, 0.6), std::invalid_argument);
}

TEST(NeighbourSearch, SkinKeepsEveryPairWhileDisplacementBelowHalfSkin) {
  const Real r = 0.08, skin = 0.02;
  auto x = random_points<2>(800, 3);
  PeriodicBox<2> b;
  b.periodic = {true, true};
  NeighbourSearch<2> ns(b);
  ns.build(x.data(), 800, r + skin);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<Real> u(-1.0, 1.0);
  for (auto& v : x) v += 0.49 * skin / std::sqrt(2.0) * u(rng);  // |displacement| < skin/2
  ASSERT_LT(ns.max_displacement_since_build(x.data()), skin / 2);
  // every pair now within r must be in the (old) lists
  const auto& L = ns.list();
  for (std::size_t i = 0; i < 800; ++i)
    for (std::size_t j = 0; j < 800; ++j) {
      if (i == j || ns.separation(x.data(), i, j).norm() >= r) continue;
      const auto first = L.indices.begin() + L.begin(i), last = L.indices.begin() + L.end(i);
      EXPECT_TRUE(std::binary_search(first, last, static_cast<std::uint32_t>(j))) << i << "," << j;
    }
}

TEST(NeighbourSearch, QueryFindsPointsOfTheBuiltSet) {
  const auto x = random_points<3>(400, 5);
  NeighbourSearch<3> ns;
  ns.build(x.data(), 400, 0.2);
  const Vec<3> p(0.5, 0.5, 0.5);
  std::vector<std::uint32_t> got;
  ns.query(p, 0.25, got);
  std::vector<std::uint32_t> expect;
  for (std::uint32_t j = 0; j < 400; ++j)
    if ((Eigen::Map<const Vec<3>>(x.data() + 3 * j) - p).norm() < 0.25) expect.push_back(j);
  EXPECT_EQ(got, expect);
  EXPECT_FALSE(expect.empty());
}

TEST(NeighbourSearch, RebuildAndMoveKeepResultsExact) {
  auto x = random_points<2>(300, 21);
  NeighbourSearch<2> ns;
  ns.build(x.data(), 300, 0.1);
  NeighbourSearch<2> moved(std::move(ns));
  for (auto& v : x) v = 0.5 * v + 0.25;  // new positions, same object: rebuild reuses buffers
  moved.build(x.data(), 300, 0.1);
  expect_matches_brute_force(moved, x, 0.1);
  std::vector<std::uint32_t> got;
  moved.query(Vec<2>(0.5, 0.5), 0.05, got);
  for (auto j : got) EXPECT_LT((Eigen::Map<const Vec<2>>(x.data() + 2 * j) - Vec<2>(0.5, 0.5)).norm(), 0.05);
}

TEST(NeighbourSearch, ListsIndependentOfThreadCount) {
  const auto x = random_points<3>(2000, 11);
  PeriodicBox<3> b;
  b.periodic = {true, true, false};
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  NeighbourSearch<3> one(b);
  one.build(x.data(), 2000, 0.12);
  omp_set_num_threads(2);
  NeighbourSearch<3> two(b);
  two.build(x.data(), 2000, 0.12);
  omp_set_num_threads(saved);
  EXPECT_EQ(one.list().offsets, two.list().offsets);
  EXPECT_EQ(one.list().indices, two.list().indices);
  expect_matches_brute_force(two, x, 0.12);
}

TEST(NeighbourSearch, RebuildWithoutMorePairsAllocatesNothing) {
  auto x = random_points<2>(1000, 13);
  PeriodicBox<2> b;
  b.periodic = {true, true};
  NeighbourSearch<2> ns(b);
  ns.build(x.data(), 1000, 0.06);
  EXPECT_EQ(ns.allocations(), 1);
  const std::size_t pairs = ns.list().pairs();
  for (int k = 1; k <= 4; ++k) {
    for (std::size_t i = 0; i < x.size(); i += 2) x[i] += 0.1;  // a periodic translation: the same pairs
    ns.build(x.data(), 1000, 0.06);
    EXPECT_EQ(ns.list().pairs(), pairs);
  }
  EXPECT_EQ(ns.allocations(), 1);
  expect_matches_brute_force(ns, x, 0.06);
}

TEST(NeighbourSearch, PerParticleRadiiListPairsWithinTheLargerRadius) {
  const auto x = random_points<2>(800, 17);
  PeriodicBox<2> b;
  b.periodic = {true, true};
  std::vector<Real> radii(800);
  for (std::size_t i = 0; i < radii.size(); ++i) radii[i] = 0.03 + 0.05 * std::abs(std::sin(1.7 * i));
  NeighbourSearch<2> ns(b);
  ns.build(x.data(), 800, 0.08, nullptr, radii.data());
  std::size_t total = 0;
  for (std::size_t i = 0; i < 800; ++i) {
    std::vector<std::uint32_t> expect;
    for (std::size_t j = 0; j < 800; ++j)
      if (j != i && ns.separation(x.data(), i, j).norm() < std::max(radii[i], radii[j]))
        expect.push_back(static_cast<std::uint32_t>(j));
    const auto& L = ns.list();
    ASSERT_EQ(std::vector<std::uint32_t>(L.indices.begin() + L.begin(i), L.indices.begin() + L.end(i)), expect) << i;
    total += expect.size();
  }
  EXPECT_GT(total, 800u);
}

// Row i of `after` is row order[i] of `before`, its entries renamed (new i = old order[i]).
static void expect_renamed_rows(const NeighbourList& before, const std::vector<std::uint32_t>& order, const NeighbourList& after) {
  std::vector<std::uint32_t> inverse(order.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) inverse[order[i]] = i;
  for (std::size_t i = 0; i < order.size(); ++i) {
    std::vector<std::uint32_t> expect;
    for (std::size_t k = before.begin(order[i]); k < before.end(order[i]); ++k) expect.push_back(inverse[before.indices[k]]);
    ASSERT_EQ(std::vector<std::uint32_t>(after.indices.begin() + after.begin(i), after.indices.begin() + after.end(i)), expect)
        << i;
  }
}

// row_spans() after renumber: per particle, the least and largest index of itself and its row.
static void expect_row_spans(const NeighbourList& list, const std::vector<RowSpan>& spans) {
  ASSERT_EQ(spans.size(), list.particles());
  for (std::size_t i = 0; i < spans.size(); ++i) {
    RowSpan expect{static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i)};
    for (std::size_t k = list.begin(i); k < list.end(i); ++k) {
      expect.first = std::min(expect.first, list.indices[k]);
      expect.second = std::max(expect.second, list.indices[k]);
    }
    ASSERT_EQ(spans[i], expect) << i;
  }
}

TEST(NeighbourSearch, RenumberKeepsTheListsOfTheRenamedParticles) {
  const auto x = random_points<2>(500, 19);
  NeighbourSearch<2> ns;
  ns.build(x.data(), 500, 0.1);
  const NeighbourList before = ns.list();
  const std::vector<std::uint32_t> order = ns.cell_order();  // new i = old order[i]
  ns.renumber(order);
  expect_renamed_rows(before, order, ns.list());
  expect_row_spans(ns.list(), ns.row_spans());
  // the displacement check reads positions in the order before renumbering through `order`
  std::vector<Real> moved = x;
  EXPECT_EQ(ns.max_displacement_since_build(moved.data(), order.data()), 0.0);
  moved[2 * order[7] + 1] += 0.003;
  EXPECT_NEAR(ns.max_displacement_since_build(moved.data(), order.data()), 0.003, 1e-15);
}

// Sparse lists (fewer listed pairs than particles, e.g. smoothing lengths far too small): the
// renumbering writes exactly the list's entries (it wrote one per particle past the end before).
TEST(NeighbourSearch, RenumberOfSparseListsKeepsThemAndTheirLength) {
  const auto x = random_points<2>(500, 29);
  NeighbourSearch<2> ns;
  ns.build(x.data(), 500, 0.02);
  const NeighbourList before = ns.list();
  ASSERT_LT(before.indices.size(), 500u);
  ASSERT_GT(before.indices.size(), 0u);
  const std::vector<std::uint32_t> order = ns.cell_order();
  ns.renumber(order);
  EXPECT_EQ(ns.list().indices.size(), before.indices.size());
  expect_renamed_rows(before, order, ns.list());
}

// The cell scan's vector path (AVX2 where the CPU has it) lists the same pairs in the same order
// as the x86-64 baseline path: open and periodic axes, one radius and per-particle radii.
TEST(NeighbourSearch, ListsIndependentOfTheVectorPath) {
  const auto x = random_points<3>(2000, 23);
  std::vector<Real> radii(2000);
  for (std::size_t i = 0; i < radii.size(); ++i) radii[i] = 0.08 + 0.07 * std::abs(std::sin(1.3 * i));
  PeriodicBox<3> b;
  b.periodic = {true, false, true};
  const PairLoopSimd widest = widest_pair_loop_simd(), saved = pair_loop_simd();
  for (const Real* r : {static_cast<const Real*>(nullptr), static_cast<const Real*>(radii.data())}) {
    use_pair_loop_simd(PairLoopSimd::Sse2);
    NeighbourSearch<3> base(b);
    base.build(x.data(), 2000, 0.15, nullptr, r);
    use_pair_loop_simd(widest);
    NeighbourSearch<3> wide(b);
    wide.build(x.data(), 2000, 0.15, nullptr, r);
    EXPECT_EQ(base.list().offsets, wide.list().offsets);
    EXPECT_EQ(base.list().indices, wide.list().indices);
    EXPECT_GT(wide.list().pairs(), 2000u * 20);
    if (!r) expect_matches_brute_force(wide, x, 0.15);
  }
  use_pair_loop_simd(saved);
}

// With keys, each row ascends in key: rows shorter than the vectorised sort's threshold (2D) and
// longer (3D, ~100 per row) against brute force sorted by key.
template <int D>
void expect_rows_ascending_in_key(std::size_t n, Real r, std::size_t min_mean_row) {
  const auto x = random_points<D>(n, 29 + D);
  std::vector<std::uint32_t> key(n);
  for (std::size_t i = 0; i < n; ++i) key[i] = static_cast<std::uint32_t>((i * 7919u) % n);  // a permutation (n prime to 7919)
  NeighbourSearch<D> ns;
  ns.build(x.data(), n, r, key.data());
  const auto& L = ns.list();
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::uint32_t> expect;
    for (std::size_t j = 0; j < n; ++j)
      if (j != i && ns.separation(x.data(), i, j).norm() < r) expect.push_back(static_cast<std::uint32_t>(j));
    std::sort(expect.begin(), expect.end(), [&](std::uint32_t p, std::uint32_t q) { return key[p] < key[q]; });
    ASSERT_EQ(std::vector<std::uint32_t>(L.indices.begin() + L.begin(i), L.indices.begin() + L.end(i)), expect) << i;
  }
  EXPECT_GE(L.pairs(), min_mean_row * n);
}

TEST(NeighbourSearch, KeyedRowsAscendInKey) {
  expect_rows_ascending_in_key<2>(1000, 0.08, 15);   // ~20 per row: std::sort
  expect_rows_ascending_in_key<3>(1500, 0.3, 90);    // ~170 per row: the vectorised sort
}
