// The builder rule: Q = mean (r_max / r_i)^D (1 for equal radii; the two-population closed
// form), the grid below the crossover and the tree above, and AdaptiveNeighbourSearch giving the
// cell grid's lists whichever it picks.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "sphark/neighbours/neighbour_method.hpp"

using namespace sphark;

TEST(NeighbourMethod, GridOverheadIsTheMeanRadiusRatioToTheDimension) {
  std::vector<Real> same(100, 0.3);
  EXPECT_DOUBLE_EQ(cell_grid_overhead(same.data(), same.size(), 0.3), 1.0);
  EXPECT_DOUBLE_EQ(cell_grid_overhead(nullptr, 100, 0.3), 1.0);
  // 3 of 4 particles at r_max / 3: Q = (1 + 3 * 27) / 4
  std::vector<Real> two = {0.9, 0.3, 0.3, 0.3};
  EXPECT_NEAR(cell_grid_overhead(two.data(), two.size(), 0.9), (1 + 3 * 27.0) / 4, 1e-12);
  EXPECT_EQ(choose_neighbour_method(same.data(), same.size(), 0.3), NeighbourMethod::cell_grid);
  EXPECT_EQ(choose_neighbour_method(two.data(), two.size(), 0.9), NeighbourMethod::kd_tree);  // 20.5 > 19
  // in 2D the grid's overhead is the area ratio: Q = (1 + 3 * 9) / 4 = 7, below the 2D crossover
  EXPECT_NEAR(cell_grid_overhead(two.data(), two.size(), 0.9, 2), 7.0, 1e-12);
  EXPECT_EQ(choose_neighbour_method(two.data(), two.size(), 0.9, 2), NeighbourMethod::cell_grid);
  std::vector<Real> far = {0.9, 0.2, 0.2, 0.2};  // Q2 = (1 + 3 * 20.25) / 4 = 15.4
  EXPECT_EQ(choose_neighbour_method(far.data(), far.size(), 0.9, 2), NeighbourMethod::kd_tree);
  // radii above the build radius are capped, as the builders cap them
  std::vector<Real> capped = {2.0, 0.5};
  EXPECT_DOUBLE_EQ(cell_grid_overhead(capped.data(), 2, 0.5), 1.0);
}

TEST(NeighbourMethod, AdaptiveSearchPicksByTheRuleAndListsAsTheGrid) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<Real> U(0, 1);
  const std::size_t n = 3000;
  std::vector<Real> x(3 * n);
  for (auto& v : x) v = U(rng);
  PeriodicBox<3> box;
  box.periodic.fill(true);
  for (Real spread : {1.0, 8.0}) {  // equal radii, then radii spanning 8x
    std::vector<Real> radii(n);
    for (std::size_t i = 0; i < n; ++i) radii[i] = 0.12 / (1 + (spread - 1) * (i % 7 == 0 ? 0 : 1));
    AdaptiveNeighbourSearch<3> adaptive(box);
    NeighbourSearch<3> grid(box);
    adaptive.build(x.data(), n, 0.12, nullptr, radii.data());
    grid.build(x.data(), n, 0.12, nullptr, radii.data());
    EXPECT_EQ(adaptive.method(), spread > 1 ? NeighbourMethod::kd_tree : NeighbourMethod::cell_grid);
    EXPECT_EQ(adaptive.list().offsets, grid.list().offsets);
    EXPECT_EQ(adaptive.list().indices, grid.list().indices);
    EXPECT_GT(adaptive.list().pairs(), n);
  }
}
