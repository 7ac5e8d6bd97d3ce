#pragma once
// Variable-radius neighbour lists from a kd-tree with a per-node maximum radius: the
// alternative to the cell grid (sphark/neighbours/neighbour_search.hpp) when the radii span
// decades (a collapsing core: h shrinks 200x). The cell grid sizes every cell by the largest
// radius, so a dense core shares a few cells and each of its particles scans thousands of
// candidates; the tree prunes by the radii actually present in each subtree.
//
// Same interface and the same lists as NeighbourSearch<D> (rows ascending, or ascending by key;
// never i): with radii, j is listed for i when |x_i - x_j| < max(r_i, r_j) (symmetric), found in
// ONE traversal per leaf, shared by the leaf's particles: a node is opened when its bounding box
// lies within max(r_leaf, r_node) of the leaf's box, r_leaf and r_node the largest radii inside
// each (so both the pairs i gathers and the pairs that reach i are found). Periodic axes: minimum image (box >= 2 radius).
//
// Tree: median splits along the widest axis of each node's bounding box down to leaves of at
// most kLeafSize particles; leaf particles are stored contiguously (tree order, a spatial order,
// returned by cell_order() like the grid's). Build and queries are OpenMP-parallel; the lists do
// not depend on the thread count; a rebuild that needs no larger buffers allocates nothing.
// Which of the two to use: sphark/neighbours/neighbour_method.hpp.
#include <cstdint>
#include <optional>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/neighbours/neighbour_search.hpp"
#include "sphark/neighbours/periodic_box.hpp"

namespace sphark {

template <int D>
class KdTreeNeighbourSearch {
 public:
  static constexpr std::uint32_t kLeafSize = 12;

  explicit KdTreeNeighbourSearch(std::optional<PeriodicBox<D>> box = std::nullopt) : box_(std::move(box)) {}

  // As NeighbourSearch<D>::build: every pair closer than `radius`, or with radii (each capped at
  // radius) every pair closer than max(radii[i], radii[j]); rows sorted by index or by key.
  void build(const Real* x, std::size_t n, Real radius, const std::uint32_t* key = nullptr,
             const Real* radii = nullptr);
  // New index i is old index order[i]; lists, stored points and the tree follow, rows keep order.
  void renumber(const std::vector<std::uint32_t>& order);
  // As NeighbourSearch::keep; the tree is dropped (query() needs a build again).
  void keep(const std::vector<std::uint32_t>& kept);
  const std::vector<RowSpan>& row_spans() const { return spans_; }  // after renumber(): NeighbourSearch's
  // The built particles in tree order (leaf by leaf).
  const std::vector<std::uint32_t>& cell_order() const { return index_; }
  // Built particles within `radius` of p, ascending.
  void query(const Vec<D>& p, Real radius, std::vector<std::uint32_t>& out) const;

  const NeighbourList& list() const { return list_; }
  Real radius() const { return radius_; }
  const std::optional<PeriodicBox<D>>& box() const { return box_; }
  Vec<D> separation(const Real* x, std::size_t i, std::size_t j) const {
    Vec<D> d = Eigen::Map<const Vec<D>>(x + D * i) - Eigen::Map<const Vec<D>>(x + D * j);
    return box_ ? box_->minimum_image(d) : d;
  }
  Real max_displacement_since_build(const Real* x) const;
  void displacements_since_build(const Real* x, std::vector<Real>& out) const;  // per particle
  long allocations() const { return allocations_; }
  std::size_t nodes() const { return node_.size(); }

 private:
  struct Node {
    Vec<D> lo, hi;            // bounding box of its particles
    Real reach2 = 0;          // largest squared radius of its particles
    std::uint32_t begin = 0, end = 0;  // tree-order slots
    std::int32_t left = -1, right = -1;  // children (-1: leaf)
  };
  void build_tree(std::size_t n);
  void split(std::int32_t node);
  void list_rows(const std::uint32_t* key);
  Real gap(Real alo, Real ahi, Real blo, Real bhi, int k) const;
  Real box_distance2(const Node& nd, const Real* p) const;
  Real box_distance2(const Node& a, const Node& b) const;
  void collect(const Real* p, Real r2, std::vector<std::uint32_t>& out, std::vector<std::int32_t>& stack) const;
  void candidate_leaves(const Node& a, std::vector<std::int32_t>& out, std::vector<std::int32_t>& stack) const;
  std::size_t capacity() const;

  std::optional<PeriodicBox<D>> box_;
  Real radius_ = 0;
  std::size_t n_ = 0;
  NeighbourList list_;
  std::vector<Node> node_;
  std::vector<std::int32_t> leaves_;     // leaf nodes in slot order
  std::vector<std::size_t> row_start_;   // per slot: where its row starts in its thread's buffer
  Vec<D> period_ = Vec<D>::Zero();       // box length along periodic axes, 0 on open ones
  std::vector<std::uint32_t> index_;     // tree slot -> particle
  std::vector<Real> ppts_, pr2_;         // per particle: D wrapped coordinates, squared radius
  std::vector<Real> pts_, r2_;           // the same per tree slot (leaves contiguous)
  std::vector<std::vector<std::uint32_t>> thread_rows_;
  std::vector<std::vector<std::int32_t>> thread_stack_;
  std::vector<std::uint32_t> scratch_u32_, swap_rows_;  // renumber() scratch
  std::vector<RowSpan> spans_;                           // row_spans()
  std::vector<std::size_t> scratch_offsets_;
  std::vector<Real> swap_pts_, swap_r2_;
  long allocations_ = 0;
};

}  // namespace sphark
