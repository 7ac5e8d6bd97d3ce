// The mutual walk (see sphark/gravity/dual_tree_walk.hpp).
#include "sphark/gravity/dual_tree_walk.hpp"

#include <cmath>
#include <stdexcept>

namespace sphark {

namespace {
// |z_A - z_B|, computed identically for (A, B) and (B, A).
Real centre_distance(const TreeNode& A, const TreeNode& B) {
  const Real dx = A.com[0] - B.com[0], dy = A.com[1] - B.com[1], dz = A.com[2] - B.com[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}
// No particle of one node can be inside the softening reach of a particle of the other.
bool beyond_softening(const TreeNode& A, const TreeNode& B, Real d) {
  return d - A.radius - B.radius >= std::max(A.reach, B.reach);
}
}  // namespace

DualTreeWalk::Step DualTreeWalk::classify(std::uint32_t a, std::uint32_t b) const {
  const std::vector<TreeNode>& nd = *nodes_;
  const TreeNode &A = nd[a], &B = nd[b];
  if (a == b) return A.leaf() ? Step::Near : Step::Self;
  const Real d = centre_distance(A, B);
  if (A.radius + B.radius < theta_ * d && beyond_softening(A, B, d)) return Step::Far;
  if (A.leaf() && B.leaf()) return Step::Near;
  if (B.leaf() || (!A.leaf() && A.radius >= B.radius)) return Step::SplitA;
  return Step::SplitB;
}

// Terminal steps into out; splits are the caller's (depth or breadth first).
void DualTreeWalk::record(Step s, NodePair p, Found& out) const {
  if (s == Step::Far) {
    out.far.push_back(p);
  } else if (s == Step::Near) {
    const std::vector<TreeNode>& nd = *nodes_;
    const bool newtonian = p.a != p.b && beyond_softening(nd[p.a], nd[p.b], centre_distance(nd[p.a], nd[p.b]));
    out.near.push_back({p.a, newtonian ? (p.b | kNewtonian) : p.b});
  }
}

void DualTreeWalk::walk_depth_first(NodePair p, Found& out) const {
  const Step s = classify(p.a, p.b);
  const TreeNode &A = (*nodes_)[p.a], &B = (*nodes_)[p.b];
  switch (s) {
    case Step::Far:
    case Step::Near:
      record(s, p, out);
      return;
    case Step::Self:
      walk_depth_first({A.left, A.left}, out);
      walk_depth_first({A.right, A.right}, out);
      walk_depth_first({A.left, A.right}, out);
      return;
    case Step::SplitA:
      walk_depth_first({A.left, p.b}, out);
      walk_depth_first({A.right, p.b}, out);
      return;
    case Step::SplitB:
      walk_depth_first({p.a, B.left}, out);
      walk_depth_first({p.a, B.right}, out);
      return;
  }
}

// Expands (root, root) breadth first until kJobs pairs wait (or nothing is left to split);
// the waiting pairs stay in queue_ from index head on, moved to the front.
void DualTreeWalk::expand_breadth_first(Found& out) {
  queue_.assign(1, NodePair{0, 0});
  std::size_t head = 0;
  while (head < queue_.size() && queue_.size() - head < static_cast<std::size_t>(kJobs)) {
    const NodePair p = queue_[head++];
    const Step s = classify(p.a, p.b);
    const TreeNode &A = (*nodes_)[p.a], &B = (*nodes_)[p.b];
    if (s == Step::Far || s == Step::Near) {
      record(s, p, out);
    } else if (s == Step::Self) {
      queue_.push_back({A.left, A.left});
      queue_.push_back({A.right, A.right});
      queue_.push_back({A.left, A.right});
    } else if (s == Step::SplitA) {
      queue_.push_back({A.left, p.b});
      queue_.push_back({A.right, p.b});
    } else {
      queue_.push_back({p.a, B.left});
      queue_.push_back({p.a, B.right});
    }
  }
  queue_.erase(queue_.begin(), queue_.begin() + static_cast<std::ptrdiff_t>(head));
}

void DualTreeWalk::walk(const GravityTree& tree, Real theta) {
  if (!(theta > 0 && theta < 1)) throw std::invalid_argument("DualTreeWalk: theta must be in (0, 1)");
  nodes_ = &tree.nodes();
  theta_ = theta;
  std::size_t capacity_before = queue_.capacity() + found_.capacity() + cursor_.capacity();
  for (const Found& f : found_) capacity_before += f.far.capacity() + f.near.capacity();
  for (const PartnerLists* l : {&far_, &near_}) capacity_before += l->start.capacity() + l->partner.capacity();

  if (found_.size() < 1 + static_cast<std::size_t>(kJobs)) found_.resize(1 + kJobs);
  for (Found& f : found_) f.far.clear(), f.near.clear();
  if (!nodes_->empty()) expand_breadth_first(found_[0]);
  const auto jobs = static_cast<std::ptrdiff_t>(queue_.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::ptrdiff_t j = 0; j < jobs; ++j) walk_depth_first(queue_[j], found_[1 + j]);
  assemble(far_, &Found::far, false);
  assemble(near_, &Found::near, true);

  std::size_t capacity_after = queue_.capacity() + found_.capacity() + cursor_.capacity();
  for (const Found& f : found_) capacity_after += f.far.capacity() + f.near.capacity();
  for (const PartnerLists* l : {&far_, &near_}) capacity_after += l->start.capacity() + l->partner.capacity();
  if (capacity_after > capacity_before) ++allocations_;
}

// Per-node partner lists from the unordered pairs, in the order found (prologue, then jobs).
void DualTreeWalk::assemble(PartnerLists& lists, std::vector<NodePair> Found::*which, bool newtonian_flags) {
  const std::size_t nn = nodes_->size();
  const std::uint32_t mask = newtonian_flags ? ~kNewtonian : ~0u;
  lists.start.assign(nn + 1, 0);
  std::size_t pairs = 0;
  for (const Found& f : found_)
    for (const NodePair& p : f.*which) {
      ++lists.start[p.a + 1];
      if (p.a != (p.b & mask)) ++lists.start[(p.b & mask) + 1];
      ++pairs;
    }
  for (std::size_t i = 0; i < nn; ++i) lists.start[i + 1] += lists.start[i];
  lists.partner.resize(lists.start[nn]);
  cursor_.assign(lists.start.begin(), lists.start.end() - 1);
  for (const Found& f : found_)
    for (const NodePair& p : f.*which) {
      const std::uint32_t b = p.b & mask, flag = p.b & ~mask;
      lists.partner[cursor_[p.a]++] = p.b;
      if (p.a != b) lists.partner[cursor_[b]++] = p.a | flag;
    }
  (newtonian_flags ? near_pairs_ : far_pairs_) = pairs;
}

}  // namespace sphark
