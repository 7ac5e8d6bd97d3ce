#pragma once
// Domain decomposition by weighted recursive coordinate bisection (RCB; Berger & Bokhari 1987):
// the ranks [r0, r1) of a tree node split into k = (r1 - r0) / 2 and the rest; the node's
// particles are cut along the longest side of their bounding box at the coordinate c where
// the weight left of c (x < c) is closest to k / (r1 - r0) of the node's weight. Every rank
// ends up with one box-shaped domain of (nearly) equal total weight: the weight is the cost
// per particle (e.g. its neighbour count or measured RHS time), 1 by default.
//
// The cut search is parallel: every rank bins its own particles into a histogram of the current
// bracket (kBins bins) for every node of a tree level at once, one Allreduce per refinement,
// and the bracket shrinks to the bin where the target weight is crossed, until that bin holds
// at most `tolerance` of the node's weight (or one particle, or no width is left). No particle
// moves during partitioning: migration (parallel/migration.hpp) follows.
//
// Periodic axes: positions are wrapped into the PeriodicBox first, and the domains tile the box;
// on open axes the outermost domains extend to +-infinity, so every point has an owner.
#include <cstddef>
#include <optional>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/neighbours/periodic_box.hpp"
#include "sphark/parallel/communicator.hpp"

namespace sphark {

template <int D>
struct DomainBox {
  Vec<D> lo, hi;  // [lo, hi) along every axis; +-infinity on the open faces
};

struct RcbOptions {
  Real tolerance = 1e-3;  // largest weight fraction of a node left undecided in the cut bin
  int max_refinements = 12;
};

struct RcbStats {
  int refinements = 0;       // Allreduce rounds of histogram refinement, all levels
  Real imbalance = 1;        // max over ranks of (domain weight) / (mean weight)
};

template <int D>
class Decomposition {
 public:
  // One domain (rank 0) covering everything.
  explicit Decomposition(std::optional<PeriodicBox<D>> box = std::nullopt);

  int ranks() const { return static_cast<int>(domains_.size()); }
  const std::vector<DomainBox<D>>& domains() const { return domains_; }
  const std::optional<PeriodicBox<D>>& box() const { return box_; }

  // The rank whose domain contains x (wrapped into the box along periodic axes first).
  int owner(const Vec<D>& x) const;
  // Owner of each of n positions (D each) into owners[0 .. n).
  void owners(const Real* x, std::size_t n, int* owners) const;
  // Appends to `out` (ascending, unique) every rank whose domain comes closer than r to x or to
  // one of its periodic images (distance point-box; x itself need not be wrapped). A descent of
  // the tree: O(log P) per query plus the ranks found.
  void ranks_within(const Vec<D>& x, Real r, std::vector<int>& out) const;

  // Tree of cuts, built by partition_rcb. Leaves hold a rank.
  struct Node {
    int axis = -1;   // -1: leaf
    Real cut = 0;    // left child: x[axis] < cut
    int left = -1, right = -1;
    int rank = 0;    // leaf only
  };
  void set_tree(std::vector<Node> nodes);  // computes domains(); validates the tree
  const std::vector<Node>& tree() const { return nodes_; }

 private:
  Vec<D> wrapped(const Vec<D>& x) const { return box_ ? box_->wrap(x) : x; }
  void ranks_near(int node, const Vec<D>& p, Real r, std::vector<int>& out) const;  // the subtree's leaves within r
  std::optional<PeriodicBox<D>> box_;
  std::vector<Node> nodes_;
  std::vector<DomainBox<D>> domains_;
};

// Collective: RCB of every rank's n local particles (x: D values each; weight: n values, or
// nullptr for weight 1) into comm.size() domains. Every rank returns the same Decomposition.
template <int D>
Decomposition<D> partition_rcb(const Communicator& comm, const Real* x, const Real* weight, std::size_t n,
                               const std::optional<PeriodicBox<D>>& box, const RcbOptions& options = {},
                               RcbStats* stats = nullptr);

}  // namespace sphark
