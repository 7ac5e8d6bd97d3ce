// The gravity tree is a function of the positions alone: a rebuild that starts from the order of
// the last build (of other positions) equals a build from scratch bit for bit — the same
// particles in every node, in the same order, the same moments — on random points and on a
// lattice, whose coordinates tie along every axis. And the split rule itself: each node's left
// child holds the points first in (coordinate along the node's longest side, particle index);
// each leaf lists its particles by index.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <utility>
#include <vector>

#include "sphark/gravity/gravity_tree.hpp"
#include "sphark/gravity/sphere_particles.hpp"

using namespace sphark;

namespace {

constexpr Real kSupport = 2;
constexpr int kLeaf = 8;

// The same points moved by up to `amount` along each axis (seeded).
SphereParticles moved(SphereParticles p, Real amount, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<Real> u(-amount, amount);
  for (Real& x : p.x) x += u(rng);
  return p;
}

bool same_bits(const Real* a, const Real* b, std::size_t n) { return std::memcmp(a, b, n * sizeof(Real)) == 0; }

void expect_same_tree(const GravityTree& a, const GravityTree& b) {
  ASSERT_EQ(a.nodes().size(), b.nodes().size());
  EXPECT_EQ(a.order(), b.order());
  EXPECT_EQ(a.leaves(), b.leaves());
  const std::size_t n = a.particles();
  EXPECT_TRUE(same_bits(a.x(), b.x(), n) && same_bits(a.y(), b.y(), n) && same_bits(a.z(), b.z(), n));
  std::size_t differing = 0;
  for (std::size_t i = 0; i < a.nodes().size(); ++i) {
    const TreeNode &p = a.nodes()[i], &q = b.nodes()[i];
    differing += p.begin != q.begin || p.end != q.end || p.left != q.left || p.right != q.right ||
                 !same_bits(p.com, q.com, 3) || !same_bits(p.quad, q.quad, 6) || !same_bits(&p.mass, &q.mass, 1) ||
                 !same_bits(&p.radius, &q.radius, 1) || !same_bits(&p.reach, &q.reach, 1);
  }
  EXPECT_EQ(differing, 0u);
}

// A fresh tree of `now` against one rebuilt on `now` after a build on `before` (warm start).
void expect_rebuild_equals_fresh_build(const SphereParticles& before, const SphereParticles& now) {
  GravityTree fresh, rebuilt;
  fresh.build(now.sources(), kSupport, kLeaf);
  rebuilt.build(before.sources(), kSupport, kLeaf);
  rebuilt.build(now.sources(), kSupport, kLeaf);
  expect_same_tree(fresh, rebuilt);
}

}  // namespace

TEST(GravityTreeBuild, ARebuildEqualsAFreshBuildWhateverTheLastPositions) {
  const SphereParticles p = random_sphere(SphereProfile::InverseR, 3000, 1, 1, 1.2, 5);
  expect_rebuild_equals_fresh_build(p, moved(p, 0.01, 1));  // most splits stand
  expect_rebuild_equals_fresh_build(p, moved(p, 0.3, 2));   // most do not
  expect_rebuild_equals_fresh_build(moved(p, 0.3, 2), p);
}

TEST(GravityTreeBuild, TiesAlongAnAxisGoByParticleIndex) {
  const SphereParticles lattice = lattice_sphere(2000, 1, 1, 1.2);  // coordinates tie in planes
  SphereParticles jittered = moved(lattice, 0.2, 3);
  expect_rebuild_equals_fresh_build(jittered, lattice);
  expect_rebuild_equals_fresh_build(lattice, lattice);
}

TEST(GravityTreeBuild, EachSplitTakesTheFirstPointsAlongTheLongestSideAndLeavesListByIndex) {
  const SphereParticles lattice = lattice_sphere(1500, 1, 1, 1.2);
  GravityTree tree;
  tree.build(moved(lattice, 0.5, 4).sources(), kSupport, kLeaf);  // a warm start from other positions
  tree.build(lattice.sources(), kSupport, kLeaf);
  const Real* c[3] = {tree.x(), tree.y(), tree.z()};
  const std::vector<std::uint32_t>& order = tree.order();
  std::size_t wrong_splits = 0, unsorted_leaves = 0, splits = 0;
  for (const TreeNode& nd : tree.nodes()) {
    if (nd.leaf()) {
      unsorted_leaves += !std::is_sorted(order.begin() + nd.begin, order.begin() + nd.end);
      continue;
    }
    int axis = 0;
    Real side[3];
    for (int k = 0; k < 3; ++k) {
      const auto [lo, hi] = std::minmax_element(c[k] + nd.begin, c[k] + nd.end);
      side[k] = *hi - *lo;
      if (side[k] > side[axis]) axis = k;
    }
    const auto key = [&](std::uint32_t s) { return std::pair{c[axis][s], order[s]}; };
    std::pair<Real, std::uint32_t> last_left = key(nd.begin), first_right = key(nd.end - 1);
    for (std::uint32_t s = nd.begin; s < tree.nodes()[nd.right].begin; ++s) last_left = std::max(last_left, key(s));
    for (std::uint32_t s = tree.nodes()[nd.right].begin; s < nd.end; ++s) first_right = std::min(first_right, key(s));
    wrong_splits += !(last_left < first_right);
    ++splits;
  }
  EXPECT_GT(splits, 100u);
  EXPECT_EQ(wrong_splits, 0u);
  EXPECT_EQ(unsorted_leaves, 0u);
}
