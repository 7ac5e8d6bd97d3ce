// KdTreeNeighbourSearch: the lists against brute force (1-3D, open, periodic and mixed boxes,
// uniform and per-particle radii with the max(r_i, r_j) rule), identical to the cell grid's
// (rows, order, key sort) on uniform data and on a collapse-like distribution whose radii span
// 100x, independent of the thread count, and the grid's other duties: queries, renumbering,
// the Verlet-skin displacement, allocation-free rebuilds, refusing too short periodic boxes.
#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "sphark/neighbours/kd_tree_search.hpp"
#include "sphark/neighbours/neighbour_search.hpp"

#include "../support/random_points.hpp"

using namespace sphark;

namespace {
using test::random_points;

template <int D>
std::optional<PeriodicBox<D>> unit_box(std::array<bool, D> periodic) {
  PeriodicBox<D> b;
  b.periodic = periodic;
  return b;
}

// every row against the O(n^2) definition: j != i with |x_i - x_j| < max(r_i, r_j)
template <int D>
void expect_matches_brute_force(const KdTreeNeighbourSearch<D>& kd, const std::vector<Real>& x,
                                const std::vector<Real>& radii) {
  const std::size_t n = x.size() / D;
  const NeighbourList& L = kd.list();
  ASSERT_EQ(L.particles(), n);
  std::size_t total = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::uint32_t> expect;
    for (std::size_t j = 0; j < n; ++j)
      if (j != i && kd.separation(x.data(), i, j).norm() < std::max(radii[i], radii[j]))
        expect.push_back(static_cast<std::uint32_t>(j));
    ASSERT_EQ(std::vector<std::uint32_t>(L.indices.begin() + L.begin(i), L.indices.begin() + L.end(i)), expect) << i;
    total += expect.size();
  }
  EXPECT_GT(total, n);  // not vacuous
}

template <int D>
void check_brute_force(std::array<bool, D> periodic, bool variable) {
  const std::size_t n = D == 1 ? 300 : 700;
  const auto x = random_points<D>(n, 40 + D);
  const Real r = D == 1 ? 0.02 : D == 2 ? 0.07 : 0.15;
  std::vector<Real> radii(n, r);
  if (variable)
    for (std::size_t i = 0; i < n; ++i) radii[i] = r * (0.3 + 0.7 * std::abs(std::sin(1.3 * i)));
  KdTreeNeighbourSearch<D> kd(unit_box<D>(periodic));
  kd.build(x.data(), n, r, nullptr, variable ? radii.data() : nullptr);
  expect_matches_brute_force(kd, x, radii);
}

// a sphere with rho ~ 1 / (1 + r^2 / rc^2) (contrast 1e6: radii span 100x) in sparse ambient gas
std::vector<Real> collapse_like(std::size_t n, std::vector<Real>& radii, Real& r_max) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<Real> U(0, 1);
  const Real rc = 1e-3;
  std::vector<Real> x;
  radii.clear();
  while (radii.size() < n) {
    Vec<3> p;
    Real rho;
    if (radii.size() % 5 == 0) {  // ambient
      p = Vec<3>(4 * U(rng) - 2, 4 * U(rng) - 2, 4 * U(rng) - 2);
      if (p.norm() < 1) continue;
      rho = 1.0 / 30;
    } else {  // r ~ M(<r) inverted for rho ~ 1/(rc^2 + r^2) at large r, with a core
      const Real r = std::pow(U(rng), 2.0) + 1e-4, mu = 2 * U(rng) - 1, ph = 2 * kPi * U(rng);
      p = r * Vec<3>(std::sqrt(1 - mu * mu) * std::cos(ph), std::sqrt(1 - mu * mu) * std::sin(ph), mu);
      rho = (1 + rc * rc) / (rc * rc + r * r);
    }
    x.insert(x.end(), {p[0], p[1], p[2]});
    radii.push_back(0.08 * std::cbrt(1 / rho));
  }
  r_max = *std::max_element(radii.begin(), radii.end());
  return x;
}
}  // namespace

TEST(KdTreeNeighbourSearch, MatchesBruteForceOpenPeriodicAndMixed) {
  check_brute_force<1>({false}, false);
  check_brute_force<1>({true}, true);
  check_brute_force<2>({false, false}, false);
  check_brute_force<2>({true, true}, true);
  check_brute_force<2>({true, false}, true);
  check_brute_force<3>({false, false, false}, true);
  check_brute_force<3>({true, true, true}, false);
  check_brute_force<3>({true, false, true}, true);
}

TEST(KdTreeNeighbourSearch, SameListsAsTheCellGridOnAUniformLattice) {
  const int nx = 20;
  std::vector<Real> x;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<Real> jitter(-0.05 / nx, 0.05 / nx);
  for (int k = 0; k < nx; ++k)
    for (int j = 0; j < nx; ++j)
      for (int i = 0; i < nx; ++i)
        x.insert(x.end(), {(i + 0.5) / nx + jitter(rng), (j + 0.5) / nx + jitter(rng), (k + 0.5) / nx + jitter(rng)});
  const std::size_t n = x.size() / 3;
  std::vector<std::uint32_t> key(n);
  for (std::size_t a = 0; a < n; ++a) key[a] = static_cast<std::uint32_t>((a * 7919) % n);  // a permutation
  const auto box = unit_box<3>({true, true, true});
  const Real r = 2 * 1.2 * 1.25 / nx;
  NeighbourSearch<3> grid(box);
  KdTreeNeighbourSearch<3> kd(box);
  const std::uint32_t* no_key = nullptr;
  for (const std::uint32_t* k : {no_key, static_cast<const std::uint32_t*>(key.data())}) {
    grid.build(x.data(), n, r, k);
    kd.build(x.data(), n, r, k);
    EXPECT_EQ(kd.list().offsets, grid.list().offsets);
    EXPECT_EQ(kd.list().indices, grid.list().indices);
  }
  EXPECT_GT(grid.list().pairs(), 100 * n);
}

