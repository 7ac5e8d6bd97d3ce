// The mutual walk's lists cover every ordered particle pair (a, b), a != b, exactly once, and
// mutually: if a takes b's field through a far (cell-cell) pair of ancestors, b takes a's through
// the same pair; if a meets b directly, b meets a directly. A pair missed or counted twice is a
// wrong force; a one-sided one breaks momentum conservation. (An exact property of the lists,
// independent of the expansions' accuracy.)
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "sphark/gravity/sphere_particles.hpp"
#include "sphark/gravity/tree_gravity.hpp"

using namespace sphark;

namespace {

enum Kind : std::uint8_t { kNone = 0, kFar = 1, kDirect = 2, kTwice = 255 };

// kind[a * n + b]: how tree slot a takes tree slot b's field.
class Coverage {
 public:
  explicit Coverage(std::size_t n) : n_(n), kind_(n * n, kNone) {}
  void add_block(const TreeNode& A, const TreeNode& B, Kind k) {
    for (std::uint32_t a = A.begin; a < A.end; ++a)
      for (std::uint32_t b = B.begin; b < B.end; ++b)
        if (a != b) {
          std::uint8_t& s = kind_[a * n_ + b];
          s = s == kNone ? k : kTwice;
        }
  }
  std::uint8_t at(std::size_t a, std::size_t b) const { return kind_[a * n_ + b]; }

 private:
  std::size_t n_;
  std::vector<std::uint8_t> kind_;
};

// A node's particles take the far fields of its own far list and its ancestors' (the
// expansions pass down): listing the block (node, partner) for every node covers both.
Coverage coverage(const GravityTree& tree, const DualTreeWalk& walk) {
  const std::vector<TreeNode>& nd = tree.nodes();
  Coverage c(tree.particles());
  for (std::uint32_t i = 0; i < nd.size(); ++i)
    for (std::uint32_t k = walk.far().begin(i); k < walk.far().end(i); ++k) c.add_block(nd[i], nd[walk.far().partner[k]], kFar);
  for (std::uint32_t leaf : tree.leaves())
    for (std::uint32_t k = walk.near().begin(leaf); k < walk.near().end(leaf); ++k)
      c.add_block(nd[leaf], nd[walk.near().partner[k] & ~DualTreeWalk::kNewtonian], kDirect);
  return c;
}

void expect_exact_mutual_cover(const SphereParticles& p, int leaf_size, Real theta,
                               GravityOpening opening = GravityOpening::Fixed) {
  GravityOptions opt;
  opt.leaf_size = leaf_size;
  opt.theta = theta;
  opt.opening = opening;
  TreeGravity<CubicSpline<3>> gravity(opt);
  std::vector<Real> acc(3 * p.size()), pot(p.size());
  gravity.compute(p.sources(), acc.data(), pot.data());
  const Coverage c = coverage(gravity.tree(), gravity.walk());
  std::size_t bad = 0, one_sided = 0, far = 0, direct = 0;
  for (std::size_t a = 0; a < p.size(); ++a)
    for (std::size_t b = 0; b < p.size(); ++b) {
      if (a == b) continue;
      const std::uint8_t k = c.at(a, b);
      if (k == kNone || k == kTwice) {
        ++bad;
        continue;
      }
      (k == kFar ? far : direct) += 1;
      one_sided += c.at(b, a) != k;
    }
  EXPECT_EQ(bad, 0u) << "leaf " << leaf_size << " theta " << theta;
  EXPECT_EQ(one_sided, 0u) << "leaf " << leaf_size << " theta " << theta;
  EXPECT_GT(direct, 0u);
  // both kinds occur wherever the tree has more than a few leaves (leaf 40 at theta 0.3: none far)
  if (leaf_size <= 8) {
    EXPECT_GT(far, 0u) << "leaf " << leaf_size << " theta " << theta;
  }
}

}  // namespace

TEST(DualTreeWalk, CoversEveryParticlePairOnceAndMutually) {
  const SphereParticles uniform = random_sphere(SphereProfile::Uniform, 1500, 1, 1, 1.2, 21);
  const SphereParticles clumped = random_sphere(SphereProfile::InverseR, 1500, 1, 1, 1.2, 22);
  for (int leaf : {1, 5, 8, 40})
    for (Real theta : {0.3, 0.5, 0.7}) {
      expect_exact_mutual_cover(uniform, leaf, theta);
      expect_exact_mutual_cover(clumped, leaf, theta);
    }
}

// The mass-dependent opening angle (each cell its own theta(M), the criterion still symmetric in
// A and B) keeps the cover exact and mutual.
TEST(DualTreeWalk, MassDependentOpeningCoversEveryPairOnceAndMutually) {
  const SphereParticles uniform = random_sphere(SphereProfile::Uniform, 1500, 1, 1, 1.2, 21);
  const SphereParticles clumped = random_sphere(SphereProfile::InverseR, 1500, 1, 1, 1.2, 22);
  for (int leaf : {1, 8})
    for (Real theta_0 : {0.25, 0.35, 0.5}) {
      expect_exact_mutual_cover(uniform, leaf, theta_0, GravityOpening::Mass);
      expect_exact_mutual_cover(clumped, leaf, theta_0, GravityOpening::Mass);
    }
}

// A walker remembers each node's mass-dependent opening angle between walks; a walk after the
// masses (or theta_0) changed lists exactly what a new walker lists, and the change mattered.
TEST(DualTreeWalk, RememberedOpeningAnglesFollowTheMassesAndTheta) {
  SphereParticles p = random_sphere(SphereProfile::InverseR, 1500, 1, 1, 1.2, 23);
  const auto lists = [](const DualTreeWalk& w) {
    return std::vector<std::vector<std::uint32_t>>{w.far().start, w.far().partner, w.near().start, w.near().partner};
  };
  GravityTree tree;
  tree.build(p.sources(), 2, 8);
  DualTreeWalk kept;
  kept.walk(tree, 0.35, GravityOpening::Mass);
  const auto first = lists(kept);
  for (std::size_t a = 0; a < p.size(); a += 3) p.m[a] *= 40;  // a third of the particles 40x heavier
  tree.build(p.sources(), 2, 8);
  for (Real theta_0 : {0.35, 0.5}) {
    SCOPED_TRACE(theta_0);
    kept.walk(tree, theta_0, GravityOpening::Mass);
    DualTreeWalk fresh;
    fresh.walk(tree, theta_0, GravityOpening::Mass);
    EXPECT_EQ(lists(kept), lists(fresh));
    EXPECT_NE(lists(kept), first);
  }
}
