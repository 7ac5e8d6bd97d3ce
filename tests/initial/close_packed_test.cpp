// Close-packed lattices: every site has its nearest neighbour at exactly the spacing d (no
// pair closer), interior sites have exactly 12 neighbours at d, the ball's centre of mass is
// the origin to round-off (the origin is an inversion centre), the site count of a ball lies
// between n V(r - d/sqrt2) and n V(r + d/sqrt2) (covering radius), and the fcc cube tiles
// periodically (the same 12 neighbours at d across every face).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sphark/initial/close_packed.hpp"
#include "sphark/neighbours/neighbour_search.hpp"

using namespace sphark;

namespace {
Real ball_volume(Real r) { return 4.0 / 3.0 * kPi * r * r * r; }

Vec<3> centre_of_mass(const std::vector<Real>& x) {
  Vec<3> c = Vec<3>::Zero();
  for (std::size_t a = 0; a < x.size(); a += 3) c += Vec<3>(x[a], x[a + 1], x[a + 2]);
  return c / static_cast<Real>(x.size() / 3);
}
}  // namespace

class CloseLatticeTest : public ::testing::TestWithParam<CloseLattice> {};

TEST_P(CloseLatticeTest, NearestNeighboursAtTheSpacingAndTwelveInside) {
  const Real d = 0.1, R = 1.0;
  const std::vector<Real> x = close_packed_ball(GetParam(), d, R);
  const std::size_t n = x.size() / 3;
  ASSERT_GT(n, 3000u);
  NeighbourSearch<3> closer;  // nothing strictly closer than d (1e-9 relative below d)
  closer.build(x.data(), n, d * (1 - 1e-9));
  EXPECT_EQ(closer.list().pairs(), 0u);
  NeighbourSearch<3> at;
  at.build(x.data(), n, d * (1 + 1e-9));
  std::size_t interior = 0;
  for (std::size_t a = 0; a < n; ++a) {
    const Real r = std::sqrt(x[3 * a] * x[3 * a] + x[3 * a + 1] * x[3 * a + 1] + x[3 * a + 2] * x[3 * a + 2]);
    if (r < R - 1.01 * d) {
      ++interior;
      EXPECT_EQ(at.list().count(a), 12u) << a;
    }
  }
  EXPECT_GT(interior, n / 2);
}

TEST_P(CloseLatticeTest, CentreOfMassAtTheOriginAndCountWithinTheCoveringBound) {
  for (Real R : {0.37, 1.0, 1.73}) {
    const Real d = 0.07;
    const std::vector<Real> x = close_packed_ball(GetParam(), d, R);
    const Real n = static_cast<Real>(x.size() / 3), nd = close_packed_number_density(d);
    const Real rc = close_packed_covering_radius(d);
    EXPECT_LT(centre_of_mass(x).norm(), 1e-14 * R) << R;
    EXPECT_GE(n, nd * ball_volume(R - rc)) << R;
    EXPECT_LE(n, nd * ball_volume(R + rc)) << R;
    EXPECT_EQ(close_packed_ball_count(GetParam(), d, R), x.size() / 3);
  }
}

INSTANTIATE_TEST_SUITE_P(Lattices, CloseLatticeTest, ::testing::Values(CloseLattice::fcc, CloseLattice::hcp),
                         [](const auto& info) { return info.param == CloseLattice::fcc ? "fcc" : "hcp"; });

TEST(FccPeriodicCube, TilesThePeriodicBoxWithTwelveNeighboursAtTheSpacing) {
  const Real side = 2.0;
  const std::size_t cells = 6;
  const std::vector<Real> x = fcc_periodic_cube(side, cells);
  const std::size_t n = x.size() / 3;
  ASSERT_EQ(n, 4 * cells * cells * cells);
  const Real d = side / cells / std::sqrt(2.0);
  PeriodicBox<3> box;
  box.lo = Vec<3>::Constant(-side / 2);
  box.hi = Vec<3>::Constant(side / 2);
  box.periodic.fill(true);
  for (std::size_t a = 0; a < n; ++a)
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(x[3 * a + k], box.lo[k]);
      EXPECT_LT(x[3 * a + k], box.hi[k]);
    }
  NeighbourSearch<3> closer(box), at(box);
  closer.build(x.data(), n, d * (1 - 1e-9));
  EXPECT_EQ(closer.list().pairs(), 0u);
  at.build(x.data(), n, d * (1 + 1e-9));
  for (std::size_t a = 0; a < n; ++a) EXPECT_EQ(at.list().count(a), 12u) << a;
  // the cut-out: no site inside the radius, every other site kept
  const std::vector<Real> holed = fcc_periodic_cube(side, cells, 0.5);
  std::size_t inside = 0;
  for (std::size_t a = 0; a < n; ++a)
    inside += x[3 * a] * x[3 * a] + x[3 * a + 1] * x[3 * a + 1] + x[3 * a + 2] * x[3 * a + 2] < 0.25;
  EXPECT_EQ(holed.size() / 3, n - inside);
  EXPECT_GT(inside, 0u);
}
