// Dehnen's (2002, JCP 179, 27) mass-dependent opening angle: theta(M) solves
// theta^5 / (1 - theta)^2 = theta_0^5 / (1 - theta_0)^2 (M_root / M)^(1/3) to round-off, is
// theta_0 at the root, grows with M_root / M and stays below 1.
#include <gtest/gtest.h>

#include <cmath>

#include "sphark/gravity/dual_tree_walk.hpp"

using namespace sphark;

namespace {

Real lhs(Real t) { return std::pow(t, 5) / ((1 - t) * (1 - t)); }

}  // namespace

TEST(MassOpeningAngle, SolvesDehnensEquation) {
  for (Real theta_0 : {0.1, 0.25, 0.35, 0.5, 0.7})
    for (Real ratio : {1.0, 1.5, 8.0, 1e3, 1e6, 1e12}) {
      const Real t = mass_opening_angle(theta_0, ratio);
      EXPECT_GE(t, theta_0) << theta_0 << ' ' << ratio;
      EXPECT_LT(t, 1.0) << theta_0 << ' ' << ratio;
      EXPECT_NEAR(lhs(t) / (lhs(theta_0) * std::cbrt(ratio)), 1.0, 1e-11) << theta_0 << ' ' << ratio;
    }
}

TEST(MassOpeningAngle, IsTheRootsAngleAtTheRootAndGrowsAsCellsGetLighter) {
  for (Real theta_0 : {0.25, 0.35, 0.5}) {
    EXPECT_NEAR(mass_opening_angle(theta_0, 1.0), theta_0, 1e-14);
    EXPECT_EQ(mass_opening_angle(theta_0, 0.5), mass_opening_angle(theta_0, 1.0));  // never below theta_0
    Real previous = theta_0;
    for (Real ratio = 2; ratio < 1e9; ratio *= 4) {
      const Real t = mass_opening_angle(theta_0, ratio);
      EXPECT_GT(t, previous) << theta_0 << ' ' << ratio;
      previous = t;
    }
  }
}

// A worked value, solved independently (mpmath, 30 digits): theta_0 = 0.35 and a cell of
// 1/12,500 of the mass (a leaf of 8 among 10^5 particles): theta^5 / (1 - theta)^2 =
// 0.0124312130 x 12500^(1/3) = 0.2885028977 at theta = 0.5610452903829303.
TEST(MassOpeningAngle, WorkedValueOfALeafAmongAHundredThousand) {
  EXPECT_NEAR(mass_opening_angle(0.35, 12500.0), 0.5610452903829303, 1e-14);
}
