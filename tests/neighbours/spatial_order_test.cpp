// cell_order and scrambled_fraction (neighbours/spatial_order.hpp): a permutation in row-major
// cell order, ties by index; the measure 0 in that order, 3/16 for a square lattice numbered row
// by row against cells of four spacings, 2/(n - 1) more for one particle moved out of its run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "sphark/neighbours/spatial_order.hpp"

namespace sphark {
namespace {

constexpr int kSide = 32;  // particles per row of the square lattice, spacing 1 / kSide

// x_i of a square lattice numbered row by row (i = row * kSide + column), cells of 4 spacings
std::vector<Real> row_by_row_lattice() {
  std::vector<Real> x(2 * kSide * kSide);
  for (int r = 0; r < kSide; ++r)
    for (int c = 0; c < kSide; ++c) {
      x[2 * (r * kSide + c)] = (c + 0.5) / kSide;
      x[2 * (r * kSide + c) + 1] = (r + 0.5) / kSide;
    }
  return x;
}

PeriodicBox<2> unit_box() {
  PeriodicBox<2> b;
  b.periodic = {true, true};
  return b;
}

constexpr Real kCell = 4.0 / kSide;

TEST(SpatialOrder, CellOrderIsAPermutationInRowMajorCellsTiesByIndex) {
  const std::vector<Real> x = row_by_row_lattice();
  const std::size_t n = x.size() / 2;
  const std::vector<std::size_t> order = cell_order<2>(x.data(), n, kCell, unit_box());
  std::vector<std::size_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::size_t> all(n);
  std::iota(all.begin(), all.end(), std::size_t{0});
  ASSERT_EQ(sorted, all);
  auto cell = [&](std::size_t i) {
    return static_cast<int>(std::floor(x[2 * i + 1] / kCell)) * 8 + static_cast<int>(std::floor(x[2 * i] / kCell));
  };
  for (std::size_t k = 1; k < n; ++k) {
    const std::size_t a = order[k - 1], b = order[k];
    ASSERT_TRUE(cell(a) < cell(b) || (cell(a) == cell(b) && a < b)) << k;
  }
  EXPECT_EQ(order.front(), 0u);  // the first cell: the lattice's first four rows' first four columns
  EXPECT_EQ(order[4], static_cast<std::size_t>(kSide));
}

TEST(SpatialOrder, ScrambledFractionCountsTheCellChangesBeyondTheFewest) {
  const std::vector<Real> x = row_by_row_lattice();
  const std::size_t n = x.size() / 2;
  // row by row: each of the 64 cells entered 4 times (changes 4 * 64 - 1), fewest 63
  EXPECT_DOUBLE_EQ(scrambled_fraction<2>(x.data(), n, kCell, unit_box()), (4.0 * 64 - 1 - 63) / (n - 1));
  std::vector<Real> sorted(x.size());
  const std::vector<std::size_t> order = cell_order<2>(x.data(), n, kCell, unit_box());
  for (std::size_t k = 0; k < n; ++k)
    for (int d = 0; d < 2; ++d) sorted[2 * k + d] = x[2 * order[k] + d];
  EXPECT_EQ(scrambled_fraction<2>(sorted.data(), n, kCell, unit_box()), 0.0);
  sorted[2 * 5] += 5 * kCell;  // particle 5 (inside the first cell's run) moved to another cell
  EXPECT_DOUBLE_EQ(scrambled_fraction<2>(sorted.data(), n, kCell, unit_box()), 2.0 / (n - 1));
  sorted[2 * 5] -= 1.0;  // the same cell through the periodic image: wrapped
  EXPECT_DOUBLE_EQ(scrambled_fraction<2>(sorted.data(), n, kCell, unit_box()), 2.0 / (n - 1));
}

TEST(SpatialOrder, WithoutABoxTheCellsStartAtTheBoundingBox) {
  const std::vector<Real> x = row_by_row_lattice();
  std::vector<Real> shifted = x;
  for (Real& v : shifted) v += 8 + 3.0 / kSide;  // exact in binary; not a whole number of cells
  const std::size_t n = x.size() / 2;
  const std::vector<std::size_t> order = cell_order<2>(x.data(), n, kCell, std::nullopt);
  EXPECT_EQ(cell_order<2>(shifted.data(), n, kCell, std::nullopt), order);  // translation: the same order
  EXPECT_EQ(scrambled_fraction<2>(shifted.data(), n, kCell, std::nullopt),
            scrambled_fraction<2>(x.data(), n, kCell, std::nullopt));
  EXPECT_THROW(cell_order<2>(x.data(), n, 0.0, std::nullopt), std::invalid_argument);
}

}  // namespace
}  // namespace sphark
