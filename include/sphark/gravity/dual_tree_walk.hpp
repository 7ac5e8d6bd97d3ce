#pragma once
// The mutual (dual-tree) walk of Dehnen (2000, ApJ 536, L39; 2002, JCP 179, 27): starting from
// (root, root), a pair of nodes (A, B) is
//   far     if r_A / theta_A + r_B / theta_B < |z_A - z_B|  and  |z_A - z_B| - r_A - r_B >= max(reach_A, reach_B)
//           (theta_C = theta for GravityOpening::Fixed, theta(M_C) for Mass: self_gravity.hpp)
//           (no particle of A is inside the softening of one of B or vice versa): multipoles;
//   near    if not far and both are leaves: every particle pair directly, softened where needed
//           (flagged Newtonian when no pair of their particles is inside a softening);
//   split   otherwise: the node with the larger radius (a non-leaf) into its two children;
//   (A, A)  leaf: near with itself; otherwise (L, L), (R, R), (L, R).
// Both tests are symmetric in A and B, so the lists are symmetric: B is in A's far (near) list
// iff A is in B's. Each unordered pair is found once; both nodes list it. The near lists are
// sorted by partner index (so that near partner leaves form runs of consecutive particles).
//
// Targets (the field wanted at some particles only: GravitySources::wanted): a pair of nodes
// neither of which holds a wanted particle is not recorded, nor walked below; the pairs kept are
// found, and listed, in the same order as in the full walk.
//
// Parallel: the walk is expanded breadth first into a fixed number of independent node pairs
// (kJobs, not the thread count), each walked depth first into its own buffers; the lists are
// assembled in job order. The lists do not depend on the thread count.
#include <cstdint>
#include <vector>

#include "sphark/gravity/gravity_tree.hpp"

namespace sphark {

// Partners of node i: partner[start[i] .. start[i+1]).
struct PartnerLists {
  std::vector<std::uint32_t> start, partner;
  std::uint32_t begin(std::uint32_t i) const { return start[i]; }
  std::uint32_t end(std::uint32_t i) const { return start[i + 1]; }
};

// The opening angle of a cell of mass M with GravityOpening::Mass: the root of
// theta^5 / (1 - theta)^2 = theta_0^5 / (1 - theta_0)^2 (M_root / M)^(1/3) in [theta_0, 1).
Real mass_opening_angle(Real theta_0, Real mass_ratio_root_over_cell);

class DualTreeWalk {
 public:
  // Partner entries of the near lists carry this bit when every pair of the two leaves is
  // beyond both softenings (the leaf index is entry & ~kNewtonian).
  static constexpr std::uint32_t kNewtonian = 0x80000000u;
  static constexpr int kJobs = 256;

  // Throws std::invalid_argument unless 0 < theta < 1. targets: per node, whether it holds a
  // wanted particle (nullptr: every node).
  void walk(const GravityTree& tree, Real theta, GravityOpening opening = GravityOpening::Fixed,
            const std::vector<std::uint8_t>* targets = nullptr);

  const PartnerLists& far() const { return far_; }    // indexed by node
  const PartnerLists& near() const { return near_; }  // indexed by node (non-empty for leaves)
  std::size_t far_pairs() const { return far_pairs_; }    // unordered far node pairs
  std::size_t near_pairs() const { return near_pairs_; }  // unordered near leaf pairs (self included)
  long allocations() const { return allocations_; }

  // What the walk reads of a node (one cache line).
  struct WalkNode {
    Real com[3], radius, reach, critical;  // critical = radius / theta_C
    std::uint32_t count, left, right;
    bool leaf() const { return left == 0; }
  };

 private:
  struct NodePair {
    std::uint32_t a, b;
  };
  struct Found {  // what one job found
    std::vector<NodePair> far, near;
  };
  enum class Step { Far, Near, Self, SplitA, SplitB };
  Step classify(std::uint32_t a, std::uint32_t b) const;
  void record(Step s, NodePair p, Found& out) const;
  void record_leaf_pairs(std::uint32_t a, std::uint32_t b, Found& out) const;
  void walk_depth_first(NodePair p, Found& out) const;
  void expand_breadth_first(Found& out);
  std::size_t assemble(PartnerLists& lists, std::vector<NodePair> Found::*which, std::uint32_t index_mask,
                       bool sorted);
  std::size_t capacity() const;

  bool wanted(NodePair p) const { return !targets_ || (*targets_)[p.a] || (*targets_)[p.b]; }

  // A node's mass-dependent opening angle and what it was computed from: the same again while
  // the node's mass, the root's and theta_0 are (a walk per event of block steps, the tree
  // rebuilt in between, finds most nodes' masses unchanged).
  struct OpeningMemo {
    Real mass = -1, root_mass = -1, theta_0 = -1, theta_c = 0;
  };
  static Real opening_angle(OpeningMemo& memo, Real theta_0, Real root_mass, Real mass);

  std::vector<WalkNode> nodes_;
  std::vector<OpeningMemo> memo_;  // per node
  const std::vector<std::uint8_t>* targets_ = nullptr;  // during walk()
  std::vector<NodePair> queue_;
  std::vector<Found> found_;  // [0]: found while expanding; [1 + j]: job j
  PartnerLists far_, near_;
  std::vector<std::uint32_t> cursor_;
  std::size_t far_pairs_ = 0, near_pairs_ = 0;
  long allocations_ = 0;
};

}  // namespace sphark
