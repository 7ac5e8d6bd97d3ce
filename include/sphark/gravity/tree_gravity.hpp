#pragma once
// Tree gravity: kd-tree (gravity_tree.hpp), mutual dual-tree walk (dual_tree_walk.hpp) and
// quadrupole-order cell-cell expansions (multipole.hpp), evaluated in gather form:
//   1. per node A: its local expansion from every far partner B (add_far_field);
//   2. top down: each node's expansion re-expanded about its children's centres and added;
//   3. per particle a of leaf A: the expansion of A at x_a, plus every particle of A's near
//      partner leaves (and of A itself) with the softened pair interaction (softened_pair),
//      plus the self potential G m_a phi(0, h_a). The near leaves of A are merged into runs of
//      consecutive particles (sorted by position in tree order), Newtonian-only runs apart,
//      so that the inner loops are long and vectorise.
// With GravitySources::wanted, the nodes holding no wanted particle (targets_) are sources only:
// no walk between two of them, no expansion of theirs, no near runs.
// Every step is OpenMP-parallel over independent nodes or leaves and sums in a fixed order:
// results do not depend on the thread count. The far and near lists are symmetric, and each
// far interaction's total force on A is minus that on B to round-off (docs/gravity.md), so
// linear momentum is conserved to round-off.
#include <string_view>
#include <vector>

#include "sphark/gravity/dual_tree_walk.hpp"
#include "sphark/gravity/gravity_tree.hpp"
#include "sphark/gravity/multipole.hpp"
#include "sphark/gravity/self_gravity.hpp"
#include "sphark/kernels/kernels.hpp"

namespace sphark {

// The instruction set of the tree's near-field loops: "avx2" (x86-64 CPUs with AVX2 and FMA,
// unless the environment says SPHARK_GRAVITY_SIMD=sse2), else "sse2" (or "scalar"). The
// results differ between them in the last bits (other summation order, FMA); on one setting
// they do not depend on the thread count.
std::string_view gravity_simd();
// Switches the AVX2 loops on (if the CPU has them) or off, for tests and comparisons; returns
// whether they are on. Not while a compute() runs.
bool use_gravity_avx2(bool on);

template <class K>
class TreeGravity final : public SelfGravity {
 public:
  // Throws std::invalid_argument unless 0 < theta < 1 and leaf_size >= 1.
  explicit TreeGravity(const GravityOptions& options);
  Real compute(const GravitySources& src, Real* acceleration, Real* potential) override;
  GravitySolver solver() const override { return GravitySolver::Tree; }
  long allocations() const override { return tree_.allocations() + walk_.allocations() + allocations_; }

  const GravityTree& tree() const { return tree_; }
  const DualTreeWalk& walk() const { return walk_; }

 private:
  void mark_targets(const std::uint8_t* wanted);
  bool target(std::size_t node) const { return targets_.empty() || targets_[node]; }
  void far_field_expansions();
  void pass_expansions_down();
  void merge_near_runs();
  void evaluate_leaf(std::uint32_t leaf, const std::uint8_t* wanted, Real* acceleration, Real* potential,
                     std::uint32_t* inside) const;

  GravityOptions opt_;
  GravityTree tree_;
  DualTreeWalk walk_;
  std::vector<std::uint8_t> targets_;  // per node: holds a wanted particle (empty: all wanted)
  std::vector<LocalExpansion> local_;
  // Leaf i's runs: runs_[near.begin(i) ..): newtonian_runs_[i] Newtonian-only runs, then up to
  // all_runs_[i] runs that may hold softened pairs (masked_length_: the most particles in the
  // latter over all leaves, the size of each thread's inside_ list).
  std::vector<ParticleRun> runs_;
  std::vector<std::uint32_t> newtonian_runs_, all_runs_;
  std::uint32_t masked_length_ = 0;
  std::vector<std::vector<std::uint32_t>> inside_;
  long allocations_ = 0;
};

}  // namespace sphark
