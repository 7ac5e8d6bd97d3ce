// The neighbour lists' validity with a few fast movers (SpmhdScheme::lists_serve): three particles
// of a disordered periodic lattice moved further than one displacement for all allows (the others
// a little). Where no pair at the particles' h is missing the lists are kept, where one is they are
// rebuilt; either way the derivatives are a fresh scheme's at the same state, to ten times the
// density solve's tolerance (a missing neighbour would be an error of order one in its terms).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "spmhd_checks.hpp"

namespace sphark {
namespace {

using K = CubicSpline<3>;
const std::vector<std::size_t> kMovers = {7, 200, 401};

struct Lattice {
  SpmhdScheme<3, K> s;
  std::vector<Real> y, ydot;
  Lattice()
      : s(test::lattice_masses<3>(test::LatticeCase{}), test::conserving_options(), test::unit_box<3>()),
        y(test::lattice_state(s, test::LatticeCase{})), ydot(y.size()) {}
};

// y with kMovers moved by `far` along (1, 2, 2)/3 and every other particle by `rest` (wrapped).
std::vector<Real> moved(const Lattice& c, std::vector<Real> y, Real far, const Vec<3>& rest) {
  const std::size_t x0 = c.s.layout().offset(Field::Position);
  for (std::size_t a = 0; a < c.s.particles(); ++a) {
    const bool mover = std::find(kMovers.begin(), kMovers.end(), a) != kMovers.end();
    const Vec<3> step = mover ? Vec<3>(far / 3, 2 * far / 3, 2 * far / 3) : rest;
    for (int k = 0; k < 3; ++k) y[x0 + 3 * a + k] = std::fmod(y[x0 + 3 * a + k] + step[k] + 1, 1.0);
  }
  return y;
}

// max |f - g| / max |g| over all entries
Real relative_difference(const std::vector<Real>& f, const std::vector<Real>& g) {
  Real diff = 0, scale = 0;
  for (std::size_t k = 0; k < f.size(); ++k) diff = std::max(diff, std::abs(f[k] - g[k])), scale = std::max(scale, std::abs(g[k]));
  return diff / scale;
}

// The persistent scheme at state y and time t against a fresh one; returns the list builds it made.
long builds_at(Lattice& c, Real t, const std::vector<Real>& y) {
  const long before = c.s.neighbour_builds();
  std::vector<Real> f(y.size()), fresh(y.size());
  EXPECT_EQ(c.s.rhs(t, y.data(), f.data()), 0) << c.s.last_error();
  Lattice twin;
  EXPECT_EQ(twin.s.rhs(t, y.data(), fresh.data()), 0) << twin.s.last_error();
  // The two density solves start from different h and stop within h_tolerance (1e-10) of the root:
  // measured 2.6e-12 to 3.2e-12 here, bounded by ten h_tolerances (a missing pair: order one).
  EXPECT_LT(relative_difference(f, fresh), 10 * c.s.options().h_tolerance);
  return c.s.neighbour_builds() - before;
}

TEST(SpmhdFastMovers, ListsAreKeptWhereNoPairIsMissingAndRebuiltWhereOneIs) {
  Lattice c;
  ASSERT_EQ(c.s.rhs(0, c.y.data(), c.ydot.data()), 0) << c.s.last_error();
  // All translated by more than the skin: lists rebuilt for the solved h (list_h = h, so every
  // list reaches support h_i (1 + skin), skin_own_fraction 1).
  ASSERT_EQ(c.s.options().skin_own_fraction, 1.0);
  const std::vector<Real> y1 = moved(c, c.y, 0.3, Vec<3>(0.3, 0.1, 0.2));
  EXPECT_EQ(builds_at(c, 1e-3, y1), 1);
  const std::vector<Real> h = c.s.h();
  const Real h_min = *std::min_element(h.begin(), h.end()), h_max = *std::max_element(h.begin(), h.end());
  // One displacement for all (the movers', d) serves particle j only while
  // 2 d <= R_j - support h_j = support skin h_j: the old rule rebuilds here.
  const Real skin = c.s.options().skin, d = 0.8 * K::support * skin * h_min;
  for (std::size_t j : kMovers) ASSERT_LT(K::support * skin * h[j], 2 * d) << "the old rule would keep the lists";
  const Vec<3> little(1e-4 * d, 0, 0);
  EXPECT_EQ(builds_at(c, 2e-3, moved(c, y1, d, little)), 0);  // no pair within the h is new: kept
  EXPECT_EQ(builds_at(c, 3e-3, moved(c, y1, 3 * K::support * h_max, little)), 1);  // through the others: rebuilt
}

}  // namespace
}  // namespace sphark
