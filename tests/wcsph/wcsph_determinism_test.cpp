// The WCSPH RHS is a gather over sorted neighbour lists: the result does not depend on the
// OpenMP thread count, and reusing Verlet-skin lists gives the same forces as a fresh build,
// bit for bit (pairs beyond the support contribute exactly zero and the order of the
// contributing pairs is the same ascending neighbour index).
#include <gtest/gtest.h>
#include <omp.h>

#include "sphark/scenes/water_drop/water_drop.hpp"

using namespace sphark;

namespace {
std::vector<Real> rhs_of(WaterDrop& drop, const std::vector<Real>& y) {
  std::vector<Real> ydot(y.size());
  EXPECT_EQ(drop.model->system().rhs(0, y.data(), ydot.data()), 0);
  return ydot;
}
}  // namespace

TEST(WcsphDeterminism, IndependentOfThreadCount) {
  WaterDrop drop = make_water_drop(WaterDropConfig{});
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto one = rhs_of(drop, drop.y0);
  omp_set_num_threads(2);
  WaterDrop again = make_water_drop(WaterDropConfig{});
  const auto two = rhs_of(again, again.y0);
  omp_set_num_threads(saved);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t k = 0; k < one.size(); ++k) ASSERT_EQ(one[k], two[k]) << "entry " << k;
}

TEST(WcsphDeterminism, SkinReuseEqualsFreshBuild) {
  WaterDrop reused = make_water_drop(WaterDropConfig{});
  rhs_of(reused, reused.y0);  // builds the lists at y0
  const long builds = reused.model->neighbour_builds();
  // move every particle by less than half the skin (skin = 0.1 * support = 0.1 * 2h)
  std::vector<Real> y = reused.y0;
  auto x = vector_field<2>(y.data(), reused.model->layout(), Field::Position);
  const Real h = reused.config.h_factor * reused.config.spacing;
  for (Index a = 0; a < x.cols(); ++a) x.col(a) += 0.4 * 0.1 * h * Vec<2>(std::cos(a), std::sin(1.3 * a));
  const auto a = rhs_of(reused, y);
  EXPECT_EQ(reused.model->neighbour_builds(), builds);  // the lists were reused
  WaterDrop fresh = make_water_drop(WaterDropConfig{});
  const auto b = rhs_of(fresh, y);
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(a[k], b[k]) << "entry " << k;
}
