#pragma once
// A kd-tree of particles for gravity: each node is split along the longest side of its
// particles' bounding box, near the median: the left child gets ceil(k/2) full leaves of the
// k = ceil(n / leaf_size) the node needs (so leaves hold leaf_size particles, all but one per
// subtree), until a node holds at most leaf_size particles. Nodes are numbered
// in pre-order (a parent before its children; left child = node + 1), so a node's index and its
// children's follow from the particle counts alone: the build is level by level, OpenMP over the
// nodes of a level. Ties along a split axis go by particle index and each leaf lists its particles
// by index, so the tree is a function of the positions alone: not of the thread count, nor of the
// order of the last build, from which a rebuild of as many particles starts (most splits stand).
//
// Per node: mass, centre of mass z, second moment Q = sum m (x - z)(x - z)^T, radius
// r = max |x - z| (exact, over its particles) and reach = support * max h (how far the softening
// of its particles extends). Particles are copied into tree order (structure of arrays, with 1/h).
// A rebuild with the same particle count reuses every buffer.
#include <cstdint>
#include <vector>

#include "sphark/gravity/self_gravity.hpp"

namespace sphark {

struct TreeNode {
  Real com[3] = {0, 0, 0};
  Real mass = 0;
  Real quad[6] = {0, 0, 0, 0, 0, 0};  // sym2: xx xy xz yy yz zz
  Real radius = 0;
  Real reach = 0;
  std::uint32_t begin = 0, end = 0;    // particles [begin, end) in tree order
  std::uint32_t left = 0, right = 0;   // children; 0 (the root's index) for a leaf
  bool leaf() const { return left == 0; }
  std::uint32_t count() const { return end - begin; }
};

// Tree slots [begin, end).
struct ParticleRun {
  std::uint32_t begin, end;
};

class GravityTree {
 public:
  // support: the kernel support in units of h. Throws std::invalid_argument if leaf_size < 1
  // or n >= 2^32.
  void build(const GravitySources& src, Real support, int leaf_size);

  const std::vector<TreeNode>& nodes() const { return nodes_; }
  const std::vector<std::uint32_t>& leaves() const { return leaves_; }  // leaf node indices, ascending
  // Tree slot k holds input particle order()[k]; x(), y(), z(), m(), h() are in tree order.
  const std::vector<std::uint32_t>& order() const { return order_; }
  const Real* x() const { return px_.data(); }
  const Real* y() const { return py_.data(); }
  const Real* z() const { return pz_.data(); }
  const Real* m() const { return pm_.data(); }
  const Real* h() const { return ph_.data(); }
  const Real* h_inv() const { return phinv_.data(); }  // 1/h
  std::size_t particles() const { return order_.size(); }
  long allocations() const { return allocations_; }

 private:
  void split(std::uint32_t node, int leaf_size);
  void compute_moments(std::uint32_t node, Real support);

  struct BuildPoint {
    Real x[3];
    std::uint32_t index;
  };
  struct Plane {  // a node's last split: its left side held the points with x[axis] < at
    Real at = 0;
    std::int8_t axis = -1;  // none
  };
  bool split_at_plane(std::vector<BuildPoint>::iterator first, std::uint32_t half, std::vector<BuildPoint>::iterator last,
                      Plane& plane);
  std::vector<BuildPoint> points_;  // the particles during the build, partitioned in place
  std::vector<TreeNode> nodes_;
  std::vector<std::uint32_t> order_, leaves_, level_, next_level_;
  std::vector<Real> px_, py_, pz_, pm_, ph_, phinv_;
  long allocations_ = 0;
  std::uint32_t built_for_ = 0;  // the particle count of the last build (points_ holds its order)
  int built_leaf_size_ = 0;
  bool warm_ = false;            // this build starts from the last one's order and planes
  std::vector<Plane> plane_;     // per node
};

// Particles of the left child of a node of n > leaf_size particles.
std::uint32_t left_count(std::uint32_t n, std::uint32_t leaf_size);
// Number of nodes of a tree over n particles.
std::uint32_t tree_node_count(std::uint32_t n, std::uint32_t leaf_size);

}  // namespace sphark
