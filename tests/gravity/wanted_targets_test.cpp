// The field at some particles only (GravitySources::wanted; the active particles of a block-step
// evaluation, issue #17): every particle is still a source, the wanted ones' accelerations and
// potentials equal the full computation's bit for bit, the others are NaN (not computed), and the
// energy, which needs them all, is NaN. Tree and direct summation; for a clump of wanted particles
// the tree walk leaves out the node pairs that hold none.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "gravity_test_support.hpp"
#include "sphark/gravity/sphere_particles.hpp"
#include "sphark/gravity/tree_gravity.hpp"

using namespace sphark;
using namespace sphark::gravity_test;

namespace {

// Every fifth particle (nearly every leaf holds one), or those within 0.2 of the centre (a
// clump, as the active particles of a collapse: most node pairs hold none and are not walked).
std::vector<std::uint8_t> every_fifth(const SphereParticles& p) {
  std::vector<std::uint8_t> wanted(p.size(), 0);
  for (std::size_t a = 0; a < p.size(); a += 5) wanted[a] = 1;
  return wanted;
}
std::vector<std::uint8_t> central_clump(const SphereParticles& p) {
  std::vector<std::uint8_t> wanted(p.size(), 0);
  for (std::size_t a = 0; a < p.size(); ++a) wanted[a] = p.x[3 * a] * p.x[3 * a] + p.x[3 * a + 1] * p.x[3 * a + 1] + p.x[3 * a + 2] * p.x[3 * a + 2] < 0.04;
  return wanted;
}

void expect_wanted_equal_full(GravitySolver solver, std::vector<std::uint8_t> (*choose)(const SphereParticles&),
                              std::size_t expected) {
  const SphereParticles p = random_sphere(SphereProfile::InverseR, 1500, 1, 1, 1.2, 21);
  const GravitySources all = p.sources();
  const std::vector<std::uint8_t> wanted = choose(p);
  GravitySources some = all;
  some.wanted = wanted.data();
  const Field full = solve(solver, all), part = solve(solver, some);
  std::size_t checked = 0;
  for (std::size_t a = 0; a < all.n; ++a) {
    for (int c = 0; c < 3; ++c) {
      if (wanted[a]) {
        EXPECT_EQ(part.acc[3 * a + c], full.acc[3 * a + c]) << a;
      } else {
        EXPECT_TRUE(std::isnan(part.acc[3 * a + c])) << a;
      }
    }
    if (wanted[a]) {
      EXPECT_EQ(part.pot[a], full.pot[a]) << a;
      ++checked;
    } else {
      EXPECT_TRUE(std::isnan(part.pot[a])) << a;
    }
  }
  EXPECT_EQ(checked, expected);
  EXPECT_TRUE(std::isfinite(full.energy));
  EXPECT_TRUE(std::isnan(part.energy));
}

}  // namespace

TEST(WantedTargets, TreeFieldAtTheWantedParticlesEqualsTheFullOne) {
  expect_wanted_equal_full(GravitySolver::Tree, every_fifth, 300);
}
TEST(WantedTargets, DirectFieldAtTheWantedParticlesEqualsTheFullOne) {
  expect_wanted_equal_full(GravitySolver::Direct, every_fifth, 300);
}
TEST(WantedTargets, TreeFieldAtAClumpEqualsTheFullOne) {
  const std::size_t clump = 61;  // of the 1,500 (InverseR: the mass within r grows as r^2, 1,500 x 0.2^2 = 60)
  expect_wanted_equal_full(GravitySolver::Tree, central_clump, clump);
}

// The walk leaves out the node pairs without a wanted particle: for the clump, most of them.
TEST(WantedTargets, TheWalkForAClumpRecordsFewerPairs) {
  const SphereParticles p = random_sphere(SphereProfile::InverseR, 1500, 1, 1, 1.2, 21);
  GravitySources src = p.sources();
  std::vector<Real> acc(3 * src.n), pot(src.n);
  TreeGravity<CubicSpline<3>> full(GravityOptions{}), clump(GravityOptions{});
  full.compute(src, acc.data(), pot.data());
  const std::vector<std::uint8_t> wanted = central_clump(p);
  src.wanted = wanted.data();
  clump.compute(src, acc.data(), pot.data());
  // measured: 864 of 5,577 far pairs, 1,678 of 7,755 near pairs
  EXPECT_LT(5 * clump.walk().far_pairs(), full.walk().far_pairs());
  EXPECT_LT(4 * clump.walk().near_pairs(), full.walk().near_pairs());
}