TEST(KdTreeNeighbourSearch, SameListsAsTheCellGridWhenRadiiSpanDecades) {
  std::vector<Real> radii;
  Real r_max = 0;
  const std::vector<Real> x = collapse_like(6000, radii, r_max);
  const auto [lo, hi] = std::minmax_element(radii.begin(), radii.end());
  ASSERT_GT(*hi / *lo, 100.0);
  NeighbourSearch<3> grid;
  KdTreeNeighbourSearch<3> kd;
  grid.build(x.data(), radii.size(), r_max, nullptr, radii.data());
  kd.build(x.data(), radii.size(), r_max, nullptr, radii.data());
  EXPECT_EQ(kd.list().offsets, grid.list().offsets);
  EXPECT_EQ(kd.list().indices, grid.list().indices);
  expect_matches_brute_force(kd, x, radii);
}

TEST(KdTreeNeighbourSearch, ListsIndependentOfThreadCount) {
  std::vector<Real> radii;
  Real r_max = 0;
  const std::vector<Real> x = collapse_like(4000, radii, r_max);
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  KdTreeNeighbourSearch<3> one;
  one.build(x.data(), radii.size(), r_max, nullptr, radii.data());
  omp_set_num_threads(2);
  KdTreeNeighbourSearch<3> two;
  two.build(x.data(), radii.size(), r_max, nullptr, radii.data());
  omp_set_num_threads(saved);
  EXPECT_EQ(one.list().offsets, two.list().offsets);
  EXPECT_EQ(one.list().indices, two.list().indices);
}

TEST(KdTreeNeighbourSearch, QueryRenumberAndDisplacement) {
  const auto x = random_points<3>(600, 5);
  const auto box = unit_box<3>({true, true, true});
  KdTreeNeighbourSearch<3> kd(box);
  kd.build(x.data(), 600, 0.2);
  // query: every built point within 0.15 of p (minimum image), ascending
  const Vec<3> p(0.95, 0.02, 0.5);
  std::vector<std::uint32_t> got, expect;
  kd.query(p, 0.15, got);
  for (std::uint32_t j = 0; j < 600; ++j)
    if (box->minimum_image(p - Eigen::Map<const Vec<3>>(x.data() + 3 * j)).norm() < 0.15) expect.push_back(j);
  EXPECT_EQ(got, expect);
  EXPECT_FALSE(expect.empty());
  EXPECT_THROW(kd.query(p, 0.3, got), std::invalid_argument);  // beyond the build radius, periodic
  // renumber in tree order: row i is old row order[i], renamed
  const NeighbourList before = kd.list();
  const std::vector<std::uint32_t> order = kd.cell_order();
  kd.renumber(order);
  std::vector<std::uint32_t> inverse(600);
  for (std::uint32_t i = 0; i < 600; ++i) inverse[order[i]] = i;
  std::vector<Real> y(x.size());
  for (std::size_t i = 0; i < 600; ++i)
    for (int k = 0; k < 3; ++k) y[3 * i + k] = x[3 * order[i] + k];
  for (std::size_t i = 0; i < 600; ++i) {
    std::vector<std::uint32_t> row;
    for (std::size_t k = before.begin(order[i]); k < before.end(order[i]); ++k) row.push_back(inverse[before.indices[k]]);
    ASSERT_EQ(std::vector<std::uint32_t>(kd.list().indices.begin() + kd.list().begin(i),
                                         kd.list().indices.begin() + kd.list().end(i)),
              row);
  }
  ASSERT_EQ(kd.row_spans().size(), 600u);  // per row: the least and largest of itself and its entries
  for (std::size_t i = 0; i < 600; ++i) {
    RowSpan expect{static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i)};
    for (std::size_t k = kd.list().begin(i); k < kd.list().end(i); ++k) {
      expect.first = std::min(expect.first, kd.list().indices[k]);
      expect.second = std::max(expect.second, kd.list().indices[k]);
    }
    ASSERT_EQ(kd.row_spans()[i], expect) << i;
  }
  EXPECT_EQ(kd.max_displacement_since_build(y.data()), 0.0);
  y[3 * 17] += 0.01;
  EXPECT_NEAR(kd.max_displacement_since_build(y.data()), 0.01, 1e-15);
}

TEST(KdTreeNeighbourSearch, RebuildWithoutMorePairsAllocatesNothing) {
  auto x = random_points<2>(1000, 13);
  KdTreeNeighbourSearch<2> kd(unit_box<2>({true, true}));
  kd.build(x.data(), 1000, 0.06);
  EXPECT_EQ(kd.allocations(), 1);
  const std::size_t pairs = kd.list().pairs();
  for (int k = 1; k <= 4; ++k) {
    for (std::size_t i = 0; i < x.size(); i += 2) x[i] += 0.1;  // a periodic translation: the same pairs
    kd.build(x.data(), 1000, 0.06);
    EXPECT_EQ(kd.list().pairs(), pairs);
  }
  EXPECT_EQ(kd.allocations(), 1);
}

TEST(KdTreeNeighbourSearch, RejectsBoxShorterThanTwoRadii) {
  const auto x = random_points<2>(10, 1);
  KdTreeNeighbourSearch<2> kd(unit_box<2>({true, false}));
  EXPECT_THROW(kd.build(x.data(), 10, 0.6), std::invalid_argument);
  EXPECT_NO_THROW(kd.build(x.data(), 10, 0.4));
}
