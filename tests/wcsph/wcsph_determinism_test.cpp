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
  // move every particle by less than half the skin (skin = config.skin * support, support 2h)
  std::vector<Real> y = reused.y0;
  auto x = vector_field<2>(y.data(), reused.model->layout(), Field::Position);
  const Real h = reused.config.h_factor * reused.config.spacing;
  for (Index a = 0; a < x.cols(); ++a) x.col(a) += 0.4 * reused.config.skin * h * Vec<2>(std::cos(a), std::sin(1.3 * a));
  const auto a = rhs_of(reused, y);
  EXPECT_EQ(reused.model->neighbour_builds(), builds);  // the lists were reused
  WaterDrop fresh = make_water_drop(WaterDropConfig{});
  const auto b = rhs_of(fresh, y);
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(a[k], b[k]) << "entry " << k;
}

// The skin is a cost, not a result: lists with a wider skin hold more pairs beyond the support,
// which add exactly zero, in the same ascending order.
TEST(WcsphDeterminism, SkinWidthDoesNotChangeTheRhs) {
  WaterDropConfig narrow_cfg, wide_cfg;
  narrow_cfg.skin = 0.05;
  wide_cfg.skin = 0.6;
  WaterDrop narrow = make_water_drop(narrow_cfg), wide = make_water_drop(wide_cfg);
  std::vector<Real> y = narrow.y0;
  auto x = vector_field<2>(y.data(), narrow.model->layout(), Field::Position);
  const Real h = narrow.config.h_factor * narrow.config.spacing;
  for (Index a = 0; a < x.cols(); ++a) x.col(a) += 0.2 * h * Vec<2>(std::cos(a), std::sin(1.3 * a));
  for (const std::vector<Real>* state : {&narrow.y0, &y}) {  // the second: lists rebuilt or reused
    const auto a = rhs_of(narrow, *state), b = rhs_of(wide, *state);
    for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(a[k], b[k]) << "entry " << k;
  }
  EXPECT_EQ(narrow.model->neighbour_builds(), 2);  // 0.2 h is beyond half the narrow skin (0.05 h)
  EXPECT_EQ(wide.model->neighbour_builds(), 1);    // and within half the wide one (0.6 h)
}
