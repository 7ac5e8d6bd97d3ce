// The field at some particles only (GravitySources::wanted; the active particles of a block-step
// evaluation, issue #17): every particle is still a source, the wanted ones' accelerations and
// potentials equal the full computation's bit for bit, the others are NaN (not computed), and the
// energy, which needs them all, is NaN. Tree and direct summation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "gravity_test_support.hpp"
#include "sphark/gravity/sphere_particles.hpp"

using namespace sphark;
using namespace sphark::gravity_test;

namespace {

void expect_wanted_equal_full(GravitySolver solver) {
  const SphereParticles p = random_sphere(SphereProfile::InverseR, 1500, 1, 1, 1.2, 21);
  const GravitySources all = p.sources();
  std::vector<std::uint8_t> wanted(all.n, 0);
  for (std::size_t a = 0; a < all.n; a += 5) wanted[a] = 1;
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
  EXPECT_EQ(checked, 300u);
  EXPECT_TRUE(std::isfinite(full.energy));
  EXPECT_TRUE(std::isnan(part.energy));
}

}  // namespace

TEST(WantedTargets, TreeFieldAtTheWantedParticlesEqualsTheFullOne) { expect_wanted_equal_full(GravitySolver::Tree); }
TEST(WantedTargets, DirectFieldAtTheWantedParticlesEqualsTheFullOne) { expect_wanted_equal_full(GravitySolver::Direct); }
