// The multirate interface of the SPMHD scheme (issue #17): rhs_subset(A) and
// rhs_subset(complement of A) add up to rhs() bit for bit on a self-gravitating, magnetised,
// rotating clump with a sink particle (every term on); each is zero outside its set; the pair
// interactions split between them; particle_stable_dt is what max_stable_dt minimises, capped by
// 4 x the neighbours', and a sink's is the shortest gas step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "sphark/initial/spheres.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"
#include "../support/sink_clump.hpp"

namespace sphark {
namespace {

using test::Clump;
using test::clump;

TEST(SpmhdSubsets, TwoComplementarySubsetsAddUpToTheFullRhsBitForBit) {
  Clump c = clump();
  SpmhdScheme<3>& s = *c.scheme;
  ASSERT_TRUE(s.supports_subsets());
  const std::size_t np = s.num_particles();
  ASSERT_EQ(np, s.particles() + 1);  // gas, then the sink
  std::vector<std::size_t> a_set, b_set;
  for (std::size_t i = 0; i < np; ++i) (i % 3 == 1 || i == np - 1 ? a_set : b_set).push_back(i);
  std::vector<Real> full(c.y.size()), fa(c.y.size(), 7), fb(c.y.size(), 7);
  ASSERT_EQ(s.rhs(0, c.y.data(), full.data()), 0) << s.last_error();
  const std::size_t pairs_full = s.interacting_pairs();
  ASSERT_EQ(s.rhs_subset(0, c.y.data(), a_set, fa.data()), 0) << s.last_error();
  const std::size_t pairs_a = s.interacting_pairs();
  ASSERT_EQ(s.rhs_subset(0, c.y.data(), b_set, fb.data()), 0) << s.last_error();
  const std::size_t pairs_b = s.interacting_pairs();
  EXPECT_EQ(pairs_a + pairs_b, pairs_full);  // the rows split, none is computed twice
  EXPECT_LT(pairs_a, pairs_full / 2);
  const std::vector<std::size_t> owner = s.entry_particles();
  std::size_t nonzero = 0;
  for (std::size_t k = 0; k < c.y.size(); ++k) {
    const bool in_a = owner[k] % 3 == 1 || owner[k] == np - 1;
    EXPECT_EQ(in_a ? fb[k] : fa[k], 0.0) << "entry " << k << " outside its set";
    EXPECT_EQ(in_a ? fa[k] : fb[k], full[k]) << "entry " << k << " (particle " << owner[k] << ")";
    nonzero += full[k] != 0;
  }
  EXPECT_GT(nonzero, c.y.size() / 2);
}

TEST(SpmhdSubsets, ParticleStableStepsAreWhatMaxStableDtMinimises) {
  Clump c = clump();
  SpmhdScheme<3>& s = *c.scheme;
  const std::size_t v0 = s.layout().offset(Field::Velocity);
  for (int k = 0; k < 3; ++k) c.y[v0 + 3 * 5 + k] *= 300;  // particle 5: a short Courant step, its neighbours capped
  std::vector<Real> dt(s.num_particles());
  ASSERT_EQ(s.particle_stable_dt(0, c.y.data(), nullptr, dt.data()), 0) << s.last_error();
  const Real least = *std::min_element(dt.begin(), dt.end() - 1);
  EXPECT_EQ(dt.back(), least);  // the sink: the shortest gas step
  EXPECT_EQ(least, s.max_stable_dt(0, c.y.data(), nullptr));
  const Real most = *std::max_element(dt.begin(), dt.end() - 1);
  EXPECT_GT(most, least);
  // Each step is its own (Courant, force) capped by 4 x its neighbours' own ones.
  std::vector<Real> courant, force;
  ASSERT_EQ(s.stable_steps(0, c.y.data(), nullptr, courant, force), 0);
  const std::vector<Real> h = s.h(), x = s.positions();
  std::size_t capped = 0;
  for (std::size_t a = 0; a < s.particles(); ++a) {
    Real expected = std::min(courant[a], force[a]);
    for (std::size_t b = 0; b < s.particles(); ++b) {
      const Real r = (Eigen::Map<const Vec<3>>(&x[3 * a]) - Eigen::Map<const Vec<3>>(&x[3 * b])).norm();
      if (b != a && r < CubicSpline<3>::support * std::max(h[a], h[b]))
        expected = std::min(expected, 4 * std::min(courant[b], force[b]));
    }
    EXPECT_EQ(dt[a], expected) << "particle " << a;
    capped += expected < std::min(courant[a], force[a]);
  }
  std::printf("neighbour limiter: %zu of %zu particles capped, steps from %.3e to %.3e\n", capped, s.particles(),
              least, most);
  EXPECT_GT(capped, 0u);
}

}  // namespace
}  // namespace sphark
